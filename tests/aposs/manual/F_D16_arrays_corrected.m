// F_D16 (corrected copy) — DIM arrays: several DIM lines, reading/writing elements, a two-dimensional array filled in nested loops
// Source: D:6443-6451 (DIM samples), D:6510 (reading/writing), D:6457 + D:6465-6474 (2-D array, D17)
//         (MCO 305 Design Guide)
// Kind: fragments made into one complete program. Scaffolding added:
//   - the DIM lines are the DIM of D:6451 plus "DIM test[10][100]" (D:6457); the first program of D:6443 uses other
//     names for the same array positions and is not repeated
//   - PRINT line at the end
// OCR repairs:
// - D:6510 the sample is flattened into one paragraph; split into one statement per line
// - D:6510 "xpos [1]", "ypos [i]", "zpos [1]", "offs [1]" with a blank before "[" -> "xpos[1]" etc. (a blank would
//   split "POSA xpos [1]" into two arguments)
// - D:6510 Markdown escape "i\*1000" -> "i*1000"
// - D:6474 "ENDWHILE</pre>" HTML debris removed
// Not repaired (manual content): the 2-D fill never resets col, so only row 1 is filled (spec §10 item 16).
// Expected: offs[1] = 1000, ypos[19] = 19000, test[1][100] = 100, lin = 11, col = 101
// Correction (the manual's own slip, not OCR): D:6465-6474 never resets "col", so only row 1 is filled; this
//   copy adds "col = 1" after "lin++".

DIM xpos[20], ypos[20], zpos[20], offs[50]
DIM test[10][100]
xpos[1] = 10000
xpos[2] = 20000
xpos[3] = 30000
i = 1
WHILE (i<20) DO
ypos[i] = i*1000
i = i+1
ENDWHILE
zpos[1] = APOS
POSA xpos[1]
offs[1] = (xpos[2]) % 20
lin = 1
col = 1
value = 1
WHILE(lin <= 10) do
    WHILE(col <= 100) do
        test[lin][col++] = value++
        ENDWHILE
        lin++
        col = 1
ENDWHILE
PRINT "offs[1] = ", offs[1], " test[1][100] = ", test[1][100]
