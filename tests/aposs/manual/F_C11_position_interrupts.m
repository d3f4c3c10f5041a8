// F_C11 — Position interrupts: ON ±APOS/IPOS/MAPOS/MIPOS/MCPOS ... GOSUB, re-routing, ON DELETE ... GOSUB,
//         background outputs ON ±ipos ... SETOUT [TOIN], ON DELETE ... SETOUT
// Source: C:2567-2576 + C:2591-2594 (C11, ON DELETE / re-routing), C:2954-2984 (C16, position interrupts),
//         C:2621-2628 + C:3011-3013 (C12, SETOUT) (MCO 305 Command Reference)
// Kind: fragments made into one complete program. Scaffolding added:
//   - the placeholder subprogram name "name" (C:2954, C:2963) replaced by "passneg" / "passmapos"
//   - the "…" / "(program)" placeholders dropped; SET SYNCMPULSS appears once
//   - SUBMAINPROG ... ENDPROG with minimal handlers hitinfo, hitzero, hitposdir, prog1, prog2, passneg, passmapos;
//     C16 example 5 puts its subprogram area (SUBPROG output) before the ON statement — kept in that order, so the
//     whole subprogram area comes first (layout 2 of spec §3.1)
//   - "DEFMCPOS 0" before ON +MCPOS (MCPOS interrupts need DEFMCPOS or SETCURVE first, spec §6.1)
//   - the endless main loop "mainloop: / GOTO mainloop", with the ON DELETE ... SETOUT lines of C12 under "IF (IN 8)"
//   - at most 20 position interrupts are alive at any time (limit, spec §6.1)
// OCR repairs:
// - C:2567-2594 typographic en dash "–" used as minus sign ("ON – APOS 20000") -> ASCII "-"
// - C:2567, 2591, 2621, 2954-2965, 3011 headings "Syntax Example n" (manual layout, not code) dropped

SUBMAINPROG // set subprogram output
SUBPROG output
OUT 3 1 // 03 on
RETURN
SUBPROG hitinfo
OUT 2 1
RETURN
SUBPROG hitzero
OUT 2 0
RETURN
SUBPROG hitposdir
OUT 4 1
RETURN
SUBPROG prog1
OUT 5 1
RETURN
SUBPROG prog2
OUT 5 0
RETURN
SUBPROG passneg
OUT 6 1
RETURN
SUBPROG passmapos
OUT 6 0
RETURN
ENDPROG
ON - APOS 20000 GOSUB hitinfo // Interrupt #1
ON - APOS 10000 GOSUB hitinfo // Interrupt #2
ON + APOS 10000 GOSUB hitinfo // Interrupt #3
ON + APOS 0 GOSUB hitzero // Interrupt #4
ON - APOS 0 GOSUB hitzero // Interrupt #5
ON INT 3 GOSUB hitinfo // Interrupt #6
ON DELETE 0 GOSUB hitinfo
ON + APOS 99999 GOSUB hitinfo // New defined position interrupt
ON - APOS 10000 GOSUB hitinfo // Interrupt #1
ON + APOS 10000 GOSUB hitinfo // Interrupt #2
ON + APOS 10000 GOSUB hitposdir // Re-routed interrupt #2
ON -apos 800 GOSUB passneg
// Call up the subroutine name when slave position 800
// is passed in negative direction
SET SYNCMPULSS 20000 // distance between two markers
ON +ipos 5000 GOSUB prog1
ON +ipos 15000 GOSUB prog2
ON +mapos 1200 GOSUB passmapos
// Always call up subprogram at position 1200
SET SYNCMPULSM 20000 // distance between two markers
ON +mipos 5000 GOSUB prog1
ON +mipos 15000 GOSUB prog2
DEFMCPOS 0
ON +MCPOS 4500 GOSUB output
// call subprogram output always on position 4500
ON +ipos 500 SETOUT 1
ON +ipos 1000 SETOUT -1
on +ipos 500 setout 1 toin 2
on +ipos 1000 setout -1
mainloop:
IF (IN 8) THEN
ON DELETE 0 SETOUT 1
ON DELETE 0 SETOUT -1
ENDIF
GOTO mainloop
