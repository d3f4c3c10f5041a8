// C15 (syntax example 1) — ON PARAM 3267: react to a change of parameter 32-67 POSERR
// Source: C:2819-2823 (MCO 305 Command Reference)
// OCR repairs:
// - C:2823 the example stops after RETURN; the closing "ENDPROG" of the subprogram area is missing and was added
// - C:2819 heading "Syntax Example 1" (manual layout, not code) dropped
// Note: the subprogram name "poserr" equals the parameter code name POSERR used in "GET POSERR" (parameter names are not commands, so the name is kept).

ON PARAM 3267 GOSUB poserr // when position error is changed
SUBMAINPROG
SUBPROG poserr
PRINT "New position error: ", GET POSERR
RETURN
ENDPROG
