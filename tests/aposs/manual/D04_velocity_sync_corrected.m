// D4 (corrected copy) — Velocity synchronizing (suit case conveyor belt) with manual jog mode
// Source: D:850-942 (MCO 305 Design Guide)
// OCR repairs:
// - D:852-893 three text columns interleaved and the middle column partly lost; lines rebuilt by joining the column pieces (col 1 + col 2 + col 3) in order
// - D:852-853, 862, 867, 870, 876-878 banner comments split across columns / unterminated; rejoined and closed with "/"
// - D:863 "ON ERROR GC /****** rhandle // ... Basic settings ****" -> "ON ERROR GOSUB errhandle // ..." plus a separate "Basic settings" banner
// - D:868 "LINKGPAR 190 | 00 "Man | ual velocity" 0 100 0" -> LINKGPAR 1900 "Manual velocity" 0 100 0
// - D:869 only the last column 'ocity step" 0 10 0' survives -> LINKGPAR 1901 "Velocity step" 0 10 0 (parameter number from GET 1901 at D:898; the 18 lost characters fit 'LINKGPAR 1901 "Vel')
// - D:871 LaTeX debris "$sync_flag = 0$" -> "sync_flag = 0"
// - D:873-879 stray "_" line and repeated "err = 0"/"man_vel = 0" copies dropped (each kept once)
// - D:892 main loop rebuilt from the column pieces: "MAIN: IF (IN 1 == 1 | ) AND ( | sync_flag == 0) THEN", "SYNCV", "sync_flag = | = 1", "OUT 1 1", "ELSE", "MOTOR STC | OP", "sync_flag = | = 0", "OUT 1 0", "ENDIF", "IF (IN 2 == 1 | ) AND ( | sync_flag == 0) THEN", "OUT 2 1", "man_vel = | GET 19 | 00", "CVEL man_ | _vel", "CSTART"
// - D:893-897 lines lost at the page break; reconstructed (DOUBTFUL): "WHILE (IN 2 == 1) DO" (only the piece "2 == 1" survives), "CVEL man_vel" (the loop must hand the changed man_vel to the drive; no other CVEL survives), "IF (IN 3 == 1) AND (done == 0) THEN" (mirrors the surviving ELSEIF at D:900)
// - D:940 "RFTURN" -> "RETURN"
// Not repaired (the manual's own slip, see the corrected copy): "IF (IN 1 == 1) AND (sync_flag == 0) THEN … sync_flag = 1
//   ELSE MOTOR STOP … sync_flag = 0" takes the ELSE branch on the next pass while input 1 stays high (sync_flag is 1 then)
//   and re-arms the IF for the pass after: SYNCV and MOTOR STOP alternate and the slave hardly moves.
// Correction (the manual's own slip, not OCR): "ELSE" -> "ELSEIF (IN 1 == 0) AND (sync_flag == 1) THEN", the form of D11
//   (D:1815, "Stop once when input 1 is low")

/*************************** Velocity synchronizing sample program ***********************/
// Inputs:  1 Start/stop synchronization
//          2 Start manual mode
//          3 Increase manual velocity
//          4 Decrease manual velocity
//          8 Clear Error
// Outputs: 1 In synchronizing mode
//          2 In manual mode
//          8 Error
/**************************************** Interrupts ************************************/
ON ERROR GOSUB errhandle // In case of error go to error handler routine, this must always be included
/********* Basic settings ************************************/
VEL 100 // Sets maximum slave velocity related to parameter 32-80 Maximum velocity
ACC 100 // Sets slave acceleration related to parameter 32-81 Shortest ramp
DEC 100 // Sets slave deceleration related to parameter 32-81 Shortest ramp
/****************************** Define application parameters *****************************/
LINKGPAR 1900 "Manual velocity" 0 100 0
LINKGPAR 1901 "Velocity step" 0 10 0
/******************************* Define flags and variables ***********************************/
sync_flag = 0
done = 0
err = 0
man_vel = 0
/******************************* main loop **********************************/
MAIN:
IF (IN 1 == 1) AND (sync_flag == 0) THEN // Start synchronizing once when input 1 is high
  SYNCV // Start velocity synchronizing mode
  sync_flag = 1 // Set sync_flag to ensure synchronizing is only started once.
  OUT 1 1 // Set "In synchronizing mode" output
ELSEIF (IN 1 == 0) AND (sync_flag == 1) THEN
  MOTOR STOP // Stop if input 1 is low.
  sync_flag = 0 // Reset sync_flag after stop
  OUT 1 0 // Reset "In synchronizing mode" output
ENDIF
IF (IN 2 == 1) AND (sync_flag == 0) THEN // Start manual mode if input 2 high and not synchronizing
  OUT 2 1 // Set "In manual mode" output
  man_vel = GET 1900 // Set manual velocity to parameter 1900
  CVEL man_vel
  CSTART // Start constant velocity mode
  WHILE (IN 2 == 1) DO
    CVEL man_vel
    IF (IN 3 == 1) AND (done == 0) THEN
      man_vel = man_vel + GET 1901
      done = 1
    ELSEIF (IN 4 == 1) AND (done == 0) THEN
                                    // Decrease manual velocity by 1 step when input 3 is set
      man_vel = man_vel - GET 1901
      done = 1
    ELSE
      done = 0
    ENDIF
 ENDWHILE
 CSTOP
                  // Stop when leaving manual mode
 OUT 2 0
                  // Reset "In manual mode" output when leaving manual mode
ENDIF
GOTO MAIN
SUBMAINPROG
SUBPROG errhandle
 err = 1
                  // Set error flag to remain in error handler until error is reset.
 OUT 8 1
                  // Set error output
 OUT 1 0
                 // Reset "In synchronizing mode" output in case of error
 OUT 2 0
                 // Reset "In manual mode" output in case of error
 WHILE err DO
                 // Remain in error handler until the reset is received
    IF (IN 8) AND NOT (IN 1) AND NOT (IN 2) THEN
                 // Reset error when Input 8 is high and input 1+2 is low.
      ERRCLR
                  // Clear error
      err=0
                  // Reset error flag
    ENDIF
 ENDWHILE
 OUT 8 0
                  // Reset error output
                  // Reset sync_flag after an error
 sync_flag = 0
 done = 0
                  // Reset done flag after an error
RETURN
ENDPROG
