// F_C13 — ON ERROR and ON INT (positive and negative edge) skeletons
// Source: C:2667-2673 (ON ERROR), C:2737-2749 (ON INT) (MCO 305 Command Reference)
// Kind: two skeletons made into one complete program. Scaffolding added: the placeholders "command line(s) 1 … n"
//   replaced by OUT statements / an endless main loop; one subprogram area for all three handlers.
// OCR repairs:
// - C:2738 typographic en dash "ON INT –5" -> "ON INT -5"
// - C:2667, 2737 headings "Syntax Example" (manual layout, not code) dropped

ON ERROR GOSUB errhandle /* definition of an error subroutine */
ON INT 4 GOSUB posin /* Definition of Input 4 (positive edge) */
ON INT -5 GOSUB negin /* Definition of input 5 (negative edge) */
mainloop:
GOTO mainloop
SUBMAINPROG /* subroutine errhandle must be defined */
SUBPROG errhandle
ERRCLR
RETURN
SUBPROG posin
OUT 1 1
RETURN
SUBPROG negin
OUT 1 0
RETURN
ENDPROG
