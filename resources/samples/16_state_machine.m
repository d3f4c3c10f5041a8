// Title: A machine cycle as a SWITCH state machine
// Shows: SWITCH/CASE/DEFAULT/BREAK/ENDSWITCH, #define constants, NOWAIT, AXEND, TIME
// Run: motiontool run 16_state_machine.m --seconds 20 --input 1=0@0 --input 1=1@300 --input 1=0@400
// Test-inputs: 1=0@0 1=1@300 1=0@400
// Test-seconds: 20
// Expect: 301 ms: start pressed
// Expect: 3161 ms: cycle 1 complete
// Expect: 6021 ms: cycle 2 complete
// Expect: 8881 ms: cycle 3 complete
// Expect: batch finished after 3 cycles
// Expect-end: ended
//
// Written as a state machine, a machine cycle never blocks: each pass
// of the main loop looks at the current state, checks its condition
// and maybe moves on to the next state. The loop stays free to watch
// buttons, timers and faults at any moment, which a chain of blocking
// POSA / DELAY / WAITI commands cannot do.
//
// Each CASE ends with BREAK; without it execution would fall through
// into the next CASE, as in C. The states are named with #define so
// the code reads like the machine's flow chart.

#define ST_WAIT_START 0
#define ST_FEED 1
#define ST_PRESS 2
#define ST_RETURN 3
#define ST_DONE 4

t0 = TIME - 1                 // the start (TIME counts from power-up; line 1 runs at start + 1 ms)
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
VEL 60
ACC 60
DEC 60
NOWAIT ON                       // moves must not block the loop
state = ST_WAIT_START
cycles = 0

WHILE state != ST_DONE DO
    SWITCH (state)
    CASE ST_WAIT_START:
        IF IN 1 THEN
            PRINT TIME - t0, " ms: start pressed"
            state = ST_FEED
            POSA 25000
        ENDIF
        BREAK
    CASE ST_FEED:
        IF (AXEND & 1) THEN    // target reached
            OUT 2 1            // press down
            press_until = TIME + 300
            state = ST_PRESS
        ENDIF
        BREAK
    CASE ST_PRESS:
        IF TIME >= press_until THEN
            OUT 2 0
            POSA 0
            state = ST_RETURN
        ENDIF
        BREAK
    CASE ST_RETURN:
        IF (AXEND & 1) THEN
            cycles++
            PRINT TIME - t0, " ms: cycle ", cycles, " complete"
            IF cycles < 3 THEN
                state = ST_FEED // next part, no new start needed
                POSA 25000
            ELSE
                state = ST_DONE
            ENDIF
        ENDIF
        BREAK
    DEFAULT:
        PRINT "unknown state ", state
        state = ST_DONE
    ENDSWITCH
    DELAY 5                     // loop time: 5 ms plus the code
ENDWHILE
PRINT "batch finished after ", cycles, " cycles"
