// F_C21 — Software PID filter: SET PID factors, INAD, PID, PRINT
// Source: C:3424-3433 (MCO 305 Command Reference)
// Kind: fragment, already a valid statement sequence; nothing added.
// OCR repairs:
// - C:3431 heading "Syntax Example" (manual layout, not code) dropped; the prose line C:3429 between the SET lines
//   and the example is not code and was dropped

SET PID KPROP 1 /* set KP 1 */
SET PID KDER 1 /* set KD 1 */
SET PID KINT 0 /* set KI 0 */
SET PID KILIM 0 /* Integration limit 0 */
SET PID TIMER 1 /* Sample time = 1 */
e = INAD 53
u = PID e
PRINT "input = ",e, "output = ",u
