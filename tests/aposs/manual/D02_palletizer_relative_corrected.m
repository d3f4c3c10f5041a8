// D2 (corrected copy) — Relative positioning for palletizer application
// Source: D:637-681 (MCO 305 Design Guide)
// OCR repairs:
// - D:639-681 the right half of every line is cut off (page column lost); truncated comments kept as they are
// - D:639, 644, 647, 649, 653, 655, 667, 669 unterminated "/****" banner comments; closed with "/" (D:639, cut mid-title: with "... */")
// - D:645 "ON ERROR GOSUB errha" completed to "errhandle" (the SUBPROG name at D:670)
// - D:654 "LINKGPAR 1900 "Box hi" completed to "Box height" 0 1073741823 0 (same parameter in D:1801)
// - D:657 "IF (IN 1 == 1) AND (fla" completed to "AND (flag == 0) THEN" (flag logic as in D3/D11)
// - D:671-679 body of SUBPROG errhandle lost, only its comments survive; statements reconstructed from those comments (same handler as D1/D11): err = 1, OUT 8 1, WHILE err DO, IF IN 8 THEN, ERRCLR, err=0, ENDIF, ENDWHILE, OUT 8 0, flag = 0, RETURN
// - D:680-681 "***** ... ** End of program ****" lines: ENDPROG lost; reconstructed as banner + ENDPROG + end-of-program banner
// Not repaired (the manual's own slip, see the corrected copy): "IF (IN 1 == 1) AND (flag == 0) THEN … flag = 1
//   ELSE MOTOR STOP … flag = 0" takes the ELSE branch on the next pass while input 1 stays high (flag is 1 then)
//   and re-arms the IF for the pass after: the box height is travelled again and again while input 1 is held,
//   not once per press.
// Correction (the manual's own slip, not OCR): "ELSE" -> "ELSEIF (IN 1 == 0) AND (flag == 1) THEN", the form of D11
//   (D:1815, "Stop once when input 1 is low")

/******** Relative p... */
// Inputs:
//
// Outputs:
//
/***************/
ON ERROR GOSUB errhandle
// In case of error go to
/***************/
flag = 0
/**************/
VEL 80 // Sets pos
ACC 100 // Sets pos
DEC 100 // Sets pos
/***************/
LINKGPAR 1900 "Box height" 0 1073741823 0
/***************/
MAIN:
IF (IN 1 == 1) AND (flag == 0) THEN
OUT 1 0
POSR (GET 1900)
OUT 1 1
flag = 1
ELSEIF (IN 1 == 0) AND (flag == 1) THEN
MOTOR STOP // Stop
flag = 0
ENDIF
GOTO MAIN
/*************/
SUBMAINPROG
/*************/
SUBPROG errhandle
err = 1 // Set error flag to remain in error handler until error is reset.
OUT 8 1 // Set error output.
WHILE err DO // Remain in error handler until the reset is received.
IF IN 8 THEN // Reset error when Input 8 is high.
ERRCLR // Clear error.
err=0 // Reset error flag.
ENDIF
ENDWHILE
OUT 8 0 // Reset error output.
flag = 0 // Reset "flag" to enable new positioning.
RETURN
/***************************************/
ENDPROG
/** End of program ************************************/
