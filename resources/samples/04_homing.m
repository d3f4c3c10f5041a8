// Title: Homing on a reference switch, then working moves
// Shows: SET I_FUNCTION_1, HOME_VEL, HOME_TYPE, HOME_OFFSET, HOME, POSA, APOS
// Run: motiontool run 04_homing.m --seconds 30
// Test-seconds: 30
// Expect: before HOME: 5000 qc below the cam, switch 0
// Expect: after HOME:  APOS 3, switch 0
// Expect: loading station at -15000
// Expect: work station at    -5000
// Expect: back at zero, APOS -1
// Expect-end: ended
//
// After power-up an incremental encoder does not know where the axis is.
// HOME drives to a reference switch and makes the point found there the
// zero of all later absolute moves. In the simulator the switch is a cam
// that starts at 20000 qc; a positive HOME_VEL searches in that
// direction.
//
// HOME_TYPE 1 reverses off the switch slowly and takes the switch edge
// as the reference (type 0 would go on to the encoder index pulse for a
// more repeatable result). HOME_OFFSET shifts the zero away from the
// switch, so that the working range does not sit on the cam.

SET I_FUNCTION_1 1      // input 1 is the reference switch (normally open)
SET HOME_VEL 10         // keep the search slow: the switch is only a cam
SET HOME_RAMP 20
SET HOME_TYPE 1         // switch edge only, no index pulse
SET HOME_OFFSET -2000   // zero lies 2000 qc before the switch edge
DELAY 2                 // input 1 follows the switch from the next scan, not a level set before

// A machine that has been running may stand below the cam, on it or
// above it, and HOME searches in one direction only (the sign of
// HOME_VEL). So first find the cam in widening sweeps, down and up,
// then its lower edge, and start HOME from below it as after power-up:
// the same edge, the same zero, wherever the axis was.
RSTORIGIN               // positions of the machine, not of a fixture
VEL 100
ACC 100
DEC 100
NOWAIT ON
span = 40000
dir = -1
WHILE IN 1 == 0 DO
    POSR (dir * span)
    WHILE IN 1 == 0 AND (AXEND & 2) DO
        DELAY 1
    ENDWHILE
    dir = -dir
    span = span * 2
ENDWHILE
CVEL -50                // on the cam: down through it
CSTART
down_on_cam = 0
REPEAT                  // (coming up, the axis may brake beyond the cam)
    IF IN 1 AND AVEL < 0 THEN
        down_on_cam = 1
    ENDIF
    DELAY 1
UNTIL down_on_cam AND IN 1 == 0
low = APOS              // where the cam begins
NOWAIT OFF
POSA (low - 5000)
PRINT "before HOME: ", low - CPOS, " qc below the cam, switch ", IN 1
HOME
DELAY 50                // let the loop settle on the new zero
PRINT "after HOME:  APOS ", APOS, ", switch ", IN 1

// From now on every absolute position refers to the homed zero.
VEL 50
ACC 50
DEC 50
POSA -15000
PRINT "loading station at ", CPOS
POSA -5000
PRINT "work station at    ", CPOS
POSA 0
DELAY 100
PRINT "back at zero, APOS ", APOS
