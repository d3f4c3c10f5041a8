// C10 — MIPOS: latch the master marker position in an ON INT 5 handler
// Source: C:2291-2310 (MCO 305 Command Reference)
// OCR repairs: none
// (C:2291 heading "Sample" in front of the first comment is manual layout and was dropped.)

// Definition Interrupt-Handler
ON INT 5 GOSUB master_int
// Definition of IPOS-Latching on positive edge at input 5
SET SYNCMTYPM 2
CVEL 10 // Start moving
CSTART // Endless-Loop
mainloop: // ...
GOTO mainloop
SUBMAINPROG
SUBPROG master_int
int_mpos = MAPOS
// Latching MAPOS for testing, how exact it would be …
DELAY 2 // Wait 2 ms, to be sure, that MIPOS is correct updated
triggered_mpos = MIPOS // Latching IPOS for a later handling etc.
// ...
// ...
PRINT "Interrupt master position: ",int_mpos
PRINT "Triggered master position: ",triggered_mpos
RETURN
ENDPROG
