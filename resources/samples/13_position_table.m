// Title: A table of target positions driven in sequence
// Shows: DIM, array indexing, WHILE, POSA, DELAY, OUT, ++
// Run: motiontool run 13_position_table.m --seconds 20
// Test-seconds: 20
// Expect: table initialised
// Expect: station 1 at 4000, cycle 611 ms
// Expect: station 2 at 12500, cycle 844 ms
// Expect: station 3 at 21000, cycle 844 ms
// Expect: station 4 at 9000, cycle 984 ms
// Expect: station 5 at 30000, cycle 1270 ms
// Expect: parked
// Expect-end: ended
//
// A pick-and-place axis serves five stations. Their positions live in
// a DIM array instead of being written into the code: DIM arrays are
// kept in the controller's array memory, can be edited in the Array
// Editor (or saved with SAVE ARRAYS) and survive a new download, so a
// machine setter can retune a station without touching the program.
//
// The program fills the table only when it is still empty (a fresh
// controller), so values entered by hand are not overwritten.
// Array indexes start at 1; an index outside 1..n raises error 171.

DIM station[5]

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
IF station[1] == 0 AND station[5] == 0 THEN
    station[1] = 4000
    station[2] = 12500
    station[3] = 21000
    station[4] = 9000          // stations need not be in order
    station[5] = 30000
    PRINT "table initialised"
ENDIF

VEL 70
ACC 60
DEC 60
i = 1
WHILE i <= 5 DO
    t0 = TIME
    POSA station[i]
    OUT 4 1                    // gripper: pick or place
    DELAY 100
    OUT 4 0
    PRINT "station ", i, " at ", station[i], ", cycle ", TIME - t0, " ms"
    i++
ENDWHILE

POSA 0
PRINT "parked"
