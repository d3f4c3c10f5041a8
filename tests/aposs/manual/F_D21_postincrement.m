// F_D21 — Post-increment / post-decrement on variables and array elements
// Source: D:6690-6702 (MCO 305 Design Guide); operator rows D:6673, D:6675
// Kind: fragments made complete. Scaffolding added:
//   - one DIM line first with both arrays (the manual uses "test" without a DIM and puts "DIM testarray[20]" after code)
//   - "index = 1" before the loop, "value = 0", "testarray[5] = 7" and "testarray[10] = 0" before use (the manual shows "...")
//   - PRINT lines
// OCR repairs:
// - D:6694 "value-</pre>" -> "value--" (post-decrement statement; "</pre>" is HTML debris; DOUBTFUL: the line may be a cut-off "value--" or "value++")
// - D:6700 "testarray[10]" is a cut-off line with no operator; completed as "testarray[10]++" (DOUBTFUL)
// Expected: var = 7, testarray[5] = 8, testarray[10] = 1, value = -1, index = 100 after the loop
// Note: in "test[index] = index++" the manual does not say whether the element index is taken before or after
//   the increment (intended: test[i] = i); a test should not depend on it.
// Note: "index" names a variable although INDEX is a command (D:7013) and D:6425 says names must not equal
//   command names: the manual's own program does it, so it compiles with a warning (decision L14)

DIM test[100], testarray[20]
index = 1
while(index < 100) do
    test[index] = index++
endwhile
value = 0
value--
testarray[5] = 7
testarray[10] = 0
var = testarray[5]++
testarray[10]++
PRINT "var = ", var, " testarray[5] = ", testarray[5]
