// Title: Conveyor following a virtual master with velocity synchronisation
// Shows: PULSVEL, PULSACC, SYNCFACTM, SYNCFACTS, SYNCV, MAVEL, AVEL, MOTOR STOP
// Run: motiontool run 29_syncv_conveyor.m --seconds 10
// Test-seconds: 10
// Expect: master 80000 qc/s  slave 40000
// Expect: master 80000 qc/s  slave 102000
// Expect: slave stopped at 280400
// Expect-end: ended
//
// Without an external master encoder the MCO's encoder simulation (the
// virtual master) drives the master input: PULSVEL sets its frequency in
// encoder lines per second (one line = 4 qc), PULSACC the ramp to it.
// SYNCV then makes the slave run at master velocity × SYNCFACTS/SYNCFACTM.
// Speed synchronisation only matches velocities: a position offset that
// builds up while ramping stays; use SYNCP when positions matter.
//
// AVEL counts whole qc per 20 ms (steps of 50 qc/s), and where within a
// qc the axis stands depends on what ran before: the speeds are printed
// to 1000 qc/s, the position to 100 qc.

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
SET SYNCFACTM 2          // gear 1 : 2 -> the slave runs at half the master speed
SET SYNCFACTS 1
ACC 200
DEC 200
VEL 100

PULSACC 20000            // lines/s^2: 1 s to reach the speed below
PULSVEL 20000            // 20000 lines/s = 80000 master qc/s
SYNCV
DELAY 2000
PRINT "master ", MAVEL, " qc/s  slave ", (AVEL rnd 1000) * 1000
SET SYNCFACTS 3          // 3:2 = 120000 qc/s at once (the gear can change while
                         // synchronised), but VEL 100 % allows only VELMAX
DELAY 2000
PRINT "master ", MAVEL, " qc/s  slave ", (AVEL rnd 1000) * 1000
MOTOR STOP               // leaves synchronisation with DEC
WAITAX
PRINT "slave stopped at ", (APOS rnd 100) * 100
