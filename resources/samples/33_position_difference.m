// Title: Distances between two positions with APOSDIFF, CPOSDIFF and MAPOSDIFF
// Shows: APOSDIFF, CPOSDIFF, MAPOSDIFF, APOS, CPOS, MAPOS, PULSVEL, PULSACC, POSR
// Run: motiontool run 33_position_difference.m --seconds 5
// Test-seconds: 5
// Expect: moved 24906 qc, commanded 25000
// Expect: moved -9904 qc back
// Expect: APOS - old: -2147383648, APOSDIFF: 100000
// Expect: master moved 70020
// Expect-end: ended
//
// "How far since then?" is APOS - old for a machine that runs back and
// forth, but a conveyor that always runs one way counts up until the
// position counter overflows, and then APOS - old is suddenly a huge
// negative number. APOSDIFF old (and CPOSDIFF, IPOSDIFF, MAPOSDIFF for the
// other positions) returns the difference with the overflow taken care
// of, so the program is still right after days of running.
// (This does not help if the application counts in user units.)
//
// The virtual master (PULSVEL) drives the master position MAPOS here.

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
PULSACC 0                // an earlier program's virtual master may still run:
PULSVEL 0                // switch it off (CR 3570-3571) and wait until the master
WHILE MAVEL != 0 DO      // stands: this program starts it from standstill
    DELAY 1
ENDWHILE
VEL 100
ACC 100
DEC 100
POSA 0                   // the set-point on a whole qc (a stopped synchronisation may leave it between two)
old_a = APOS
old_c = CPOS
POSR 25000
PRINT "moved ", APOSDIFF old_a, " qc, commanded ", CPOSDIFF old_c   // APOS lags CPOS by the tracking error
old_a = APOS
POSR -10000
PRINT "moved ", APOSDIFF old_a, " qc back"

// A position stored just before the counter overflowed (made up here:
// the simulated axis would need days to get there) is far "ahead" of
// the present one. The plain subtraction is nonsense, APOSDIFF is not.
old_a = APOS - 100000 + 2147483647 + 1
PRINT "APOS - old: ", APOS - old_a, ", APOSDIFF: ", APOSDIFF old_a

old_m = MAPOS
PULSACC 20000
PULSVEL 10000                   // 10000 lines/s = 40000 master qc/s
DELAY 2000
PRINT "master moved ", (MAPOSDIFF old_m rnd 10) * 10    // to 10 qc: where within a qc the master starts depends on what ran before
