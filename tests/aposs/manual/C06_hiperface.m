// C6 — ENCPOSOFFS: sync the incremental counter of a Hiperface encoder to its absolute position
// Source: C:1206-1223 (MCO 305 Command Reference)
// OCR repairs:
// - C:1206 heading "Program Sample" (manual layout, not code) dropped
// Not repaired (the manual's own slip, see the corrected copy): C:1210 "SET ENCODEABSRES" misspells 32-03
//   ENCODERABSRES; `motiontool check` reports the unknown parameter.

MOTOR OFF
SET ENCODERTYPE 0 // no incremental encoder is connected
SET ENCODERABSTYPE 1 // Hiperface encoder
SET ENCODEABSRES 4096 // Hiperface resolution
DELAY 1000
pos = 0
RSTORIGIN
offset = 0
PRINT "apos before: ", apos
retval = ENCPOSOFFS offset
PRINT "encposoffs returned: ", retval, " offset is: ", offset
SETORIGIN -offset
PRINT "apos afterwards: ", apos
WHILE(1) DO
PRINT apos // print incremental position
DELAY 500
ENDWHILE
