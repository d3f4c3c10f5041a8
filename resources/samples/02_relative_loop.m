// Title: Cut to length with a relative positioning LOOP
// Shows: POSR, LOOP, labels, OUT, DELAY, CPOS
// Run: motiontool run 02_relative_loop.m --seconds 10
// Test-seconds: 10
// Expect: piece 1 cut at 6000
// Expect: piece 2 cut at 12000
// Expect: piece 3 cut at 18000
// Expect: piece 4 cut at 24000
// Expect: piece 5 cut at 30000
// Expect: batch of 5 done, fed 30000 qc
// Expect-end: ended
//
// A feed axis pushes material forward by one piece length, a knife on
// output 1 cuts, and the cycle repeats. Relative moves (POSR) are the
// natural choice here: every piece is "one length further", wherever
// the axis happens to stand, so the program never needs to know an
// absolute coordinate and can run forever without overflowing.
//
// POSR counts from the actual position APOS. Here the cut gives the
// position loop time to settle, so every piece is exact. Without such
// a pause the few counts APOS still lags behind at the end of a move
// would add up piece by piece; then POSA (CPOS + length) is better.
//
// LOOP n label jumps back n times, so the block runs n + 1 times in
// total; that is why PIECES - 1 is passed to LOOP.

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
VEL 80
ACC 60
DEC 60

pieces = 5
length = 6000          // qc per piece
count = 0

next_piece:
    POSR length        // feed one piece from where we are
    OUT 1 1            // knife down ...
    DELAY 150          // ... long enough to cut through
    OUT 1 0
    count = count + 1
    PRINT "piece ", count, " cut at ", CPOS
    LOOP (pieces - 1) next_piece

PRINT "batch of ", count, " done, fed ", CPOS, " qc"
