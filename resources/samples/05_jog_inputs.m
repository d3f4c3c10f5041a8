// Title: Jogging with push buttons
// Shows: WAITI, IN, CVEL, CSTART, CSTOP, WHILE, IF/ELSEIF
// Run: motiontool run 05_jog_inputs.m --seconds 10 --input 1=0@0 --input 2=0@0 --input 3=0@0 --input 1=1@500 --input 1=0@1500 --input 2=1@2500 --input 2=0@3000 --input 3=1@4000
// Test-inputs: 1=0@0 2=0@0 3=0@0 1=1@500 1=0@1500 2=1@2500 2=0@3000 3=1@4000
// Test-seconds: 10
// Expect: waiting for a jog button
// Expect: jog mode on
// Expect: direction 1 at APOS 0
// Expect: direction 0 at APOS 9397
// Expect: direction -1 at APOS 10240
// Expect: direction 0 at APOS 5963
// Expect: jog mode off at APOS 5120
// Expect-end: ended
//
// Input 1 jogs forward, input 2 jogs backward, input 3 ends jog mode.
// WAITI blocks until an input has the wanted level; that is the right
// tool for "wait for the operator", because it costs no CPU time and
// needs no loop. While jogging we poll the buttons with IN instead,
// since we must react to either button at any time.
//
// Speed mode suits jogging: the axis moves as long as the button is
// held and stops with the DEC ramp when it is released.

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
ACC 100
DEC 100
jog = 10                        // jog speed, % of VELMAX

PRINT "waiting for a jog button"
WAITI 1 ON                      // nothing happens until the first press
PRINT "jog mode on"

CVEL 0
CSTART                          // speed mode with speed 0: axis holds
direction = 0
WHILE IN 3 == 0 DO
    IF IN 1 AND NOT IN 2 THEN
        wanted = 1
    ELSEIF IN 2 AND NOT IN 1 THEN
        wanted = -1
    ELSE
        wanted = 0              // none or both pressed: stand still
    ENDIF
    IF wanted != direction THEN
        direction = wanted
        CVEL (direction * jog)
        PRINT "direction ", direction, " at APOS ", APOS
    ENDIF
    DELAY 10                    // poll every 10 ms, like a PLC scan
ENDWHILE

CSTOP
DELAY 200
PRINT "jog mode off at APOS ", APOS
