// Title: Waiting for a key on the FC 300 keypad with INKEY
// Shows: INKEY 0, INKEY n (timeout), INKEY (-1) (polling), key codes, TIME
// Run: motiontool run 32_lcp_keys.m --seconds 5
// Test-seconds: 5
// Expect: keypad emptied (0 old keys)
// Expect: press a key within 2 s for set-up mode
// Expect: no key after 2001 ms: automatic mode
// Expect-warnings: INKEY
// Expect-end: ended
//
// INKEY reads one key code from the drive's LCP keypad: INKEY 0 waits
// for a key for ever, INKEY n waits at most n ms, and INKEY (-1) does not
// wait at all (a negative argument must be in brackets). Without a key it
// returns -1. Keys pressed together send the sum of their codes, and a
// held key is sent again and again, so a program reads until -1 to empty
// the keypad before it waits for a new key.
//
// Here an operator has 2 s to press a key for set-up mode; without one
// the machine starts in automatic mode. In the simulator nobody presses
// a key (a host can, with press_key), so the program takes the -1 path.
// On a real drive the keys keep their FC 300 function unless par. 0-4*
// disables them.

t0 = TIME - 1
flushed = 0
REPEAT                          // empty the keypad: old keys are not a choice
    key = INKEY (-1)
    IF key != -1 THEN
        flushed = flushed + 1
    ENDIF
UNTIL key == -1
PRINT "keypad emptied (", flushed, " old keys)"

PRINT "press a key within 2 s for set-up mode"
key = INKEY 2000
IF key == -1 THEN
    PRINT "no key after ", TIME - t0, " ms: automatic mode"
ELSE
    PRINT "key code ", key, ": set-up mode"
ENDIF
