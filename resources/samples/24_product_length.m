// Title: Measuring product length with rising and falling edge interrupts
// Shows: ON INT +n, ON INT -n, CVEL, CSTART, CSTOP, DISABLE INT/ENABLE INT, DIM
// Run: motiontool run 24_product_length.m --seconds 10 --input 6=0@0 --input 6=1@400 --input 6=0@700 --input 6=1@1200 --input 6=0@1650 --input 6=1@2500 --input 6=0@2620
// Test-inputs: 6=0@0 6=1@400 6=0@700 6=1@1200 6=0@1650 6=1@2500 6=0@2620
// Test-seconds: 10
// Expect: product 1: 6144 qc
// Expect: product 2: 9216 qc
// Expect: product 3: 2458 qc
// Expect: 3 products, 1 shorter than 5000 qc
// Expect-end: ended
//
// Products pass a light barrier on input 6 while the conveyor runs at
// constant speed. The rising edge (ON INT 6) marks the front of a
// product, the falling edge (ON INT -6) its end; the difference of the
// two APOS values is the product length, independent of the speed.
// Since MCO 5.00 both edges of one input may have their own handler.
//
// The handlers store results in an array and bump a counter. The main
// program takes its snapshot of the shared values between DISABLE INT
// and ENABLE INT, so no handler can change them half-way; this matters
// as soon as more than one value must be read consistently. An edge
// arriving during a selective DISABLE INT is lost: keep it short.

DIM lengths[20]
t0 = TIME - 1                 // the start (TIME counts from power-up; line 1 runs at start + 1 ms)
ON INT 6 GOSUB front
ON INT -6 GOSUB back

count = 0
reported = 0
ACC 100
DEC 100
CVEL 20                          // 20 % of VELMAX = 20480 qc/s
CSTART

WHILE TIME - t0 < 3000 DO
    DISABLE INT
    fresh = count - reported
    ENABLE INT
    WHILE fresh > 0 DO
        reported++
        PRINT "product ", reported, ": ", lengths[reported], " qc"
        fresh = fresh - 1
    ENDWHILE
    DELAY 20
ENDWHILE
CSTOP
DELAY 300

short = 0
i = 1
WHILE i <= count DO
    IF lengths[i] < 5000 THEN
        short++
    ENDIF
    i++
ENDWHILE
PRINT count, " products, ", short, " shorter than 5000 qc"

SUBMAINPROG
SUBPROG front
    start = APOS
RETURN

SUBPROG back
    IF count < 20 THEN
        count = count + 1
        lengths[count] = APOS - start
    ENDIF
RETURN
ENDPROG
