// F_D10 — CAM box: drier on for 300 ms each time curve-master position 2500 is passed
// Source: D:1764-1771 (MCO 305 Design Guide)
// Kind: fragment made complete (no setup of the curve in the manual). Scaffolding added: the endless main loop
//   "mainloop: / GOTO mainloop" so that the interrupt stays active.
// Note: "ON MCPOS 2500" is written without a sign (spec §10 item 23: default "+").
// OCR repairs:
// - D:1764 "ON MCPOS 2500 GOSI // Call up a subp	JB drier program when ..." (columns interleaved) ->
//   "ON MCPOS 2500 GOSUB drier // Call up a subprogram when ..."

ON MCPOS 2500 GOSUB drier // Call up a subprogram when the master position 2500 is passed in positive direction
mainloop:
GOTO mainloop
SUBMAINPROG
SUBPROG drier
OUT 1 1	// Turn on drier
DELAY 300	// Dry for 300 ms
OUT 1 0	// Turn off drier
RETURN
ENDPROG
