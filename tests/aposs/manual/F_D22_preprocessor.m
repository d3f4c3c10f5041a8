// F_D22 — Preprocessor: continuation lines, #define/#undef, __LINE__, recursive and function-like macros, #ifdef/#else, #if/#elif
// Source: D:6831-6837, D:6892-6898, D:6908-6913, D:6927-6932, D:6955-6974, D:6983-6993 (MCO 305 Design Guide)
// Kind: fragments made into one complete program. Scaffolding added:
//   - D:6831-6837: the continuation-line example itself is lost (only its "is the same as" line survives);
//     reconstructed as the PRINT statement split after "apos," with a trailing "\"
//   - "#undef PRINT_MSG" before the second example, which defines PRINT_MSG again with another body
//   - "a = 1" / "b = 2" before SUM_SQUARE(a,b)
//   - prose lines in branches that ARE compiled ("This will always be compiled.", "Compile this for customer B.")
//     turned into PRINT "<same text>"; prose in branches that are NOT compiled is kept verbatim (the preprocessor
//     must drop it)
// OCR repairs:
// - D:6897 "__LINE___" (three trailing underscores) -> "__LINE__"
// - D:6956 "#ifdef INCLUDE DEBUG" -> "#ifdef INCLUDE_DEBUG"; D:6960 "#ifdef START AT 0" -> "#ifdef START_AT_0" (spaces for underscores)
// - D:6965 "#if O" (letter O) -> "#if 0"
// - D:6914 "is the same as:" (manual prose inside the code block) dropped
// Expected output: " apos = <apos> avel = <avel>" (twice), "This is line 24" (the physical line of that PRINT in
//   this file), "VALUE = 10", "VALUE = 20", "This will always be compiled.", "Compile this for customer B.";
//   i = 25 then 5; start = 1.

#define ARRAY_LEN 100
#define PRINT_MSG print " apos = ",apos," avel = ",avel
DIM prm[ARRAY_LEN]
PRINT_MSG
PRINT "This is line ",__LINE__
PRINT " apos = ", apos, \
" avel = ", avel
#undef PRINT_MSG
#define VALUE 10
#define PRINT_MSG print "VALUE = ",VALUE
PRINT_MSG
#define VALUE 20
PRINT_MSG
#define SQUARE(x) ((x)*(x))
#define SUM_SQUARE(x,y) (SQUARE(x) + SQUARE(y))
i = SUM_SQUARE(3,4)
a = 1
b = 2
i = SUM_SQUARE(a,b)
#ifdef INCLUDE_DEBUG
PRINT "Position = ",apos
PRINT "Velocity = ",avel
#endif
#ifdef START_AT_0
start = 0
#else
start = 1
#endif
#if 0
This will never be compiled.
#endif
#if 1
PRINT "This will always be compiled."
#endif
#define OPTION 1
#if OPTION > 2
This will be compiled only if OPTION is greater than 2.
#endif
#define CUSTOMER_A 1
#define CUSTOMER_B 2
#define CUSTOMER CUSTOMER_B
#if CUSTOMER == CUSTOMER_A
Compile this for customer A.
#elif CUSTOMER == CUSTOMER_B
PRINT "Compile this for customer B."
#else
Otherwise compile this.
#endif
