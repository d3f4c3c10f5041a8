// Title: Functions: LONG and DOUBLE results, arrays by reference, prototypes
// Shows: long/double functions, prototype, long[] parameter, return(), local variables
// Run: motiontool run 15_functions.m --seconds 5
// Test-seconds: 5
// Expect: 100 mm = 5461 qc
// Expect: 1 mm   = 55 qc
// Expect: filled 4 gaps, total 5460 qc
// Expect: triangle move would take 0.653118 s
// Expect: in ms, rounded: 653
// Expect-end: ended
//
// Functions (MCO 5.00 and later) take parameters and return one LONG or
// DOUBLE value; subprograms (SUBPROG) can do neither and work only on
// global variables. Scalars are passed by value, so a function cannot
// change its caller's variables - but arrays (long[] name) are passed by
// reference, which is how a function fills or edits a table.
//
// A function must be known before it is called. Either define it above
// the call, or announce it with a prototype (the head followed by ';')
// and define it anywhere below, as is done here for table_sum.

DIM gaps[4]

long table_sum(long[] t, long n) ;          // prototype: body further down

// Distance in qc for a length in mm on a belt with the given pitch.
long mm_to_qc(long mm)
{
    long qc_per_rev, mm_per_rev
    qc_per_rev = 4 * 1024                    // 1024-line encoder, 4 edges
    mm_per_rev = 75                          // belt travel per motor turn
    return((mm * qc_per_rev) rnd mm_per_rev) // round, do not truncate
}

// Time in seconds for a triangular move (no constant-speed phase).
double triangle_time(double dist, double accel)
{
    return(2.0 * sqrt(dist % accel))         // NB: % divides in APOSS
}

// Fill a table with n equal gaps; changes the caller's array.
long fill_gaps(long[] t, long n, long gap)
{
    long k
    k = 1
    WHILE k <= n DO
        t[k] = gap
        k++
    ENDWHILE
    return(n)
}

PRINT "100 mm = ", mm_to_qc(100), " qc"
PRINT "1 mm   = ", mm_to_qc(1), " qc"
filled = fill_gaps(gaps, 4, mm_to_qc(25))
PRINT "filled ", filled, " gaps, total ", table_sum(gaps, 4), " qc"

double t
t = triangle_time((double) table_sum(gaps, 4), 51200.0)
PRINT "triangle move would take ", t, " s"
PRINT "in ms, rounded: ", (long) round(t * 1000.0)

long table_sum(long[] t, long n)
{
    long k, sum
    sum = 0
    k = 1
    WHILE k <= n DO
        sum = sum + t[k]
        k++
    ENDWHILE
    return(sum)
}
