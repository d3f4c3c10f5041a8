// Title: Speed set-point from an analog input
// Shows: INAD, CVEL, CSTART, CSTOP, abs, rnd, dead band, ON PERIOD, IN
// Run: motiontool run 25_analog_speed.m --seconds 10 --input 1=0@0 --input 53=500@0 --input 53=-250@1500 --input 53=15@3000 --input 53=1000@4000 --input 1=1@5500
// Test-inputs: 1=0@0 53=500@0 53=-250@1500 53=15@3000 53=1000@4000 1=1@5500
// Test-seconds: 10
// Expect: 1 ms: INAD 0 -> CVEL 0
// Expect: 52 ms: INAD 500 -> CVEL 30
// Expect: 1502 ms: INAD -250 -> CVEL -15
// Expect: 3002 ms: INAD 15 -> CVEL 0
// Expect: 4002 ms: INAD 1000 -> CVEL 60
// Expect: stop button: mixer stopped
// Expect-end: ended
//
// A potentiometer on analog input 53 sets the speed of a mixer.
// INAD 53 reads -1000 ... 1000 for -10 V ... +10 V. Two details make
// such a set-point usable:
//  - a dead band around zero, because a real potentiometer never
//    reads exactly 0 V and the mixer would creep;
//  - a limit, so a wiring fault (full 10 V) cannot over-speed the load.
// The set-point is refreshed by ON PERIOD every 50 ms; the main program
// only watches the stop button on input 1.

#define DEAD_BAND 20                // +-0.2 V counts as zero
#define MAX_SPEED 60                // % of VELMAX

t0 = TIME - 1                 // the start (TIME counts from power-up; line 1 runs at start + 1 ms)
ON PERIOD 50 GOSUB follow_pot
ACC 50
DEC 50
speed = 0
raw = 0
CVEL 0
CSTART

last = -999
WHILE IN 1 == 0 DO
    IF speed != last THEN
        PRINT TIME - t0, " ms: INAD ", raw, " -> CVEL ", speed
        last = speed
    ENDIF
    DELAY 10
ENDWHILE
ON PERIOD 0 GOSUB follow_pot
CSTOP
WAITAX                              // the mixer has stopped when it stands, not when told to
PRINT "stop button: mixer stopped"

SUBMAINPROG
SUBPROG follow_pot
    raw = INAD 53
    IF abs(raw) < DEAD_BAND THEN
        wanted = 0
    ELSE
        wanted = (raw * MAX_SPEED) rnd 1000  // scale to +-MAX_SPEED
    ENDIF
    IF wanted != speed THEN
        speed = wanted
        CVEL speed                  // applied at once in speed mode
    ENDIF
RETURN
ENDPROG
