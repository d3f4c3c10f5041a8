// C17 — ON STATBIT 30: clear the master-marker error flag
// Source: C:3057-3063 (MCO 305 Command Reference)
// OCR repairs: none
// (C:3057 heading "Syntax Example" in front of the first statement is manual layout and was dropped.)

ON STATBIT 30 GOSUB markererror /* Interrupt, if error flag Master */
SUBMAINPROG
SUBPROG markererror
SYNCSTATCLR 32 /* clear error flag SYNCMMERR */
/* use value 32 of Parameter SYNCSTATCLR, not the bit-number! */
RETURN
ENDPROG
