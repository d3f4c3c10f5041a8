// C18 — ON TIME: switch a light off again 200 ms later
// Source: C:3085-3091 (MCO 305 Command Reference)
// OCR repairs: none
// (C:3085 heading "Syntax Example" in front of the first statement is manual layout and was dropped.)

OUT 1 1 /* light on */
ON TIME 200 GOSUB off1 /* light off again after 200 ms */
SUBMAINPROG
SUBPROG off1
OUT 1 0
RETURN
ENDPROG
