// F_D18 — Whole-array copy "test[] = field[]" between arrays of different size
// Source: D:6482-6486 (MCO 305 Design Guide)
// Kind: fragment made complete. Scaffolding added: the DIM line (D:6484, printed after the copy in the manual) is
//   moved to the top; field is filled before the copy; PRINT line.
// OCR repairs: none
// Expected: test[1] = 1, test[100] = 100 (only the first 100 elements of field are copied)

DIM test[100], field[200]
i = 1
WHILE (i <= 200) DO
field[i] = i
i = i + 1
ENDWHILE
test[] = field[]
PRINT "test[1] = ", test[1], " test[100] = ", test[100]
