// D5 (corrected copy) — Position synchronizing (packaging with fixed product distances) with homing and offset trimming
// Source: D:1007-1137 (MCO 305 Design Guide)
// OCR repairs:
// - D:1009, 1019, 1022, 1029, 1034, 1135 unterminated "/****" banner comments; closed with "/"
// - D:1041 LaTeX debris "IN $1 == 1$" -> "IN 1 == 1" (also "$1 = 1$" in the comment -> "1 = 1")
// - D:1072 "ENDIE" -> "ENDIF"
// - D:1076 "SUBPROG increase offset" -> "SUBPROG increase_offset" (space for underscore; called at D:1051)
// - D:1083 "FLSE" -> "ELSE"
// - D:1093 "RFTURN" -> "RETURN"
// - D:1119 LaTeX debris "Next_step = $1$" -> "Next_step = 1"
// - D:1121-1137 lines split into tab-separated columns ("E	rror handler", "Set error fla	ag", "hon	ne_done"); columns rejoined
// - D:1133 LaTeX debris "$home_done = 0$" -> "home_done = 0"
// Correction (the manual's own slip, not OCR): D:1069 "GET 132 == 0" -> "GET 1901 == 0" (1901 = "Offset type",
//   0 = absolute offset, as the subprograms read it)

/*************************************/
// Inputs: 1 Start/stop synchronization
// 2 Start homing
// 3 Home switch
// 4 Increase offset
// 5 Decrease offset
// 8 Clear Error
// Outputs: 1 Within synchronizing accuracy, set accuracy window in par. 33-13
// 2 Homing done
// 8 Error
/*************************************/
ON ERROR GOSUB errhandle
// In case of error go to error handler routine, this must always be included
/*************************************/
VEL 100 // Sets maximum slave velocity related to par. 32-80 Maximum velocity
ACC 100 // Sets slave acceleration related to par. 32-81 Shortest ramp
DEC 100 // Sets slave deceleration related to par. 32-81 Shortest ramp
/************************ Define application parameters ****************************/
LINKGPAR 1900 "Offset step" 0 10000 0
LINKGPAR 1901 "Offset type" 0 1 0
/*************************************/
SET I_FUNCTION_3 1 // Define input 3 as Home switch input
next_step = 0
home_done = 0
new_offset = 0
/*************************************/
MAIN:
IF (IN 2 == 1) THEN // Start homing if input 2 high
HOME // Go to Home and set position to 0
home_done = 1 // Set home_done flag
OUT 2 1 // Set home done output
ENDIF
IF (IN 1 == 1) AND (home_done == 1) THEN // Start synchronizing when input 1 = 1 and homing done.
SYNCP // Start position synchronizing mode
old_offset = GET SYNCPOSOFFS
  WHILE (IN 1 == 1) DO
                                     // Stay in synchronizing mode while input 1 = 1
    IF (IN 4 == 1) THEN
       GOSUB increase_offset
    ELSEIF (IN 5 == 1) THEN
       GOSUB decrease_offset
    ENDIF
    IF (SYNCSTAT & 4) THEN
      OUT 1 1
    ELSE
       OUT 1 0
    ENDIF
  ENDWHILE
  MOTOR STOP
                        // Stop if input 1 is low.
 home_done = 0
                        // Reset home_done flag after stop
 OUT 1 0
  OUT 2 0
                        // Reset home done output after stop
                                               // Save absolute offset if changed
 IF (new_offset != old_offset) AND (GET 1901 == 0) THEN
    SAVE AXPARS
                        // NOTE: Saving more that 10000 times can damage flash PROM
 ENDIF
ENDIF
GOTO MAIN
SUBMAINPROG
SUBPROG increase_offset
 IF (Next_step) THEN
                             // Check if next offset step is enabled
    IF (GET 1901 == 0) THEN // Absolute offset
       new_offset = old_offset + GET 1900 // Read existing offset and add step value
       SET SYNCPOSOFFS new_offset
                                     // Set new position offset
    ELSE
                                    // Relative offset
       MOVESYNCORIGIN GET 1900
                                    // Execute relative offset with offset step
    ENDIF
 ENDIF
                             // Disable next offset step
  Next_step=0
 ON TIME 500 GOSUB Enb_Step
                             // Enable next offset step after 500 ms
RETURN
SUBPROG decrease_offset
                             // Check if next offset step is enabled
 IF (Next_step) THEN
    IF (GET 1901 == 0) THEN
                             // Absolute offset
       new_offset = GET SYNCPOSOFFS - GET 1900
       // Read existing offset and subtract step value
       SET SYNCPOSOFFS new_offset
                                 // Set new position offset
    ELSE
                                    // Relative offset
       MOVESYNCORIGIN (- GET 1900)
                                    // Execute relative offset with - offset step
    ENDIF
  ENDIF
  Next_step=0
                              // Disable next offset step
  ON TIME 500 GOSUB Enb_Step
                            // Enable next offset step after 500 ms
RETURN
SUBPROG Enb_step
Next_step = 1	// Enable next offset step
RETURN
/*********************** Error handler *********************************/
SUBPROG errhandle
err = 1	// Set error flag to remain in error handler until error is reset.
OUT 8 1	// Set error output
OUT 2 0	// Reset home done output in case of error
WHILE err DO		// Remain in error handler until the reset is received
IF (IN 8) AND NOT (IN 1) THEN	// Reset error when Input 8 is high and input 1 low.
ERRCLR		// Clear error
err=0		// Reset error flag
ENDIF
ENDWHILE
OUT 8 0	// Reset error output
home_done = 0	// Reset home_done flag after an error
RETURN
/************************************************************/
ENDPROG
/*********************** End of program *******************************/
