// Title: Bits and bytes of the I/O word
// Shows: INB, OUTB, .n bit selector, .b1 byte selector, bit assignment, &, |, <<, >>, ~
// Run: motiontool run 18_bit_io.m --seconds 5 --input 1=1@0 --input 2=0@0 --input 3=1@0 --input 4=0@0 --input 5=0@0 --input 6=0@0 --input 7=0@0 --input 8=1@0 --input 2=1@600 --input 3=0@600
// Test-inputs: 1=1@0 2=0@0 3=1@0 4=0@0 5=0@0 6=0@0 7=0@0 8=1@0 2=1@600 3=0@600
// Test-seconds: 5
// Expect: inputs 133: code 5, enable 1, bit 3 1
// Expect:   outputs 81 = code 5, flags 1
// Expect: inputs 131: code 3, enable 1, bit 3 0
// Expect:   outputs 51 = code 3, flags 3
// Expect: inverted code nibble: 12
// Expect-end: ended
//
// A PLC selects the product with a 4-bit code on inputs 1-4 and enables
// the machine with input 8. Reading the eight inputs at once with INB 0
// gives a consistent snapshot; eight separate IN commands could see
// the code half-way through a change.
//
// Bit selectors count from 1: word.1 is the lowest bit, word.8 the
// highest of the first byte, and .b1 is the lowest byte. The same
// selectors work on the left of '=' to set single bits of a variable,
// which is handy to assemble an output pattern before one OUTB.

DELAY 10                          // let the scheduled inputs arrive
sample = 0
WHILE sample < 2 DO
    inputs = INB 0                 // inputs 1..8 -> bits 1..8
    code = inputs & 0x0F           // the product code on inputs 1-4
    enabled = inputs.8
    PRINT "inputs ", inputs, ": code ", code, ", enable ", enabled, ", bit 3 ", inputs.3

    pattern = 0
    pattern.1 = enabled            // output 1: machine enabled
    pattern.b1 = pattern.b1 | (code << 4)   // outputs 5-8 echo the code
    pattern.2 = (code == 3)        // output 2: "product 3 selected"
    OUTB 0 pattern                 // all eight outputs in one go
    PRINT "  outputs ", SYSVAR[0x0122020A], " = code ", (pattern >> 4) & 0x0F, ", flags ", pattern & 3

    DELAY 1000
    sample++
ENDWHILE

// ~ inverts every bit, so mask the byte you want to keep.
PRINT "inverted code nibble: ", (~code) & 0x0F
OUTB 0 0                           // leave all outputs off
