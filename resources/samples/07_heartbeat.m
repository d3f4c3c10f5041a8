// Title: Heartbeat with ON PERIOD and a one-shot ON TIME
// Shows: ON PERIOD, ON TIME, OUT, SYSVAR, DISABLE/ENABLE, TIME
// Run: motiontool run 07_heartbeat.m --seconds 5
// Test-seconds: 5
// Expect: 502 ms: 5 beats, outputs 1
// Expect: 1002 ms: 5 beats, outputs 0
// Expect: 1502 ms: 5 beats, outputs 1
// Expect: 2003 ms: 5 beats, outputs 0
// Expect: heartbeat stopped after 20 beats
// Expect-end: ended
//
// A "heartbeat" output that blinks while the program is alive is a
// cheap way for a PLC to see that the motion program still runs.
// ON PERIOD calls a subprogram at a fixed rate, measured from start to
// start, so the blink does not drift when the handler takes longer one
// time. ON TIME fires once, after a delay: here it ends the heartbeat
// (ON PERIOD 0 switches the period off) after 2 s.
//
// The main program and the handler share the variable beats: a handler
// run between its read and clear would lose a beat. DISABLE PERIOD holds
// the handler back for those two lines; ENABLE PERIOD runs it late, not lost.

t0 = TIME - 1                 // the start (TIME counts from power-up; line 1 runs at start + 1 ms)
ON PERIOD 100 GOSUB beat      // every 100 ms
ON TIME 2000 GOSUB stop_beat  // once, 2 s from now

beats = 0
total = 0
running = 1
blink = 0
WHILE running DO
    DELAY 500
    DISABLE PERIOD
    seen = beats
    beats = 0
    ENABLE PERIOD
    total = total + seen
    // outputs 1-8 as one byte (SDO 0x2202 sub 0x0A); bit 1 = output 1
    PRINT TIME - t0, " ms: ", seen, " beats, outputs ", SYSVAR[0x0122020A]
ENDWHILE

PRINT "heartbeat stopped after ", total + beats, " beats"
OUT 1 0                       // leave the output in a defined state

SUBMAINPROG
SUBPROG beat
    beats = beats + 1
    blink = 1 - blink
    OUT 1 blink               // output 1 toggles: on, off, on, ...
RETURN

SUBPROG stop_beat
    ON PERIOD 0 GOSUB beat    // no more heartbeat
    running = 0
RETURN
ENDPROG
