// Title: Touch probe: stop a fixed distance after a sensor edge
// Shows: ON INT, CVEL, CSTART, POSR, WAITAX, SUBMAINPROG, SUBPROG
// Run: motiontool run 06_touch_probe.m --seconds 10 --input 4=0@0 --input 4=1@1200 --input 4=0@1300
// Test-inputs: 4=0@0 4=1@1200 4=0@1300
// Test-seconds: 10
// Expect: searching ...
// Expect: edge at 19797, stopped at 22794
// Expect: distance after the edge: 2997
// Expect-end: ended
//
// A label sensor on input 4 sees the leading edge of a product while
// the conveyor runs in speed mode. The product must stop exactly
// 3000 qc after that edge, wherever the edge happens to be.
//
// ON INT 4 calls the handler on the rising edge within about 2 ms, much
// more precise than polling IN 4 from the main loop. In the handler we
// remember APOS (the probe point) and issue POSR: the relative move
// starts from there and replaces speed mode. NOWAIT is always on inside
// an interrupt handler, so WAITAX is needed if the handler must not
// return before the target is reached.

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
ON INT 4 GOSUB probe          // rising edge of input 4

// The braking distance v*v/(2*DEC) must fit into the 3000 qc, otherwise
// the set-point overshoots the target and comes back. At 20 % speed and
// DEC 100 it is about 2050 qc.
ACC 50
DEC 100
VEL 20                        // the POSR in the handler uses this speed
found = 0

CVEL 20
CSTART
PRINT "searching ..."
WHILE found == 0 DO
    DELAY 5
ENDWHILE
DELAY 100                     // let the position loop settle
PRINT "edge at ", edge, ", stopped at ", APOS
PRINT "distance after the edge: ", APOS - edge

SUBMAINPROG
SUBPROG probe
    edge = APOS               // read first: the axis keeps moving
    POSR 3000                 // ends speed mode, target = here + 3000
    WAITAX                    // handlers never wait by themselves
    found = 1
RETURN
ENDPROG
