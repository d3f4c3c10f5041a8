// Title: Speed mode: run, reverse and stop a conveyor
// Shows: CVEL, CSTART, CSTOP, ACC, DEC, AVEL, AXEND, DELAY
// Run: motiontool run 03_speed_mode.m --seconds 10
// Test-seconds: 10
// Expect: forward:  AVEL 25600  speed mode 1
// Expect: faster:   AVEL 51250
// Expect: reverse:  AVEL -25600
// Expect: stopped:  AVEL 0  speed mode 0
// Expect: holding at 73600
// Expect-end: ended
//
// In speed mode the axis has no target, only a velocity. CVEL sets it
// (negative = reverse) and CSTART switches the mode on. While the mode
// is active, a new CVEL takes effect at once, ramped with ACC/DEC, so a
// conveyor can be slowed down or reversed without stopping first.
// CSTOP brakes with DEC and the axis then holds its position again.
//
// AXEND bit value 4 tells whether speed mode is active; AVEL is the
// measured speed (qc/s), averaged over the last 20 ms.

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
ACC 40
DEC 40

CVEL 25                 // 25 % of VELMAX
CSTART
DELAY 1000
PRINT "forward:  AVEL ", AVEL, "  speed mode ", (AXEND & 4) == 4

CVEL 50                 // faster, no stop needed
DELAY 1000
PRINT "faster:   AVEL ", AVEL

CVEL -25                // reverse: ramps down through zero and back up
DELAY 2000
PRINT "reverse:  AVEL ", AVEL

CSTOP                   // brake with DEC, then hold position
DELAY 1000
PRINT "stopped:  AVEL ", AVEL, "  speed mode ", (AXEND & 4) == 4
PRINT "holding at ", APOS
