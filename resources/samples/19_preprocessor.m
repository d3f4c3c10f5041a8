// Title: Preprocessor: macros and build-time configuration
// Shows: #define, function-like macros, #if/#elif/#else/#endif, #ifdef, #undef, __LINE__
// Run: motiontool run 19_preprocessor.m --seconds 10
// Test-seconds: 10
// Expect: [line 61] variant 2
// Expect: [line 62] stroke in qc 12000
// Expect: [line 64] arrived at 12000
// Expect: [line 70] second position 10000
// Expect: clamped: 0 42 100
// Expect: done
// Expect-end: ended
//
// The preprocessor edits the text before the compiler sees it. Macros
// give numbers a name (one place to change them) and can take
// arguments; put brackets around every argument and around the whole
// body, or operator priorities will surprise you after substitution.
//
// #if selects code at compile time: one source file serves several
// machine variants, and the code for the other variants is not even
// downloaded. Directives must be written in lower case.

#define MACHINE_SMALL 1
#define MACHINE_LARGE 2
#define MACHINE MACHINE_LARGE      // the variant this build is for
#define VERBOSE                    // comment out for a quiet build

#if MACHINE == MACHINE_SMALL
    #define STROKE_MM 120
    #define SPEED 40
#elif MACHINE == MACHINE_LARGE
    #define STROKE_MM 300
    #define SPEED 70
#else
    #define STROKE_MM 0            // unknown variant: do not move
    #define SPEED 1
#endif

#define QC_PER_MM 40
#define MM(x) ((x) * QC_PER_MM)    // mm -> qc; note the brackets
#define CLAMP(v, lo, hi) (((v) < (lo)) * (lo) + ((v) > (hi)) * (hi) + ((v) >= (lo) AND (v) <= (hi)) * (v))

#ifdef VERBOSE
    #define TRACE(text, value) PRINT "[line ", __LINE__, "] ", text, value
#else
    #define TRACE(text, value)
#endif

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
VEL SPEED
ACC 50
DEC 50
TRACE("variant ", MACHINE)
TRACE("stroke in qc ", MM(STROKE_MM))
POSA MM(STROKE_MM)
TRACE("arrived at ", CPOS)

// MM(a + b) expands to ((a + b) * QC_PER_MM); without the inner
// brackets it would be (a + b * QC_PER_MM).
back = MM(STROKE_MM - 50)
POSA back
TRACE("second position ", back)
PRINT "clamped: ", CLAMP(-5, 0, 100), " ", CLAMP(42, 0, 100), " ", CLAMP(250, 0, 100)

#undef VERBOSE                     // from here on VERBOSE is unknown
#ifndef VERBOSE
PRINT "done"
#endif
