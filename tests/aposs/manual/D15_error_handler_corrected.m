// D15 (corrected copy) — Error handling: print ERRNO, wait 10 s, clear the error and terminate
// Source: D:6232-6257 (MCO 305 Design Guide)
// OCR repairs:
// - D:6251 string not terminated: PRINT "Re-set error status .... -> PRINT "Re-set error status ...." (closing quote restored)
// Correction (the manual's program itself, not OCR): the printed program tests "IF (ERRNO == 25)" for a limit switch,
//   but the limit-switch error is 125 (D:11612-11628; ERRNO holds the numbers of the troubleshooting chapter,
//   C:1326-1338) — as printed a pushed limit switch reports "It's o.k., although it wasn't a limit switch". This copy
//   tests ERRNO == 125.

ON ERROR GOSUB errhandle
PRINT "Please create a temporary error status"
PRINT " by pushing a limit switch."
                       /* Endless loop */
endless:
GOTO endless
/****** SUBROUTINE-AREA ********/
SUBMAINPROG
     SUBPROG errhandle // Evaluate error number and re-set error status
           PRINT "Current error number: ", ERRNO
           IF (ERRNO == 125) THEN /* limit switch or control stop */
                 PRINT "HW end limit activated"
           ELSE
                 PRINT "It's o.k., although it wasn't a limit switch"
           ENDIF
           PRINT "You can re-set the cause of the error";
           PRINT "within the next 10 seconds"
           DELAY 10000 /* Wait 10 seconds */
           PRINT "Re-set error status ...."
                      /* Re-set error status */
           ERRCLR
           PRINT "... and program terminated."
           EXIT /* program termination */
     RETURN
ENDPROG
