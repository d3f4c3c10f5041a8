// Title: Application parameters on the LCP with LINKGPAR
// Shows: LINKGPAR, GET 1900, SET 1901, GET/SET KPROP, SAVE AXPARS (as a comment)
// Run: motiontool run 22_app_parameters.m --seconds 20 --set 1900=7500
// Test-settings: 1900=7500
// Test-seconds: 20
// Expect: feed length 7500 qc, batch 4
// Expect: piece 1 at 7500
// Expect: piece 2 at 15000
// Expect: piece 3 at 22500
// Expect: piece 4 at 30000
// Expect: KPROP 30 -> 45
// Expect-end: ended
//
// Machine operators should not need a PC to change a feed length.
// LINKGPAR gives an application parameter 19-00 ... 19-99 a name and
// limits and shows it on the drive's keypad (LCP); the program reads it
// with GET 1900 at the moment it needs the value, so a change made on
// the LCP takes effect with the next piece. Type 1 ("online") would
// apply a change while it is being typed; type 0 waits for [OK].
//
// A stored value outside the limits is pulled to the nearer limit when
// the parameter is linked. The program also writes a piece counter to
// 19-01, so the operator sees the progress on the LCP.

// An earlier program may have left the axis anywhere, still braking, and
// a temporary zero set (the controller keeps them): wait for the
// standstill (AXEND bit value 1), then count this program's positions
// from there, without touching the machine's zero and software limits
// (SETORIGIN is relative to the real zero, CR 3984-3999).
WHILE (AXEND & 1) == 0 DO
    DELAY 1
ENDWHILE
RSTORIGIN
SETORIGIN APOS
LINKGPAR 1900 "Feed length qc" 1000 40000 0
LINKGPAR 1901 "Pieces done" 0 1000000 0
LINKGPAR 1902 "Batch size" 1 100 0

IF GET 1902 < 2 THEN
    SET 1902 4                  // first run: a sensible batch size
ENDIF
SET 1901 0
PRINT "feed length ", GET 1900, " qc, batch ", GET 1902

VEL 60
ACC 60
DEC 60
WHILE GET 1901 < GET 1902 DO
    // Read the parameter for every piece. CPOS + length rather than
    // POSR: POSR counts from APOS, which still lags a little here.
    POSA (CPOS + GET 1900)
    SET 1901 (GET 1901 + 1)
    PRINT "piece ", GET 1901, " at ", CPOS
ENDWHILE

// Axis parameters (groups 32 and 33) are read and written the same way,
// by name. SET changes them only in RAM; SAVE AXPARS would make the
// change permanent (keep that for commissioning, EPROM wear is real).
old = GET KPROP
SET KPROP (old + old % 2)       // 50 % stiffer loop for this run only
PRINT "KPROP ", old, " -> ", GET KPROP
// SAVE AXPARS                  // uncomment to store the new KPROP
