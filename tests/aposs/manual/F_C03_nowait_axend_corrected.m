// F_C03 (corrected copy) — NOWAIT ON with AXEND polling; change velocity during a move; test the controller-off bit
// Source: C:334-348 (MCO 305 Command Reference)
// Kind: two syntax examples joined into one program; nothing else added.
// OCR repairs:
// - C:334, 344 headings "Syntax Example" (manual layout, not code) dropped
// Correction (the manual's own slips, not OCR): C:338 "IF IN1 THEN" -> "IF IN 1 THEN"; C:341 "WAIT IN1 OFF" ->
//   "WAITI 1 OFF" (WAITI n s waits for an input state)

NOWAIT ON // do not wait until position is reached
POSA 100000
WHILE (AXEND&2) DO
// as long as the positioning process is active, repeat loop
IF IN 1 THEN // if input 01 is set
VEL 100 // increase velocity
POSA 100000
WAITI 1 OFF // wait until input (key) is off
ENDIF
ENDWHILE // position reached
IF (AXEND&64) THEN
OUT 1 1 // set output 01, when axis controller is switched off
ELSE
OUT 1 0
ENDIF
