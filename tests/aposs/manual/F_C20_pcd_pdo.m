// F_C20 — PCD[] and PDO[] pseudo-arrays with bit and byte suffixes (read, write, bit assignment, conditions)
// Source: C:3287-3293 (PCD), C:3398-3404 (PDO) (MCO 305 Command Reference)
// Kind: fragments made complete. Scaffolding added: ENDIF lines and one statement in each IF body (the manual's IF lines are cut off after THEN).
// OCR repairs:
// - C:3292 "_IF (PCD[2]= = 256) THEN" -> "IF (PCD[2] == 256) THEN" (stray "_", "= =" -> "==")
// - C:3293 "_IF (PCD[3].2) THEN" -> "IF (PCD[3].2) THEN"
// - C:3403-3404 "PDO [1]", "PDO [2]" with a blank before "[" -> "PDO[1]", "PDO[2]"
// - C:3287, 3292, 3398, 3403 headings "Syntax Example" / "Program Sample" (manual layout, not code) dropped

Variable = PCD[1] // Word 1
Variable = PCD[1].2 // Bit 2 of Word 1
Variable = PCD[2].b1 // Byte 1 of Word 2
PCD[1] = Variable
PCD[1].3 = Variable
IF (PCD[2] == 256) THEN // compare value
OUT 1 1
ENDIF
IF (PCD[3].2) THEN // is bit 2 of PCD3 high?
OUT 2 1
ENDIF
Variable = PDO[1] // PDO data byte 1 - 4
Variable = PDO[1].2 // Bit 2 of PDO data byte 1 - 4
Variable = PDO[2].b1 // Byte 1 of PDO data byte 5 - 8
PDO[1] = Variable
PDO[1].3 = Variable
IF (PDO[1] ==256) THEN // compare value
OUT 3 1
ENDIF
IF (PDO[2].2) THEN // Is Bit 1 of PDO data byte 5 - 8 high?
OUT 4 1
ENDIF
