// D12 — HELLO.M, the debugger demonstration program
// Source: D:3377-3380 (MCO 305 Design Guide); second screenshot D:3448-3455 shows the same program with "while (i <= 50)"
// OCR repairs:
// - D:3379-3380 screenshot debris removed: breakpoint bullets ("•"), HTML list tags ("<ul> <li> ... </li> </ul>")
// - D:3380 HTML entity "&lt;=" -> "<="
// - D:3380 the whole loop is on one line; split into one statement per line ("i = i + 1 endwhile" -> two lines)

// Hello.m
DIM arr[100]
i = 1
while (i <= 5) do
print "Hello: ",i
delay 500
i = i + 1
endwhile
print "Good bye."
