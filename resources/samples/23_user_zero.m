// Title: Machine zero and workpiece zero: DEFORIGIN, SETORIGIN, RSTORIGIN
// Shows: DEFORIGIN, SETORIGIN, RSTORIGIN, APOS, CPOS, SYSVAR 4097, GOSUB
// Run: motiontool run 23_user_zero.m --seconds 40
// Test-seconds: 40
// Expect: machine zero set: APOS 0
// Expect: fixture 1 hole 1: CPOS 2500, machine 6500
// Expect: fixture 1 hole 2: CPOS 5000, machine 9000
// Expect: fixture 1 hole 3: CPOS 7500, machine 11500
// Expect: fixture 2 hole 1: CPOS 2500, machine 23500
// Expect: fixture 2 hole 2: CPOS 5000, machine 26000
// Expect: fixture 2 hole 3: CPOS 7500, machine 28500
// Expect: parked at machine zero: CPOS 0, SYSVAR[4097] 0
// Expect-end: ended
//
// Two zero points make part programs reusable:
//  - DEFORIGIN takes the current actual position as the real (machine)
//    zero. Here the setter has jogged to a mark at 10000 qc first.
//  - SETORIGIN p puts a temporary zero at machine position p. Absolute
//    moves, APOS and CPOS then count from there, so the same drilling
//    pattern serves every fixture, whatever its place on the machine.
//    p is always a machine position: a second SETORIGIN does not add to
//    the first, and RSTORIGIN goes back to machine coordinates.
// SYSVAR[4097] shows the actual position in machine coordinates, so it
// is not affected by SETORIGIN.

VEL 60
ACC 60
DEC 60

RSTORIGIN                       // machine positions (an earlier program may have left a temporary zero)
POSA 10000                      // "jog" to the reference mark
DELAY 200                       // settle: DEFORIGIN takes APOS as it is
DEFORIGIN
PRINT "machine zero set: APOS ", APOS

fixture = 1
WHILE fixture <= 2 DO
    IF fixture == 1 THEN
        SETORIGIN 4000          // fixture 1 starts at machine 4000
    ELSE
        SETORIGIN 21000         // fixture 2 starts at machine 21000
    ENDIF
    GOSUB drill_pattern
    fixture++
ENDWHILE

RSTORIGIN                       // machine coordinates again
POSA 0
DELAY 200
PRINT "parked at machine zero: CPOS ", CPOS, ", SYSVAR[4097] ", SYSVAR[4097]

SUBMAINPROG
SUBPROG drill_pattern
    // Hole positions relative to the fixture: the same for every fixture.
    hole = 1
    WHILE hole <= 3 DO
        POSA (hole * 2500)
        DELAY 200               // drill (and let the axis settle)
        PRINT "fixture ", fixture, " hole ", hole, ": CPOS ", CPOS, ", machine ", SYSVAR[4097]
        hole++
    ENDWHILE
RETURN
ENDPROG
