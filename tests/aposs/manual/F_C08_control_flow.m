// F_C08 — Control flow: GOSUB, GOTO with label, IF/ELSEIF/ELSE, IN as condition, LOOP, REPEAT/UNTIL
// Source: C:1443-1451 (GOSUB), C:1467-1470 (GOTO), C:1553-1567 (IF), C:1590-1595 (IN), C:2133-2136 (LOOP),
//         C:3629-3632 (REPEAT) (MCO 305 Command Reference); BREAK in loops D:6524-6528
// Kind: fragments made into one complete program. Scaffolding added:
//   - every placeholder "Command line 1 / command line n / command lines" replaced by a counter statement
//   - "a = 2", "b = 0", "A = 0" style initialisations; the GOTO loop is made finite ("IF (cnt < 3) THEN" around
//     "GOTO endless") so the program terminates; the manual's GOTO is unconditional
//   - the WHILE/REPEAT loops with BREAK (D:6528 describes BREAK in loops, no example survives)
//   - the subprogram area is moved to the end of the program
// OCR repairs:
// - C:3629 "/* start l oop */" -> "/* start loop */" (comment)
// - C:1443, 1467, 1553, 1590, 2133, 3629 headings "Syntax Example" (manual layout, not code) dropped
// Expected: calls = 1, cnt = 3, branch = 2, loops = 10, reps = 2, w = 3 ("a" and "A" are the same variable:
//   variable names are case-insensitive, D:6425, so the REPEAT loop runs twice)

calls = 0
GOSUB testup /* Call-up the subroutine testup */
cnt = 0
endless: /* label to be jumped to */
cnt = cnt + 1
IF (cnt < 3) THEN
GOTO endless /* jump command to label endless */
ENDIF
/* simple branch */
a = 2
b = 0
branch = 0
IF (a == 1) THEN /* Variable a = 1, then */
branch = 1
ENDIF
/* multiple branch */
IF (a == 1 AND b != 1) THEN
branch = 1
ELSEIF (a == 2 AND b != 1) THEN
branch = 2
ELSEIF (a == 3) THEN
branch = 3
ELSE
branch = 4
ENDIF
in4 = IN 4 /* store condition input 4 in variable in4 */
IF (IN 2) THEN /* if high level on terminal 2, set output 01 */
OUT 1 1
ELSE
OUT 1 0
ENDIF
loops = 0
next_in: /* jump to label */
loops = loops + 1
LOOP 9 next_in /* repeat loop contents 10 times */
reps = 0
A = 0
REPEAT /* start loop */
reps = reps + 1
a = reps
UNTIL (A != 1) /* Abort condition */
w = 0
WHILE (1) DO
w = w + 1
IF (w == 3) THEN
BREAK
ENDIF
ENDWHILE
REPEAT
BREAK
UNTIL 0
SUBMAINPROG /* Subroutine testup must be defined */
SUBPROG testup
calls = calls + 1
RETURN
ENDPROG
