// Title: Limited jerk versus trapezoid ramps
// Shows: SET RAMPTYPE, GET JERKMIN, TIME, TRACKERR, NOWAIT, AXEND, GOSUB
// Run: motiontool run 21_jerk_vs_trapezoid.m --seconds 20 --set JERKMIN=200
// Test-settings: JERKMIN=200
// Test-seconds: 20
// Expect: JERKMIN 200 ms
// Expect: RAMPTYPE 0: 1805 ms, peak tracking error 1753 qc
// Expect: RAMPTYPE 2: 1929 ms, peak tracking error 1671 qc
// Expect: limited jerk costs 124 ms more
// Expect-end: ended
//
// With the default trapezoid ramp (RAMPTYPE 0) the acceleration jumps
// from zero to its full value at once. That jerk shakes the mechanics
// and makes the position loop lag. With RAMPTYPE 2 (limited jerk) the
// acceleration itself is ramped up and down within JERKMIN ms, which is
// smoother for the machine but makes every move a little longer.
//
// The program drives the same move with both ramp types and measures
// the time and the largest tracking error. Try other JERKMIN values
// with --set JERKMIN=... and compare.

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
VEL 80
ACC 60
DEC 60
PRINT "JERKMIN ", GET JERKMIN, " ms"

ramp = 0
WHILE ramp <= 2 DO
    SET RAMPTYPE ramp
    GOSUB timed_move
    PRINT "RAMPTYPE ", ramp, ": ", duration, " ms, peak tracking error ", peak, " qc"
    ramp = ramp + 2              // 0 and 2 only
ENDWHILE
PRINT "limited jerk costs ", duration - first, " ms more"

SUBMAINPROG
SUBPROG timed_move
    DELAY 200                    // start each move from rest
    peak = 0
    target = 50000 - CPOS        // alternate 0 -> 50000 -> 0
    t0 = TIME
    NOWAIT ON
    POSA target
    WHILE (AXEND & 2) DO
        IF abs(TRACKERR) > peak THEN
            peak = abs(TRACKERR)
        ENDIF
        DELAY 1
    ENDWHILE
    NOWAIT OFF
    duration = TIME - t0
    IF ramp == 0 THEN
        first = duration
    ENDIF
RETURN
ENDPROG
