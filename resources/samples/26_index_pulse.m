// Title: Finding the encoder index pulse with INDEX
// Shows: INDEX, HOME_VEL, GET ENCODER, mod, rnd, DEFORIGIN, REPEAT/UNTIL
// Run: motiontool run 26_index_pulse.m --seconds 40
// Test-seconds: 40
// Expect: one revolution = 4096 qc
// Expect: from 1234: index at 4096 = turn 1 + 0 qc
// Expect: from 6789: index at 8192 = turn 2 + 0 qc
// Expect: from 12344: index at 16384 = turn 4 + 0 qc
// Expect: new zero at the index: APOS 0
// Expect-end: ended
//
// An incremental encoder gives one index (zero) pulse per revolution.
// INDEX drives slowly, with HOME_VEL and in the direction of its sign,
// to the next index pulse and stops there. Because the pulse sits at
// the same place of the motor shaft every turn, it is far more
// repeatable than a mechanical switch: HOME_TYPE 0 uses exactly this
// to refine the switch position.
//
// Here the axis starts from a few odd positions; every INDEX ends on a
// multiple of one revolution (4 * ENCODER qc). DEFORIGIN then makes the
// last index position the zero.

SET HOME_VEL 5                  // slow: the pulse is only a few qc wide
VEL 50
ACC 50
DEC 50
rev = 4 * GET ENCODER           // qc per motor revolution
PRINT "one revolution = ", rev, " qc"

// The pulses sit at fixed places of the motor shaft, and an earlier
// program may have left the axis anywhere and a temporary zero set:
// make the first pulse after the machine zero this program's zero, so
// that the positions below are the same on every run (SETORIGIN p is a
// machine position, CR 3984-3999).
RSTORIGIN
POSA 0
INDEX
DELAY 100
SETORIGIN APOS

start = 1234
REPEAT
    POSA start
    INDEX                       // runs to the end even with NOWAIT ON
    DELAY 100
    PRINT "from ", start, ": index at ", APOS, " = turn ", APOS rnd rev, " + ", APOS mod rev, " qc"
    start = start + 5555
UNTIL start > 15000

RSTORIGIN                       // back to machine positions ...
DEFORIGIN                       // ... and this index pulse is the machine's zero now
PRINT "new zero at the index: APOS ", APOS
