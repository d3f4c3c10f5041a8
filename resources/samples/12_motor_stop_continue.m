// Title: Pausing a move with MOTOR STOP and resuming it with CONTINUE
// Shows: MOTOR STOP, CONTINUE, WAITI, IN, AXEND, NOWAIT, WAITAX
// Run: motiontool run 12_motor_stop_continue.m --seconds 15 --input 5=0@0 --input 5=1@1500 --input 5=0@3000
// Test-inputs: 5=0@0 5=1@1500 5=0@3000
// Test-seconds: 15
// Expect: door open: held at 51200, AXEND 75
// Expect: door closed, resuming
// Expect: target reached: 80000, AXEND 1
// Expect-end: ended
//
// A guard door on input 5 must pause the machine, not abort it. MOTOR
// STOP brakes with the programmed DEC ramp and holds the axis; the
// interrupted target is remembered. CONTINUE later resumes the very
// same move, so the program does not have to work out what was left.
//
// With NOWAIT ON the braking runs in the background, so we wait for the
// standstill ourselves: AXEND bit value 8 appears once the axis is held
// by MOTOR STOP. The manual lists the whole pattern of a paused move:
// 1 standing still + 2 positioning still pending + 8 STOP state + 64
// (the manual's "controller off" bit) = 75. Bit value 128 (ready again
// after MOTOR STOP or ERRCLR, CR 316-317) may stay from an earlier
// program, so the prints leave it out (& 127).

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
VEL 40
ACC 40
DEC 80
NOWAIT ON
POSA 80000

WHILE (AXEND & 2) DO
    IF IN 5 THEN
        MOTOR STOP                 // brake with DEC, then hold
        WHILE (AXEND & 8) == 0 DO  // still braking
            DELAY 1
        ENDWHILE
        PRINT "door open: held at ", CPOS, ", AXEND ", AXEND & 127
        WAITI 5 OFF                // wait for the door to close
        PRINT "door closed, resuming"
        CONTINUE                   // same target, same VEL/ACC/DEC
    ENDIF
    DELAY 2
ENDWHILE
WAITAX
PRINT "target reached: ", CPOS, ", AXEND ", AXEND & 127
