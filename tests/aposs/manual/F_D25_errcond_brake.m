// F_D25 — Brake output with ERRCOND 1: error handler waits for input 1, clears the error, resets the brake output
// Source: D:10580 (MCO 305 Design Guide)
// Kind: fragment made complete. Scaffolding added: SUBMAINPROG/ENDPROG around the handler and the main loop
//   "mainloop: / GOTO mainloop" in place of the comment "// Main program loop".
// OCR repairs:
// - D:10580 the whole example is flattened into one line; split into one statement per line
// - D:10580 Markdown escape "err\_handle" -> "err_handle" (twice)
// Note: "WAITI 1" is written without the state argument (spec §7.2).

ON ERROR GOSUB err_handle // p. 33-66 O4 is set to [6]
SET ERRCOND 1
// Main program loop
mainloop:
GOTO mainloop
SUBMAINPROG
SUBPROG err_handle
WAITI 1
ERRCLR
OUT 4 1
RETURN
ENDPROG
