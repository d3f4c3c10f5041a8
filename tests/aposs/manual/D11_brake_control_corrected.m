// D11 (corrected copy) — Relative positioning with mechanical brake control
// Source: D:1783-1856 (MCO 305 Design Guide)
// OCR repairs:
// - D:1785 unterminated "/****" banner closed with "/"; the header lines D:1786-1790 lost their "//" (they sat inside the open banner) and get "//" back
// - D:1785-1856 lines split into tab-separated columns ("Se	ets positi	oning", "erro	or go to e	rror", "Ensur	e"); comment text rejoined
// - D:1801 'LINKGPAR 1900 "Be	ox height	" ...' -> LINKGPAR 1900 "Box height" 0 1073741823 0
// - D:1802 '"Bi	rake close	e delay"' -> "Brake close delay"; D:1803 '"Bi	rake oper	n delay"' -> "Brake open delay"
// - D:1808 "IF (IN 1 == 1) AND	) (flag ==	• 0) THEN" -> "IF (IN 1 == 1) AND (flag == 0) THEN" (stray ")" and bullet dropped)
// - D:1810 "GOSUB disengag	e" -> "GOSUB disengage"
// - D:1812 "POSR (GET 1900	)" -> "POSR (GET 1900)"
// - D:1815 LaTeX debris "ELSEIF (IN $1 == 0$ )	AND (fla	g == 1) THEN" -> "ELSEIF (IN 1 == 0) AND (flag == 1) THEN"
// - D:1821, 1840, 1854 unterminated "/****" banners closed with "/"; D:1833 "Di	isengage" rejoined
// Not repaired (the manual's own slip, see the corrected copy): the brake relay is addressed as "OUT 11"; the
//   outputs are 1-8 (MCO), 27 (FC) and the relays 21/22 (C:3097-3106): the controller reports error 171.
// Correction (the manual's own slip, not OCR): "OUT 11" -> "OUT 21", relay 1 of the FC 300 (C:3097-3106)

/************************************************************/
// Inputs:	1	Go to position
//	8	Clear Error
// Outputs:	1	In position
//	8	Error
//	11	Relay output for mechanical brake
/******************** Interrupts ***********************************/
ON ERROR GOSUB	errhandle
// In case of error go to error handler routine, this must always be included
/******************* Define flags **********************************/
flag = 0
/****************** Basic settings **************************/
VEL 80 // Sets positioning velocity related to par. 32-80 Maximum velocity.
ACC 100 // Sets positioning acceleration related to par. 32-81 Shortest ramp.
DEC 100 // Sets positioning deceleration related to par. 32-81 Shortest ramp.
/*************** Define application parameters **********************/
LINKGPAR 1900 "Box height" 0 1073741823 0
LINKGPAR 1901 "Brake close delay" 0 1000 0
LINKGPAR 1902 "Brake open delay" 0 1000 0
/*************** Initialize drive to safe state **********************/
GOSUB engage	// Ensure that mechanical brake is closed after power up.
/*********************** main loop *******************************/
MAIN:
IF (IN 1 == 1) AND (flag == 0) THEN
// Go to position once (ensured by flag) when input 1 is high.
GOSUB disengage	// Open mechanical brake before start.
OUT 1 0		// Reset "In position" output.
POSR (GET 1900)	// Go to position.
OUT 1 1		// Set "In position" output.
flag = 1	// Set "flag" to ensure that distance is only traveled once.
ELSEIF (IN 1 == 0) AND (flag == 1) THEN // Stop once when input 1 is low
MOTOR STOP		// Stop if input is low.
flag = 0		// Reset "flag" to enable new positioning.
GOSUB engage		// Close mechanical brake after stop.
ENDIF
GOTO MAIN
/***************** Sub programs start ***********************************/
SUBMAINPROG
/************** Engage mechanical brake *******************************/
SUBPROG engage
OUT 21 0	// Close mechanical brake.
DELAY (GET 1901)
// Wait to ensure that brake is engaged before releasing the motor.
MOTOR OFF	// Stop position control and coast the motor.
RETURN
/************** Disengage mechanical brake *************************/
SUBPROG disengage
MOTOR ON	// Enable drive and start position control.
DELAY (GET 1902)
// Wait to ensure that motor is magnetized before opening the brake.
OUT 21 1	// Open mechanical brake.
RETURN
/****************** Error handler ************************************/
SUBPROG errhandle
OUT 21 0 // Close mechanical brake in case of error.
err = 1 // Set error flag to remain in error handler until error is reset.
OUT 8 1 // Set error output.
WHILE err DO // Remain in error handler until the reset is received.
IF IN 8 THEN	// Reset error when Input 8 is high.
ERRCLR	// Clear error.
err=0	// Reset error flag.
ENDIF
ENDWHILE
OUT 8 0	// Reset error output.
flag = 0	// Reset "flag" to enable new positioning.
RETURN
/******************************************************/
ENDPROG
/******************** End of program ******************************/
