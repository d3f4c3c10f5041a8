// Title: Position synchronisation with an offset (SYNCP, MOVESYNCORIGIN)
// Shows: SYNCP, SYNCACCURACY, SYNCSTAT, SYNCERR, MOVESYNCORIGIN, DEFMORIGIN, PULSVEL, MAPOS, FFVEL
// Run: motiontool run 30_syncp_offset.m --seconds 10
// Test-seconds: 10
// Expect: in sync after 1377 ms, SYNCERR 100
// Expect: CPOS - MAPOS = 0, SYNCERR 40
// Expect: CPOS - MAPOS = 2000, SYNCERR 40
// Expect-end: ended
//
// SYNCP locks the slave position to the master position as they stand at
// the start, or as DEFSYNCORIGIN relates them: slave = MAPOS x
// SYNCFACTS/SYNCFACTM (+ offset). Unlike SYNCV no position error builds
// up, so a printing roller stays in register with the web. A slave that
// starts behind a running master catches up within VEL/ACC first; bit 3
// (value 4) of SYNCSTAT tells when it is inside the SYNCACCURACY window.
// Velocity feed-forward (FFVEL) keeps the tracking error, and so SYNCERR,
// small at constant speed. MOVESYNCORIGIN shifts the relation by a master
// distance while running, e.g. to correct the register by hand.

t0 = TIME - 1                 // the start (TIME counts from power-up; line 1 runs at start + 1 ms)
SET SYNCFACTM 1
SET SYNCFACTS 1
SET SYNCACCURACY 100     // qc: the "in sync" window
SET FFVEL 1000           // 100 % velocity feed-forward
ACC 100
DEC 100
VEL 100

DEFMORIGIN               // the master position here is 0 ...
DEFSYNCORIGIN 0 0        // ... and belongs to slave position 0
PULSVEL 10000            // 40000 master qc/s
DELAY 500                // the master is 20000 qc ahead when the slave starts
SYNCP
WHILE (SYNCSTAT & 4) == 0 DO
ENDWHILE
PRINT "in sync after ", TIME - t0 - 500, " ms, SYNCERR ", SYNCERR
DELAY 1000
PRINT "CPOS - MAPOS = ", CPOS - MAPOS, ", SYNCERR ", SYNCERR
MOVESYNCORIGIN 2000      // run 2000 qc ahead of the master
DELAY 1000
PRINT "CPOS - MAPOS = ", CPOS - MAPOS, ", SYNCERR ", SYNCERR
MOTOR STOP
WAITAX
