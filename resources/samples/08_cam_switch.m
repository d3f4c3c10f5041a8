// Title: Electronic cam switch with position interrupts
// Shows: ON +APOS SETOUT, ON -APOS SETOUT, ON +APOS GOSUB, NOWAIT, AXEND, SYSVAR
// Run: motiontool run 08_cam_switch.m --seconds 10
// Test-seconds: 10
// Expect: valve 0 near APOS 0
// Expect: valve 1 near APOS 8000
// Expect: valve 0 near APOS 14000
// Expect: leg 0 done at 20000, passes 1
// Expect: valve 1 near APOS 14000
// Expect: valve 0 near APOS 8000
// Expect: leg 1 done at 0, passes 1
// Expect-end: ended
//
// A glue valve on output 2 must be open while the axis passes the
// window 8000 ... 14000 qc, in both directions. Switching it from the
// main program would depend on how fast the program loop runs; the
// SETOUT form of a position interrupt switches the output in the
// background, within a millisecond, without any program code.
//
// The sign says in which direction the position must be passed:
// +APOS fires when passing upwards, -APOS when passing downwards. So a
// window needs four entries: on/off going up and on/off coming back.
// A GOSUB form counts the upward passes, to show both kinds side by side.

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
ON +APOS 8000 SETOUT 2        // going up: open at 8000 ...
ON +APOS 14000 SETOUT -2      // ... close at 14000
ON -APOS 14000 SETOUT 2       // coming back: open at 14000 ...
ON -APOS 8000 SETOUT -2       // ... close at 8000
ON +APOS 11000 GOSUB count_pass

VEL 30
ACC 50
DEC 50
passes = 0
NOWAIT ON                     // move in the background and watch
last = -1
leg = 0
WHILE leg < 2 DO
    IF leg == 0 THEN
        POSA 20000
    ELSE
        POSA 0
    ENDIF
    REPEAT
        valve = SYSVAR[0x0122020A].2   // output 2 = bit 2 of the output byte
        IF valve != last THEN
            PRINT "valve ", valve, " near APOS ", (APOS rnd 100) * 100
            last = valve
        ENDIF
        DELAY 2
    UNTIL (AXEND & 2) == 0   // bit value 2: positioning still active
    PRINT "leg ", leg, " done at ", CPOS, ", passes ", passes
    leg = leg + 1
ENDWHILE

SUBMAINPROG
SUBPROG count_pass
    passes = passes + 1
RETURN
ENDPROG
