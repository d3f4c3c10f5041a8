// C15 (syntax example 3) — LINKPDO a received PDO to user parameter 1 and react with ON PARAM
// Source: C:2852-2860 (MCO 305 Command Reference)
// OCR repairs: none
// (C:2852 heading "Syntax Example 3" in front of the first comment is manual layout and was dropped.)

// Link the RxPdo with the user parameter 1 ...
LINKPDO 1 32 0x01220101 0
// and configure an interrupt each time it changes
ON PARAM 0x01220101 GOSUB UserParamUpdate
SUBMAINPROG
SUBPROG UserParamUpdate
PRINT "User Parameter 1 updated: ",sysvar[0x01220101]
RETURN
ENDPROG
