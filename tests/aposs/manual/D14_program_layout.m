// D14 — Program layout demonstration (arrays, interrupts, initialisation, main loop, subprogram area)
// Source: D:6033-6085 (MCO 305 Design Guide)
// Kind: complete, assembled from the layout pieces of D:6033-6044 (definitions + initialisation), D:6061-6067 (main loop)
//   and D:6071-6085 (subprogram area); the generic templates "main: / GOTO main" (D:6050-6052) and
//   "SUBMAINPROG SUBPROG name RETURN ENDPROG" (D:6056-6058) are placeholders and are not repeated here.
// OCR repairs:
// - D:6041 LaTeX debris "$sync_flag = 0$" -> "sync_flag = 0"
// - D:6066-6067 lost "ENDIF" before "GOTO main" restored (spec §10 item 34)
// - D:6071 "SUBMAINPROG SUBPROG syncprog" on one line; split into two lines (one statement per line)
// - D:6035-6037, 6066 subprograms stopprog, calc, break, speedprog are called but their bodies are not in the manual: minimal SUBPROG ... RETURN added
// Note: D:6037 "ON TIME 10000 GOSUB break" names a subprogram with the reserved word BREAK (MCO >= 5.00); after
//   GOSUB and SUBPROG only a subprogram can stand, so it compiles with a warning (decision L14, CR 2489 does the same)

DIM send[12], receive[12]	// Array
ON ERROR GOSUB errhandle	// Interrupts
ON INT -1 GOSUB stopprog
ON PERIOD 500 GOSUB calc
ON TIME 10000 GOSUB break

SET POSERR 10000000	// Parameters
offset = 0	// Flags/variables
sync_flag = 0
VEL 100	// System parameters
ACC 100
DEC 100

main:
IF (IN 3 == 1) THEN
// Go into synchronizing mode, if input 3 = 1
GOSUB syncprog
ELSE // If input 3 not 1, run in speed mode
GOSUB speedprog
ENDIF
GOTO main

SUBMAINPROG
SUBPROG syncprog
    IF (sync_flag == 0) THEN
    // synchronize, if not already synchronized
SYNCP
      sync_flag = 1
    ENDIF
    RETURN
    SUBPROG errhandle
    WAITI 18 on
    // waiting for digital input 18,
    // clear the error
      sync_flag = 0
    ERRCLR
    RETURN
SUBPROG speedprog
// body lost in the manual's OCR
RETURN
SUBPROG stopprog
// body lost in the manual's OCR
RETURN
SUBPROG calc
// body lost in the manual's OCR
RETURN
SUBPROG break
// body lost in the manual's OCR
RETURN
ENDPROG
