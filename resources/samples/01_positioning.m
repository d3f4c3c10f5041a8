// Title: Absolute positioning between two points
// Shows: VEL, ACC, DEC, POSA, APOS, CPOS, TIME, DELAY, PRINT
// Run: motiontool run 01_positioning.m --seconds 10
// Test-seconds: 10
// Expect: start at 0
// Expect: trip 0: CPOS 20000 after 1444 ms, APOS 19953, settled APOS 19999
// Expect: trip 1: CPOS 0 after 1444 ms, APOS 47, settled APOS 1
// Expect: trip 2: CPOS 20000 after 1444 ms, APOS 19953, settled APOS 19999
// Expect: trip 3: CPOS 0 after 1444 ms, APOS 47, settled APOS 1
// Expect: done
// Expect-end: ended
//
// The simplest useful program: shuttle the axis between two absolute
// positions a few times. VEL, ACC and DEC are given in percent of the
// maxima (VELRES is 100 by default), so the same program keeps its
// character when VELMAX or RAMPMIN are changed on the drive.
//
// POSA waits until the set-point (CPOS) has arrived at the target. The
// real axis (APOS) still trails by a few counts at that moment; a short
// DELAY lets the position loop settle before we look at APOS.

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
VEL 60          // 60 % of VELMAX: fast, but leaves headroom for the loop
ACC 30          // gentle start ...
DEC 50          // ... and a firmer stop: braking is usually less critical

PRINT "start at ", APOS
trips = 0
WHILE trips < 4 DO
    IF (trips mod 2) == 0 THEN
        target = 20000
    ELSE
        target = 0
    ENDIF
    t0 = TIME
    POSA target                 // blocks until CPOS == target
    moved = TIME - t0
    PRINT "trip ", trips, ": CPOS ", CPOS, " after ", moved, " ms, APOS ", APOS;
    DELAY 100                   // let the following error decay
    PRINT ", settled APOS ", APOS
    trips = trips + 1
ENDWHILE
PRINT "done"
