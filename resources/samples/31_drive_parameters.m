// Title: Reading and changing FC 300 drive parameters with GETVLT and SETVLT
// Shows: GETVLT, GETVLTSUB, SETVLT, conversion index, operating data (menu 16), CVEL, CSTART
// Run: motiontool run 31_drive_parameters.m --seconds 5
// Test-seconds: 5
// Expect: motor current 1-24: 820 (x 0.01 A)
// Expect: speed high limit 4-13: 1500 RPM
// Expect: relay 1 function 5-40[0]: 51
// Expect: max. reference 3-03: 1500000 -> 60000
// Expect: running: 250 (x 0.1 Hz), 750 RPM
// Expect: stopped: 0 (x 0.1 Hz)
// Expect-warnings: GETVLT GETVLTSUB SETVLT
// Expect-end: ended
//
// The MCO 305 sits in an FC 300 frequency converter and can read and
// write the drive's own parameters: GETVLT takes the LCP number without
// the dash (4-13 -> 413), GETVLTSUB also an index for array parameters
// such as 5-40. Only integers cross, so a value comes scaled by its
// conversion index: 16-13 "Frequency" 50.0 Hz (index -1) reads 500,
// 1-24 "Motor Current" 8.20 A (index -2) reads 820.
//
// SETVLT changes a parameter in the drive's RAM only: after a power
// cycle the drive has its old value again. A program that needs a
// different setting writes it at every start, as this one does.

PRINT "motor current 1-24: ", GETVLT 124, " (x 0.01 A)"
PRINT "speed high limit 4-13: ", GETVLT 413, " RPM"
PRINT "relay 1 function 5-40[0]: ", GETVLTSUB 540 0
old = GETVLT 303
SETVLT 303 60000                // 3-03 "Maximum Reference" = 60.000 (index -3)
PRINT "max. reference 3-03: ", old, " -> ", GETVLT 303

VEL 100
ACC 100
CVEL 50
CSTART
DELAY 2000
PRINT "running: ", GETVLT 1613, " (x 0.1 Hz), ", (GETVLT 1617 rnd 10) * 10, " RPM"   // to 10 RPM: 16-17 follows the measured speed
CSTOP
WAITAX
DELAY 100                       // 16-13 follows the motor, not the command
PRINT "stopped: ", GETVLT 1613, " (x 0.1 Hz)"
