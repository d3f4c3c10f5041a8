// Title: Watching the tracking error against POSERR
// Shows: TRACKERR, GET POSERR, SET POSERR, SET KPROP, NOWAIT, AXEND, ON ERROR
// Run: motiontool run 10_tracking_error.m --seconds 10
// Test-seconds: 10
// Expect: KPROP 30: peak tracking error 1798 qc, POSERR 20000
// Expect: error 108 after 564 ms of the move
// Expect: KPROP 3: peak tracking error 7996 qc, tripped 1
// Expect-errors: 108
// Expect-end: ended
//
// TRACKERR is the difference between where the axis should be (CPOS)
// and where it is (APOS). It grows with speed when the position loop
// is soft (small KPROP). If it exceeds POSERR the controller raises
// error 108 - usually the first sign of a blocked or overloaded axis.
//
// The program moves once with the default tuning and records the
// largest tracking error, then makes the loop ten times softer and the
// POSERR limit tighter, so that the same move trips error 108. In a
// real machine you would do the opposite: measure the peak with
// realistic moves and set POSERR with a sensible margin above it.

// An earlier program may have left the axis anywhere, still braking, and
// a temporary zero set (the controller keeps them): wait for the
// standstill (AXEND bit value 1), then count this program's positions
// from there, without touching the machine's zero and software limits
// (SETORIGIN is relative to the real zero, CR 3984-3999).
WHILE (AXEND & 1) == 0 DO
    DELAY 1
ENDWHILE
RSTORIGIN
SETORIGIN APOS
ON ERROR GOSUB on_error
VEL 80
ACC 80
DEC 80
tripped = 0

GOSUB measured_move
PRINT "KPROP ", GET KPROP, ": peak tracking error ", peak, " qc, POSERR ", GET POSERR

SET KPROP 3                   // a very soft loop ...
SET POSERR 8000               // ... and a tighter limit
GOSUB measured_move
PRINT "KPROP ", GET KPROP, ": peak tracking error ", peak, " qc, tripped ", tripped

SUBMAINPROG
SUBPROG measured_move
    peak = 0
    t_start = TIME
    NOWAIT ON
    POSA (CPOS + 40000)
    WHILE (AXEND & 2) AND tripped == 0 DO
        IF abs(TRACKERR) > peak THEN
            peak = abs(TRACKERR)
        ENDIF
        DELAY 1
    ENDWHILE
    NOWAIT OFF
RETURN

SUBPROG on_error
    IF ERRNO == 108 THEN
        tripped = 1
        // The motor already coasts (ERRCOND 0), so TRACKERR reads 0 here;
        // the peak seen by the main loop is the useful number.
        PRINT "error 108 after ", TIME - t_start, " ms of the move"
    ENDIF
    ERRCLR                    // motor on again where the axis stands
RETURN
ENDPROG
