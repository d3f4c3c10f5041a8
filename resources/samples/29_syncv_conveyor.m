// Title: Conveyor following a virtual master with velocity synchronisation
// Shows: PULSVEL, PULSACC, SYNCFACTM, SYNCFACTS, SYNCV, MAVEL, AVEL, MOTOR STOP
// Run: motiontool run 29_syncv_conveyor.m --seconds 10
// Test-seconds: 10
// Expect: master 80000 qc/s  slave 39950
// Expect: master 80000 qc/s  slave 102400
// Expect: slave stopped at 280420
// Expect-end: ended
//
// Without an external master encoder the MCO's encoder simulation (the
// virtual master) drives the master input: PULSVEL sets its frequency in
// encoder lines per second (one line = 4 qc), PULSACC the ramp to it.
// SYNCV then makes the slave run at master velocity × SYNCFACTS/SYNCFACTM.
// Speed synchronisation only matches velocities: a position offset that
// builds up while ramping stays; use SYNCP when positions matter.

SET SYNCFACTM 2          // gear 1 : 2 -> the slave runs at half the master speed
SET SYNCFACTS 1
ACC 200
DEC 200
VEL 100

PULSACC 20000            // lines/s^2: 1 s to reach the speed below
PULSVEL 20000            // 20000 lines/s = 80000 master qc/s
SYNCV
DELAY 2000
PRINT "master ", MAVEL, " qc/s  slave ", AVEL
SET SYNCFACTS 3          // 3:2 = 120000 qc/s at once (the gear can change while
                         // synchronised), but VEL 100 % allows only VELMAX
DELAY 2000
PRINT "master ", MAVEL, " qc/s  slave ", AVEL
MOTOR STOP               // leaves synchronisation with DEC
WAITAX
PRINT "slave stopped at ", APOS
