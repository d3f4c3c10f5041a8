// F_D20 (corrected copy) — Functions: declaration (prototype), call, definition with locals and return(); array passed by reference
// Source: D:6621-6631 and D:6637-6646 (MCO 305 Design Guide)
// Kind: two fragments made into one complete program. Scaffolding added:
//   - one DIM line first (D:6638 "DIM test[100]" moved to the top: DIM must be the first statement)
//   - declarations "long a, b" / "double c" and the assignments a = 1, b = 2, c = 2.0, test[2] = 7 (the manual
//     calls test_func(a,b,c) without showing a, b, c)
//   - the elided body "...." of test_func replaced by two statements computing result = a + b + (long) c
//   - the "..." placeholders between the snippets dropped; PRINT lines added
// OCR repairs:
// - D:6631 closing brace "}" of test_func lost; restored
// Correction (the manual's own slip, not OCR): "index" renamed "idx": INDEX is a command name (D:7013) and
//   may not name a variable (D:6425); the printed copy keeps "index" and `motiontool check` reports it
// Expected: wert = 5, test[2] = 70

DIM test[100]
long a, b
double c
long test_func (long a, long b, double c) ; // declaration statement
long modi(long[] myarray, long idx)
{
    myarray[idx] = myarray[idx] * 10
    return(idx)
}
a = 1
b = 2
c = 2.0
wert = test_func(a,b,c) // using the function
test[2] = 7
modi(test,2) // element 2 of test will be multiplied by 10
PRINT "wert = ", wert, " test[2] = ", test[2]
long test_func(long a, long b, double c) // function definition
{
    long result, tmpval // local variables
    tmpval = a + b
    result = tmpval + ((long) c)
    return(result) // here we return the value of the function
}
