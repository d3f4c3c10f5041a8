// Title: Background moves: polling AXEND and changing the target on the fly
// Shows: NOWAIT ON/OFF, POSA, VEL, AXEND, WAITAX, OUT, REPEAT/UNTIL
// Run: motiontool run 11_nowait_retarget.m --seconds 10
// Test-seconds: 10
// Expect: started, AXEND 2
// Expect: speed up at 20000
// Expect: new target 90000 at 50000
// Expect: arrived at 90000, AXEND 1
// Expect: home again at 0
// Expect-end: ended
//
// With NOWAIT ON a POSA only starts the move and the program goes on at
// once. The program can then watch the axis, do other work, and even
// give a new target: a POSA during a running move re-targets smoothly,
// without stopping first. A new VEL is taken over by such a repeated
// POSA, which is the usual way to change speed in the middle of a move.
//
// A new target must leave room to brake: at 60 % speed and DEC 50 the
// braking distance is about 37000 qc. A closer target would make the
// set-point overshoot and come back.
//
// AXEND bit value 2 is set while a positioning move is active and
// bit value 1 once the target has been reached. Bit value 128 (ready
// again after an ERRCLR or MOTOR STOP, CR 316-317) stays from whatever
// an earlier program did, so the prints leave it out (& 127).

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
ACC 50
DEC 50
VEL 20
NOWAIT ON

POSA 100000                   // a long move, started in the background
PRINT "started, AXEND ", AXEND & 127

step = 0
REPEAT
    IF step == 0 AND APOS > 20000 THEN
        VEL 60                // faster from here on ...
        POSA 100000           // ... taken over by repeating the target
        PRINT "speed up at ", (APOS rnd 1000) * 1000
        step = 1
    ELSEIF step == 1 AND APOS > 50000 THEN
        POSA 90000            // the order changed: stop earlier
        PRINT "new target 90000 at ", (APOS rnd 1000) * 1000
        step = 2
    ENDIF
    DELAY 5                   // the main loop is free for other work
UNTIL (AXEND & 2) == 0

PRINT "arrived at ", CPOS, ", AXEND ", AXEND & 127

// NOWAIT also lets several things happen at once: start the way back,
// switch a lamp and only then wait for the axis.
POSA 0
OUT 3 1
WAITAX
OUT 3 0
NOWAIT OFF                    // back to the default: every move waits
PRINT "home again at ", CPOS
