// Title: Software limits and an error handler
// Shows: SET POSLIMIT, SET SWPOSLIMACT, ON ERROR GOSUB, ERRNO, ERRCLR, POSA
// Run: motiontool run 09_soft_limit_error.m --seconds 30
// Test-seconds: 30
// Expect: at 30000
// Expect: error 111 at APOS 29953 - target outside the software limits
// Expect: after the refused move: CPOS 29953, errors 1
// Expect: at 45000, pending error 0
// Expect-errors: 111
// Expect-end: ended
//
// Software limits protect the mechanics from targets outside the
// working range. In positioning mode the controller checks the target
// before it starts: a POSA beyond POSLIMIT raises error 111 and the
// axis does not move at all.
//
// Without ON ERROR any error ends the program. With a handler the
// program decides itself: here it reports the error, clears it with
// ERRCLR (which also switches the position control back on) and
// carries on with a safe target. ERRCLR only helps when the cause is
// gone; the cause here was one bad command, so clearing is enough.
//
// With the default ERRCOND 0 an axis error also lets the motor coast,
// and ERRCLR takes the actual position as the new set-point. POSA had
// returned when CPOS arrived, before APOS had quite caught up, which is
// why CPOS reads a few counts short of 30000 after the error.

ON ERROR GOSUB on_error

SET POSLIMIT 50000            // qc, in user units of this axis
SET SWPOSLIMACT 1             // switch the positive limit on
VEL 50
ACC 50
DEC 50
// The software limits are positions of the machine: HOME sets its zero
// and a DEFORIGIN moves the limits along (DG 10158), a SETORIGIN does
// not. An earlier program may have left the axis anywhere and a
// temporary zero set: start from the machine zero, inside the range.
RSTORIGIN
POSA 0
DELAY 200                     // settle, as after power-up
errors = 0

table_pos = 30000
POSA table_pos
PRINT "at ", CPOS

table_pos = 65000             // a mistyped recipe value
POSA table_pos                // refused: error 111, no motion
PRINT "after the refused move: CPOS ", CPOS, ", errors ", errors

POSA 45000                    // inside the range again: fine
PRINT "at ", CPOS, ", pending error ", ERRNO

SUBMAINPROG
SUBPROG on_error
    errors = errors + 1
    PRINT "error ", ERRNO, " at APOS ", APOS;
    IF ERRNO == 111 THEN
        PRINT " - target outside the software limits"
    ELSE
        PRINT " - unexpected"
    ENDIF
    ERRCLR                    // without this the handler runs again
RETURN
ENDPROG
