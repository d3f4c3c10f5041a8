// Title: Software limit in speed mode: stop, clear and drive back
// Shows: SET NEGLIMIT, SET SWNEGLIMACT, SET ERRCOND, CVEL, CSTART, ON ERROR GOSUB, ERRCLR, POSA
// Run: motiontool run 27_speed_mode_limit.m --seconds 30
// Test-seconds: 30
// Expect: error 111 while running towards the limit
// Expect: stopped beyond NEGLIMIT: 1
// Expect: back inside the range at 0
// Expect-errors: 111
// Expect-end: ended
//
// A speed-mode move has no target, so the controller cannot refuse it
// in advance as it does with POSA (see 09_soft_limit_error.m). Instead
// it raises error 111 at the moment the actual position reaches the
// active limit. ERRCOND 2 makes the drive brake with the maximum
// deceleration instead of coasting; either way it ends a little beyond
// the limit.
//
// Since MCO 5.00 the error can be cleared while the axis stands outside
// the range, and the axis may then drive back - only in the direction
// back into the range. Driving further out raises error 198.

ON ERROR GOSUB on_error
SET NEGLIMIT -30000
SET SWNEGLIMACT 1
SET ERRCOND 2                  // controlled stop on errors
ACC 50
DEC 50
VEL 50
// The software limits are positions of the machine: HOME sets its zero
// and a DEFORIGIN moves the limits along (DG 10158), a SETORIGIN does
// not. An earlier program may have left the axis anywhere and a
// temporary zero set: start from the machine zero, inside the range.
RSTORIGIN
POSA 0
DELAY 200                     // settle, as after power-up
hit = 0

CVEL -30                       // towards the negative limit
t0 = TIME                      // (TIME counts from power-up; the way to the machine zero took a while)
CSTART
WHILE hit == 0 AND TIME - t0 < 5000 DO
    DELAY 10
ENDWHILE
IF hit == 0 THEN
    CSTOP
    PRINT "limit not detected, APOS ", APOS
ELSE
    PRINT "stopped beyond NEGLIMIT: ", APOS < (GET NEGLIMIT)
ENDIF

POSA 0                         // back into the range: allowed
PRINT "back inside the range at ", CPOS

SUBMAINPROG
SUBPROG on_error
    IF ERRNO == 111 THEN
        PRINT "error 111 while running towards the limit"
        DELAY 300              // let the controlled stop finish
        hit = 1
    ELSE
        PRINT "unexpected error ", ERRNO
    ENDIF
    ERRCLR                     // allowed outside the range since 5.00
RETURN
ENDPROG
