// D3 — Touch probe positioning for palletizer application
// Source: D:710-788 (MCO 305 Design Guide)
// OCR repairs:
// - D:714-723 header lines lost their "//" and were split ("1 Go to position" above "Inputs:"); rebuilt as "//" comment lines
// - D:725 "ON ERROR GOSUB ...ON INT 2 GOSUB tp_handler// ..." two statements on one line; split
// - D:727 "tp active = 0" -> "tp_active = 0" (space for underscore)
// - D:752 "flaq = 0" -> "flag = 0"
// - D:754, 780 "FNDIF" -> "ENDIF"
// - D:757 "SUBPROG tp handler" -> "SUBPROG tp_handler" (space for underscore)
// - D:768, 786 "RFTURN" -> "RETURN"
// - D:773-775 "IILE err DO// ...IF IN 8 THEN// ...ERRCLR// Close error" merged line plus a second "WHILE err DO": kept one "WHILE err DO", restored "IF IN 8 THEN" from the merged line, dropped the duplicate ERRCLR
// Not repaired (the manual's own slip, see the corrected copy): "IF (IN 1 == 1) AND (flag == 0) THEN … flag = 1
//   ELSE MOTOR STOP … flag = 0" takes the ELSE branch on the next pass while input 1 stays high (flag is 1 then)
//   and re-arms the IF for the pass after: CSTART and MOTOR STOP alternate, the axis hardly moves and the touch
//   probe never comes.

/******* Touch probe positioning sample program for palletizer application example ********/
// Inputs:  1 Go to position
//          2 Touch probe
//          8 Clear Error
// Outputs: 1 In position
//          8 Error
ON ERROR GOSUB errhandle // In case of error go to error handler routine, this must always be included
ON INT 2 GOSUB tp_handler // Call touch probe handler on positive edge of input 2.
flag = 0
tp_active = 0
VEL 80
        // Sets positioning velocity related to parameter 32-80 Maximum velocity.
ACC 100
        // Sets positioning acceleration related to parameter 32-81 Shortest ramp.
DEC 100
         // Sets positioning deceleration related to parameter 32-81 Shortest ramp.
/***************************** Define application parameters ********************************/
LINKGPAR 1900 "Touch probe distance" 0 1073741823 0
MAIN:
IF (IN 1 == 1) AND (flag == 0) THEN
                             // Start movement once (ensured by flag) when input 1 is high.
              // Reset "In position" output.
  OUT 1 0
  CVEL 80
                 // Set constant velocity.
  CSTART
                 // Start with constant velocity.
                // Reset "tp_active" to enable new touch probe positioning.
  tp_active = 0
                 // Set "flag" to ensure that distance is only traveled once.
  flag = 1
ELSE
  MOTOR STOP
                 // Stop if input is low.
  flag = 0
                  // Reset "flag" to enable new start.
ENDIF
GOTO MAIN
SUBMAINPROG
SUBPROG tp_handler
  IF (tp_active == 0) THEN
    POSR (GET 1900) // Go to touch probe target position
    WAITAX
                  // Halt program execution until position is reached (This is necessary as
                  // NOWAIT ON is automatically set in a subroutine called by interrupt).
    OUT 1 1
                  // Set "In position" output.
    tp_active = 1
                  // Set "tp_active" to ensure that touch probe positioning is done only once
  ENDIF
RETURN
 SUBPROG errhandle
                 // Set error flag to remain in error handler until error is reset.
  err = 1
  OUT 8 1
                 // Set error output.
  WHILE err DO // Remain in error handler until the reset is received.
    IF IN 8 THEN // Reset error when Input 8 is high.
                 // Clear error.
       ERRCLR
      err=0
                  // Reset error flag.
    ENDIF
  ENDWHILE
  OUT 8 0
                 // Reset error output.
 flag = 0
                  // Reset "flag" to enable new positioning.
RETURN
ENDPROG
