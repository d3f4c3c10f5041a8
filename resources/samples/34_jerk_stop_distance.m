// Title: Stopping at a mark with a jerk-limited ramp: JERKSTOPDIST and JERKFINVEL
// Shows: JERKSTOPDIST, JERKFINVEL, SET RAMPTYPE, CVEL, CSTART, CSTOP, CPOS, APOS, AVEL
// Run: motiontool run 34_jerk_stop_distance.m --seconds 10 --set JERKMIN=200
// Test-settings: JERKMIN=200
// Test-seconds: 10
// Expect: after 300 ms: AVEL 10650 qc/s, would end at 15 % of VELMAX
// Expect: stop at 330383 with a stop distance of 69632
// Expect: stopped at 400015, 15 qc from the mark
// Expect-end: ended
//
// A conveyor runs in speed mode and must stop with its front edge at a
// mark, smoothly (RAMPTYPE 2, limited jerk). With a jerk limit the stop
// ramp is not a simple v^2/2a: JERKSTOPDIST dec says how far a RAMPTYPE 2
// stop with deceleration dec (in % like DEC) would go from the present
// motion, whatever ramp type is running. The program watches
// CPOS + stop distance and starts the stop when it reaches the mark
// (CPOS, the commanded position: APOS lags it by the tracking error).
//
// JERKFINVEL says which speed the axis ends at if its present
// acceleration is ramped down to zero now: while speeding up that is
// more than the speed of the moment.

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
SET RAMPTYPE 2
VEL 100
ACC 50
DEC 50
POSA 0                           // the set-point on a whole qc (a stopped synchronisation may leave it between two)
mark = 400000
CVEL 80
CSTART
DELAY 300                        // still accelerating
PRINT "after 300 ms: AVEL ", AVEL, " qc/s, would end at ", JERKFINVEL, " % of VELMAX"
dist = JERKSTOPDIST 50
WHILE CPOS + dist < mark DO
    DELAY 1
    dist = JERKSTOPDIST 50
ENDWHILE
PRINT "stop at ", CPOS, " with a stop distance of ", dist
CSTOP
WAITAX
DELAY 200
// CPOS, where the ramp ended: APOS settles within a qc of it, on which
// side depends on where within a qc an earlier program left the axis
PRINT "stopped at ", CPOS, ", ", CPOS - mark, " qc from the mark"
