// C23 — SDOREADSEG: segmented SDO read (unpacked, waiting) printed by a helper function
// Source: C:3731-3751 (MCO 305 Command Reference)
// OCR repairs: none
// (C:3731 heading "Example" in front of the DIM statement is manual layout and was dropped.)
// Note: the function printstring has no return statement (as in the manual; spec §3.6 / §10 item 8).

DIM test[20]
id = 3
// Routine to read a string
// thereby the array contains only one character per element
long printstring (long[] arr, long len)
{
long ind
ind = 1
WHILE(ind <= len) DO
PRINT chr(arr[ind]);
ind++
ENDWHILE
PRINT " "
}
// Test segmented SDO unpacked with waiting
PRINT ""
PRINT "Test segmented SDO unpacked with waiting "
subindex = 1549 // Sw Version
value = SDOREADSEG id, 0x2000, subindex, test
PRINT "number characters ",value
printstring(test,value)
