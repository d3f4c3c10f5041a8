// Title: Position synchronisation with an offset (SYNCP, MOVESYNCORIGIN)
// Shows: SYNCP, SYNCACCURACY, SYNCSTAT, SYNCERR, MOVESYNCORIGIN, DEFMORIGIN, PULSVEL, MAPOS, FFVEL
// Run: motiontool run 30_syncp_offset.m --seconds 10
// Test-seconds: 10
// Expect: in sync after about 1400 ms, SYNCERR inside SYNCACCURACY: 1
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

PULSACC 0                // an earlier program's virtual master may still run:
PULSVEL 0                // switch it off (CR 3570-3571) and wait until the master
WHILE MAVEL != 0 DO      // stands: this program starts it from standstill
    DELAY 1
ENDWHILE
t0 = TIME                     // the start of the measurement (TIME counts from power-up)
// An earlier program may have left the axis anywhere and a temporary zero
// set (the controller keeps both): count this program's positions from
// where the axis stands now, without touching the machine's zero and
// software limits (SETORIGIN is relative to the real zero, CR 3984-3999).
RSTORIGIN
here = CPOS                // the slave's set-point, a machine position ...
SETORIGIN here             // ... is this program's zero
SET SYNCFACTM 1
SET SYNCFACTS 1
SET SYNCACCURACY 100     // qc: the "in sync" window
SET FFVEL 1000           // 100 % velocity feed-forward
ACC 100
DEC 100
VEL 100

DEFMORIGIN               // the master position here is 0 ...
DEFSYNCORIGIN 0 here     // ... and belongs to the slave here (machine qc)
PULSACC 1000000          // lines/s^2: full speed within 10 ms
PULSVEL 10000            // 40000 master qc/s
DELAY 500                // the master is 20000 qc ahead when the slave starts
SYNCP
WHILE (SYNCSTAT & 4) == 0 DO
ENDWHILE
// to 100 ms: the catch-up takes a few ms more or less with where
// within a qc an earlier program left the slave
PRINT "in sync after about ", ((TIME - t0 - 500) rnd 100) * 100, " ms, SYNCERR inside SYNCACCURACY: ", SYNCERR <= GET SYNCACCURACY
DELAY 1000
PRINT "CPOS - MAPOS = ", CPOS - MAPOS, ", SYNCERR ", SYNCERR
MOVESYNCORIGIN 2000      // run 2000 qc ahead of the master
DELAY 1000
PRINT "CPOS - MAPOS = ", CPOS - MAPOS, ", SYNCERR ", SYNCERR
MOTOR STOP
WAITAX
