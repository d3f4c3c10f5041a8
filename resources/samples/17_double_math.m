// Title: DOUBLE arithmetic: a crank-slider table
// Shows: double, sqrt, sin, cos, rad, round, fabs, exp, pi, (long)/(double) casts, %
// Run: motiontool run 17_double_math.m --seconds 10
// Test-seconds: 10
// Expect: 7 % 2 = 3,  7.0 % 2 = 3.5,  7 mod 2 = 1
// Expect: pi = 3.141593, 2 exp 10 = 1024.0
// Expect: crank 0 deg: stroke 0.0 mm, target 0 qc
// Expect: crank 45 deg: stroke 14.41 mm, target 5764 qc
// Expect: crank 90 deg: stroke 45.43 mm, target 18172 qc
// Expect: crank 135 deg: stroke 70.98 mm, target 28392 qc
// Expect: crank 180 deg: stroke 80.0 mm, target 32000 qc
// Expect: fabs(-2.5) = 2.5, round(-2.5) = -3.0, (long) -2.5 = -2
// Expect-end: ended
//
// A servo drives a slider through a crank. For a crank angle a the
// slider stands at  x = r*cos(a) + sqrt(l*l - (r*sin(a)) exp 2).
// Such geometry needs floating point: DOUBLE variables must be
// declared, LONG ones may appear by assignment.
//
// Three traps worth knowing:
//  - '%' is the DIVISION operator; 'mod' gives the remainder.
//  - Integer operands stay integer: 7 % 2 is 3, even when the result
//    goes into a DOUBLE. Write 7.0 % 2 (or cast) to divide exactly.
//  - sin/cos take radians; rad() converts from degrees. The controller
//    computes them with 32-bit precision, so round before comparing.

double r, l, a, x, x0
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
r = 40.0                         // crank radius, mm
l = 150.0                        // connecting rod, mm
x0 = r + l                       // slider at crank angle 0 (top)

PRINT "7 % 2 = ", 7 % 2, ",  7.0 % 2 = ", 7.0 % 2, ",  7 mod 2 = ", 7 mod 2
PRINT "pi = ", pi, ", 2 exp 10 = ", 2 exp 10

VEL 50
ACC 50
DEC 50
deg = 0
WHILE deg <= 180 DO
    a = rad((double) deg)
    x = r * cos(a) + sqrt(l * l - (r * sin(a)) exp 2)
    stroke = (long) round((x0 - x) * 100.0)   // 1/100 mm, as LONG
    POSA (stroke * 4)                         // 4 qc per 1/100 mm
    PRINT "crank ", deg, " deg: stroke ", round((x0 - x) * 100.0) % 100.0, " mm, target ", CPOS, " qc"
    deg = deg + 45
ENDWHILE

// fabs and round return DOUBLE, the casts make a LONG of them.
x = -2.5
PRINT "fabs(-2.5) = ", fabs(x), ", round(-2.5) = ", round(x), ", (long) -2.5 = ", (long) x
