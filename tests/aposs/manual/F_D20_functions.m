// F_D20 — Functions: declaration (prototype), call, definition with locals and return(); array passed by reference
// Source: D:6621-6631 and D:6637-6646 (MCO 305 Design Guide)
// Kind: two fragments made into one complete program. Scaffolding added:
//   - one DIM line first (D:6638 "DIM test[100]" moved to the top: DIM must be the first statement)
//   - declarations "long a, b" / "double c" and the assignments a = 1, b = 2, c = 2.0, test[2] = 7 (the manual
//     calls test_func(a,b,c) without showing a, b, c)
//   - the elided body "...." of test_func replaced by two statements computing result = a + b + (long) c
//   - the "..." placeholders between the snippets dropped; PRINT lines added
// OCR repairs:
// - D:6631 closing brace "}" of test_func lost; restored
// Expected: wert = 5, test[2] = 70
// Note: "index" names a variable although INDEX is a command (D:7013) and D:6425 says names must not equal
//   command names: the manual's own program does it, so it compiles with a warning (decision L14)

DIM test[100]
long a, b
double c
long test_func (long a, long b, double c) ; // declaration statement
long modi(long[] myarray, long index)
{
    myarray[index] = myarray[index] * 10
    return(index)
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
