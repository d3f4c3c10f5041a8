// C15 (syntax example 2) — ON PARAM on the CANopen DS402 "Mode of operation" object, dispatch with SWITCH
// Source: C:2824-2851 (MCO 305 Command Reference)
// OCR repairs:
// - C:2826-2830 page footer/header lines ("MG.34.R1.02 – VLT", "®", "MCO 305 Command Reference", ...) inside the listing removed
// - C:2824 heading "Syntax Example 2" (manual layout, not code) dropped
// Not repaired (the manual's own slip, see the corrected copy): the handler prints the new mode from 0x6060
//   (sysvar[0x01606000]) but switches on sysvar[0x01604000], the DS402 controlword 0x6040 (C:2833-2835).

// Trigger an interrupt each time the CANopen DS402 "Mode of operation" changes
ON PARAM 0x01606000 GOSUB OpModeUpdate
SUBMAINPROG
SUBPROG OpModeUpdate
PRINT "New DS402 Operation Mode: ",sysvar[0x01606000]
// Execute an action depending on the new operating mode
SWITCH (sysvar[0x01604000])
CASE 1:
PRINT "Profile position mode"
// Action ....
BREAK
CASE 2:
PRINT "Velocity mode"
// Action ....
BREAK
// CASE ....
// ...
// BREAK
DEFAULT:
PRINT "Operation Mode is not supported"
ENDSWITCH
RETURN
ENDPROG
