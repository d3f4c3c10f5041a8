// C1 — APOS after POSA, without and with a temporary zero (SETORIGIN)
// Source: C:228-240 (MCO 305 Command Reference, APOS)
// Kind: two fragments made into one program. Scaffolding added: none (the second example follows the first).
// OCR repairs:
// - C:238 typographic closing quote in PRINT "Actual Position”, APOS -> ASCII '"'
// - C:229, 235 the headings "Example:" / "Example with SETORIGIN" and the "Output:" blocks (C:231-233, 239-240) are
//   manual layout, not code, and were dropped
// Expected (C:231-240): "Actual Position Reached 2000" ("depending on PID settings a small deviation may occur"),
//   then "Actual Position 2000" — the axis is then at the real position 4000.

POSA 2000
PRINT "Actual Position Reached", APOS
SETORIGIN 2000
POSA 2000
PRINT "Actual Position", APOS
