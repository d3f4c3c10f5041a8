// F_C22 — PRINT forms: text, trailing ";" (no line feed), variable, function value, mixed list
// Source: C:3528-3533 (MCO 305 Command Reference)
// Kind: fragment, already a valid statement sequence; nothing added.
// OCR repairs:
// - C:3528 heading "Syntax Example" (manual layout, not code) dropped

PRINT "Information is important !" /* print text information */
PRINT "Information is important !"; /* print information without line feed */
variable = 10
PRINT variable /* print contents of variables */
PRINT APOS /* print returned value function */
PRINT "Variable", variable,"Pos.:",APOS /* print mixed information */
