// Title: Skeleton of a machine program with an endless main loop
// Shows: program layout, #pragma NOIMPLICIT, long declarations, ON ERROR, ON INT, labels, GOTO, EXIT
// Run: motiontool run 28_program_skeleton.m --seconds 7 --input 2=0@0 --input 2=1@2500 --input 2=0@4500
// Test-inputs: 2=0@0 2=1@2500 2=0@4500
// Test-seconds: 7
// Expect: cycle 1 done at 1831 ms
// Expect: pause requested during cycle 2
// Expect: cycle 2 done at 3661 ms
// Expect: resumed at 4500 ms
// Expect: cycle 3 done at 6330 ms
// Expect-end: running
//
// Most machine programs share one layout: DIM first, then the
// interrupt definitions (so they hold for the whole run), then the
// one-time initialisation, then a main loop that never ends, and at the
// bottom the subprograms between SUBMAINPROG and ENDPROG. A machine
// program normally runs until the drive is switched off; EXIT is for
// the rare cases where it really must stop.
//
// #pragma NOIMPLICIT (directly after DIM) makes every variable need a
// declaration: a misspelt name is then a compile error instead of a
// silently created new variable.

DIM log[10]
#pragma NOIMPLICIT

long cycles, paused, fault, t0
t0 = TIME - 1                 // the start (TIME counts from power-up; line 1 runs at start + 1 ms)

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
ON ERROR GOSUB on_error
ON INT 2 GOSUB pause_request        // input 2: operator pause

// --- initialisation ---------------------------------------------------
VEL 70
ACC 70
DEC 70
cycles = 0
paused = 0
fault = 0

// --- main loop -----------------------------------------------------------
main:
    IF fault THEN
        PRINT "fault ", fault, ": stopping for good"
        EXIT
    ENDIF
    IF paused THEN
        WAITI 2 OFF                 // resume when the button is released
        PRINT "resumed at ", TIME - t0, " ms"
        paused = 0
    ENDIF
    POSA 15000
    POSA 0
    cycles++
    IF cycles <= 10 THEN
        log[cycles] = TIME - t0      // cycle end times for the Array Editor
    ENDIF
    PRINT "cycle ", cycles, " done at ", TIME - t0, " ms"
    GOTO main

// --- subprograms -------------------------------------------------------
SUBMAINPROG
SUBPROG pause_request
    paused = 1                      // the main loop pauses after this cycle
    PRINT "pause requested during cycle ", cycles + 1
RETURN

SUBPROG on_error
    fault = ERRNO
    ERRCLR
RETURN
ENDPROG
