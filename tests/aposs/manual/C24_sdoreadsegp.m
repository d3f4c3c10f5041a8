// C24 — SDOREADSEGP + SDOSTATE: segmented SDO read (packed, non-waiting) with polling
// Source: C:3777-3809 (MCO 305 Command Reference)
// OCR repairs: none
// (C:3777 heading "Example" is manual layout and was dropped.)
// Note: the function printpackedstring has no return statement (as in the manual; spec §3.6 / §10 item 8).

DIM test[20]
vltid = 3
// Routine to dump a packed string
// thereby each element contains max 4 characters
long printpackedstring (long[] arr, long len)
{
long ind,cc,rel
ind = 1
cc = 1
WHILE(cc <= len) DO
ind = ((cc-1) % 4) + 1
rel = ((cc-1) mod 4) + 1
PRINT chr(arr[ind].b rel);
cc++
ENDWHILE
PRINT " "
}
// Test of the segmented SDO packed without waiting
PRINT ""
PRINT "Segmented SDO with SdoReadSegP packed without waiting"
para = 1549
res = 0
value = SDOREADSEGP -vltid, (0x2000 + para), 0, test
WHILE(value == 0) DO
value = SDOSTATE vltid res
ENDWHILE
IF(value > 0) THEN
PRINT "Parameter ",para," has the length ",res
printpackedstring(test,res)
ELSE
PRINT "Read of ",para," failed - error ",value
ENDIF
