// C7 (corrected copy) — ENCTGWRITE/ENCTGREAD: read the absolute position with raw RS485 (Hiperface) telegrams
// Source: C:1248-1278 (MCO 305 Command Reference)
// OCR repairs:
// - C:1248 heading "Program Sample" (manual layout, not code) dropped
// Correction (the manual's own slip, not OCR): C:1254 "SET ENCODEABSRES" -> "SET ENCODERABSRES" (32-03)

// Example program to receive absolute position
DIM sendbuffer[20]
#define HIPER_READ_POS 0x42
SET ENCODERTYPE 0 // no incremental encoder is connected
SET ENCODERABSTYPE 1 // hiperface encoder
SET ENCODERABSRES 4096 // hiperface resolution
DELAY 1000
pos = 0
WHILE(1) DO
sendbuffer[1] = HIPER_READ_POS
retval = ENCTGWRITE 1 sendbuffer // send telegram
DELAY 1000
retval = ENCTGREAD sendbuffer // receive answer
// check if correct amount of bytes has been received
IF(retval == 7) then // 0x40 0x42 pos0 pos1 pos2 pos3 crc
pos.b4 = sendbuffer[3]
pos.b3 = sendbuffer[4]
pos.b2 = sendbuffer[5]
pos.b1 = sendbuffer[6]
PRINT "Pos = ", pos
ELSE
PRINT "-------- Transmission error ------------: ", retval
PRINT "1: ", sendbuffer[1]
PRINT "2: ", sendbuffer[2]
PRINT "3: ", sendbuffer[3]
PRINT "4: ", sendbuffer[4]
EXIT
ENDIF
DELAY 500
ENDWHILE
