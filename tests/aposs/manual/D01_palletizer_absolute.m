// D1 — Absolute positioning for palletizer application
// Source: D:564-616 (MCO 305 Design Guide)
// OCR repairs:
// - D:566-586 column interleaving repeated the header, ON ERROR, VEL/ACC/DEC, LINKGPAR, SET and HOME lines up to 7 times; each line kept once, in manual order
// - D:577-579 "VEL 80// ...ACC 100// ...DEC 100" run together on one line; split into one statement per line
// - D:567 the first header line "// Inputs: 1 ..." is lost; reconstructed as "// Inputs: 1 Goto pick up position" (by analogy with the "2 Goto deliver position" line)
// - D:566, 567, 573, 576, 580, 586, 600, 602, 614, 616 unterminated "/****" banner comments; closed with "/"
// - D:573 "/*********/ ON ERROR GOSUB ..." banner and statement on one line; split
// - D:587-591 "MAIN:" and the first IF branch run together (several copies); label put alone on its line, duplicates dropped
// - D:566-586 "<pre>"/"</pre>" HTML debris removed

/************************************/
// Inputs: 1 Goto pick up position
//         2 Goto deliver position
//         3 Home switch
//         8 Clear Error
// Outputs: 1 In pick up position
//          2 In deliver position
//          8 Error
/**********************************/
/*********/
ON ERROR GOSUB errhandle // In case of error go to error handler routine, this must always be included
/************************************/
VEL 80 // Sets positioning velocity related to par. 32-80 Maximum velocity
ACC 100 // Sets positioning acceleration related to par. 32-81 Shortest ramp
DEC 100 // Sets positioning deceleration related to par. 32-81 Shortest ramp
/********************** Define application parameters *************************/
LINKGPAR 1900 "Pick up Position" 0 1073741823 0
LINKGPAR 1901 "Deliver Position" 0 1073741823 0
/****** Define Home(0) position after power up ************/
SET I_FUNCTION_3 1 // Define input 3 as Home switch input
HOME // Go to Home and set position to 0
/************************************/
MAIN:
IF (IN 1 == 1) AND (IN 2 == 0) THEN // Go to pick up position when only input 1 is high
OUT 2 0 // Reset "In deliver position" output
POSA (GET 1900) // Go to position
OUT 1 1 // Set "In pick up position" output
ELSEIF (IN 1 == 0) AND (IN 2 == 1) THEN // Go to deliver position when only input 2 is high
OUT 1 0 // Reset "In pick up position" output
POSA (GET 1901) // Go to position
OUT 2 1 // Set "In deliver position" output
ELSE
MOTOR STOP // Stop if both inputs are low or high.
ENDIF
GOTO MAIN
/***************************** Sub programs start ***********************************/
SUBMAINPROG
/*************************************/
SUBPROG errhandle
err = 1 // Set error flag to remain in error handler until error is reset.
OUT 8 1 // Set error output
WHILE err DO // Remain in error handler until the reset is received
IF IN 8 THEN // Reset error when Input 8 is high.
ERRCLR // Clear error
err=0 // Reset error flag
ENDIF
ENDWHILE
OUT 8 0 // Reset error output
RETURN
/**************************************/
ENDPROG
/*************************************/
