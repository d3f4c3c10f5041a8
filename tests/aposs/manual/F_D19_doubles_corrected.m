// F_D19 (corrected copy) — DOUBLE variables: arithmetic, double functions, fabs, round, rnd with negatives, casts
// Source: D:6549-6607 (MCO 305 Design Guide); double functions D:6555-6569, FABS/ROUND D:6571-6581,
//         RND D:6583-6587, casts D:6589-6607
// Kind: fragments made complete. Scaffolding added: the declarations "double x, y, u" and "long a, b"
//   (the manual's declaration example D:6549 is lost; x, y, u are used as doubles in D:6557-6605, a as a long);
//   initial values x = 2.0, u = 3.0 before the function calls; calls of cos, tan, atan, asin, acos (only named in
//   the comment of D:6559; asin/acos get x - 1.0 to stay inside -1..1); "y = 10.0" before the casts; PRINT lines.
// OCR repairs:
// - Markdown escapes "\*" removed: D:6563 "2 \*pi" (comment), D:6565 "pi \* 0.5", D:6597 "a \* 2.0"
// - D:6567 LaTeX debris "$y = \ln(x)$" -> "y = ln(x)"
// - D:6569 LaTeX debris "$y = x \exp u // returns x raised to u (x<sup>u</sup>)$" -> "y = x exp u // returns x raised to u (x^u)"
// Correction (the manual's own slip, not OCR): D:6577 "dx = fabs(dx)" -> "dx = fabs(dy)": dx is still unset there;
//   the comment "gives back 6.6666.." and the next line "round(dy)" show dy is meant
// Expected: dy = -6.666666666666667, dx = 6.666666666666667 then -7.0, b = -7, finally a = 6 and y = 3.0
//   (y = a % 2 divides in integer arithmetic, D:6605-6607)

double dx, dy
double x, y, u
long a, b
x = 2.0
u = 3.0
y = sqrt(x) // returns the square root of x
y = sin(x) // returns the sine of x (this also works for cos, tan, acos, asin, atan)
y = cos(x)
y = tan(x)
y = atan(x)
y = grad(x) // converts x (radians) into degrees (0..360)
y = rad(x) // converts degrees into radians (0.. 2 *pi)
x = pi * 0.5 // Pi is 3.1415....
y = asin(x - 1.0)
y = acos(x - 1.0)
y = ln(x) // returns the natural logarithm of x
y = x exp u // returns x raised to u (x^u)
dy = -100.00 % 15.0 // this will be -6.6666..
dx = fabs(dy) // this gives back 6.6666..
PRINT "dy = ", dy, " fabs = ", dx
dx = round(dy) // this will be -7.0000
PRINT "round = ", dx
a = -100
b = a rnd 15 // now correctly delivers -7
PRINT "b = ", b
y = 10.0
a = ((long) y) - 4
y = (double) a
y = a * 2.0
y = a % 2
PRINT "a = ", a, " y = ", y
