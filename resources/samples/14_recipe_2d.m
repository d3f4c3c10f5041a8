// Title: Recipes in a two-dimensional array
// Shows: DIM [r][c], 2-D indexing, row-major linear index, array copy, local arrays
// Run: motiontool run 14_recipe_2d.m --seconds 20
// Test-seconds: 20
// Expect: recipe 2 speed via [2][2]: 80, via [5]: 80, backup[5]: 80
// Expect: recipe 1: stroke 8000, cycle 1450 ms
// Expect: recipe 2: stroke 15000, cycle 1815 ms
// Expect: recipe 3: stroke 3000, cycle 1271 ms
// Expect: recipe 3 speed restored to 20
// Expect: slowest cycle: recipe 2
// Expect-end: ended
//
// Each product needs its own stroke, speed and dwell time. A 2-D array
// with one row per recipe and one column per setting keeps them
// together: recipe[r][c]. The array is stored row by row, so element
// [r][c] is also element (r-1)*COLS + c when the array is indexed with
// one index - that is how the Array Editor lists it.
//
// "backup[] = recipe[]" copies a whole array in one statement (as many
// elements as the smaller array holds). A local array (long name[n])
// exists only while the program runs and does not use array memory.

DIM recipe[3][3], backup[9]
#define STROKE 1
#define SPEED 2
#define DWELL 3

recipe[1][STROKE] = 8000
recipe[1][SPEED] = 40
recipe[1][DWELL] = 200
recipe[2][STROKE] = 15000
recipe[2][SPEED] = 80
recipe[2][DWELL] = 100
recipe[3][STROKE] = 3000
recipe[3][SPEED] = 20
recipe[3][DWELL] = 500

backup[] = recipe[]             // keep the original values
PRINT "recipe 2 speed via [2][2]: ", recipe[2][SPEED], ", via [5]: ", recipe[5], ", backup[5]: ", backup[5]

long used[3]                    // strokes per recipe, for this run only
ACC 80
DEC 80
r = 1
WHILE r <= 3 DO
    VEL recipe[r][SPEED]
    t0 = TIME
    POSR recipe[r][STROKE]       // out ...
    DELAY recipe[r][DWELL]
    POSR (-recipe[r][STROKE])    // ... and back
    used[r] = TIME - t0
    PRINT "recipe ", r, ": stroke ", recipe[r][STROKE], ", cycle ", used[r], " ms"
    r++
ENDWHILE

// A setter "tunes" recipe 3; the backup brings the old values back.
recipe[3][SPEED] = 60
recipe[] = backup[]
PRINT "recipe 3 speed restored to ", recipe[3][SPEED]
slowest = 1
r = 2
WHILE r <= 3 DO
    IF used[r] > used[slowest] THEN
        slowest = r
    ENDIF
    r++
ENDWHILE
PRINT "slowest cycle: recipe ", slowest
