// C5 — DEFORIGIN: the actual position becomes the zero point
// Source: C:873-880 (MCO 305 Command Reference, DEFORIGIN sample)
// OCR repairs:
// - C:876-877 the second PRINT is broken after its comma ("PRINT "Position after defining new origin"," / "APOS")
//   by the page's column layout; joined into one line
// - C:878-880 the "Output" block (with a stray "," after 2000) is manual layout, not code, and was dropped
// Expected (C:878-880): "Position before new origin 2000", "Position after defining new origin 0".

POSA 2000
PRINT "Position before new origin", APOS
DEFORIGIN
PRINT "Position after defining new origin", APOS
