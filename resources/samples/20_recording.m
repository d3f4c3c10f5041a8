// Title: Recording a move with TESTSETP and reading the samples back
// Shows: TESTSETP, TESTSTART, SYSVAR 4097/4098/4102, DIM, interleaved samples, PRINT ;, CHR
// Run: motiontool run 20_recording.m --seconds 10 --record rec.csv
// Test-seconds: 10
// Expect: t = 0 ms: APOS 0, CPOS 0, TRACKERR 0
// Expect: t = 200 ms: APOS 600, CPOS 827, TRACKERR 227
// Expect: t = 400 ms: APOS 2801, CPOS 3293, TRACKERR 492
// Expect: t = 600 ms: APOS 6640, CPOS 7397, TRACKERR 757
// Expect: t = 800 ms: APOS 12118, CPOS 13140, TRACKERR 1022
// Expect: 80 ms |
// Expect: 180 ms |##
// Expect: 280 ms |###
// Expect: 380 ms |####
// Expect: 480 ms |#####
// Expect: 580 ms |#######
// Expect: 680 ms |########
// Expect: 780 ms |#########
// Expect: 880 ms |###########
// Expect: 980 ms |##########
// Expect: peak tracking error 1107 qc in sample 45
// Expect-end: ended
//
// The controller can sample internal values in the background while
// the program runs - the same data the oscilloscope shows. TESTSETP
// sets it up in one line: the interval in ms, three SYSVAR indices and
// the array that receives the samples. TESTSTART n then records n
// samples.
//
// 4097 is the actual position (APOS in qc), 4098 the command position
// (CPOS), 4102 the tracking error. The array holds the samples one
// after the other, the three values of each sample side by side:
// rec[1..3] = sample 1, rec[4..6] = sample 2, ... so it needs
// 3 * n elements.

DIM rec[150]

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
// The recorded APOS and CPOS (SYSVAR 4097/4098) are machine positions,
// which SETORIGIN does not shift (see 23_user_zero.m): the printout
// subtracts where they stood at the start.
start_a = SYSVAR[4097]
start_c = SYSVAR[4098]
TESTSETP 20 4097 4098 4102 rec   // every 20 ms: APOS, CPOS, TRACKERR
VEL 50
ACC 40
DEC 40
TESTSTART 50                     // 50 samples = 1 s of data
POSA 30000
DELAY 200                        // be sure the last samples are taken

n = 1
WHILE n <= 50 DO
    k = (n - 1) * 3
    PRINT "t = ", (n - 1) * 20, " ms: APOS ", rec[k + 1] - start_a;
    PRINT ", CPOS ", rec[k + 2] - start_c, ", TRACKERR ", rec[k + 3]
    n = n + 10                   // every tenth sample is enough here
ENDWHILE

// A tiny bar chart of the tracking error: ';' keeps PRINT on the same
// line, CHR(35) is the character '#'.
n = 5
WHILE n <= 50 DO
    PRINT (n - 1) * 20, " ms |";
    bar = rec[n * 3] % 100       // one '#' per 100 qc
    WHILE bar > 0 DO
        PRINT CHR(35);
        bar = bar - 1
    ENDWHILE
    PRINT ""
    n = n + 5
ENDWHILE

// Find the largest tracking error in the whole recording.
peak = 0
n = 1
WHILE n <= 50 DO
    e = abs(rec[n * 3])
    IF e > peak THEN
        peak = e
        at = n
    ENDIF
    n++
ENDWHILE
PRINT "peak tracking error ", peak, " qc in sample ", at
