// C14 — ON KEYPRESSED: print the LCP key codes
// Source: C:2764-2773 (MCO 305 Command Reference)
// OCR repairs: none
// (C:2764 heading "Syntax Example" in front of the first statement is manual layout and was dropped.)

ON KEYPRESSED GOSUB keyhandler
WHILE(1) DO // endless loop
ENDWHILE
////////////////////////////////////
SUBMAINPROG
SUBPROG keyhandler
key = INKEY(-1) // don't wait for key
PRINT key
RETURN
ENDPROG
