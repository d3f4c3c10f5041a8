"""Loose mode's wrong things (ProgramGenerator with loose=True): the templates that chaos_fill completes with
names of the program ({long}, {array}, {func} ...)."""

# Values and statements that parse but are wrong (they reach the checks and the code generator) ...
CHAOS_VALUES = [
    "{undef}", "{array}", "{long}[1]", "{dim}[1][2]", "{func}", "{sub}", "nofunc(1)", "{func}(1, 2, 3, 4)",
    '"text"', "chr(65)", "{double}.3", "{long}.b5", "{long}.40", "{long}.0", "5.b9", "(1.5 << 2)",
    "({double} mod 2)", "~{double}", "(1 % 0)", "(5 mod 0)", "(1 rnd 0)", "(2.0 % 0.0)", "sqrt(-1.0)", "ln(0.0)",
    "acos(2.0)", "(0.0 exp -1.0)", "((-8.0) exp 0.5)", "(1e308 * 10.0)", "(1e308 + 1e308)", "ON", "(GET NOTAPARAM)",
    "(10 exp 400)", "(2.0 exp 1024.0)", "grad(1e308)", "(1e308 * 1e308 * 0.0)", "({long} % 0)", "(7 % (3 - 3))",
    "-(-2147483648)", "(2147483647 + 1)", "(0x80000000 % -1)", "((-2147483647 - 1) % -1)", "abs(-2147483648)",
    "(1 << -1)", "(1 >> 64)", "(1 << 99999)", "({long} exp {long})", "NOT 1.5", "((double) 1) . 3", "x(1)",
    "{long}(1)", "round(-0.5)", "(1 == 1 == 1)", "'A' + 'B'", "{long}.sb 0", "{long}.b ({long})", "{long}.uw -1",
    "(1.5).b1", "(long)(double)(long) 1.5e300", "(SDOSTATE 1 {long})", "(ENCTGREAD {long})", "{math}(1e308 * 10.0)",
    "{math}(-(1e308 * 10.0))", "{math}((1e308 * 10.0) - (1e308 * 10.0))", "{math}(1e308)", "{math}(-1e308)",
    "{math}(5e-324)", "{math}({double})", "(long) {math}(1e308 * 1e308)", "{math}(1.7976931348623157e308 * 2)",
    "{func}({long})", "{func}({array})", "{func}({double}, {double})", "{long}.{long}", "{long}.({long} + 1)",
    "{array}[0]", "{array}[-1]", "{dim}[1]", "(SDOSTATE 1 {dim}[1][1])", "({double} AND {double})", "NOT {double}",
    "((1e308 * 10.0) == 0.0)", "(long) (1e308 * 10.0)", "{double} exp 0.5", "__LINE__", "__FILE__", "(x(1) + 1)",
    "PI", "(long) PI", "(CPOSDIFF x(2) 5)", "(APOSDIFF X({long}) {long})",
]
# ... and ones that stop the parser.
CHAOS_VALUES_SYNTAX = [
    "1e400", "round(1e400)", "((long) 1e400)", "0x100000000", "99999999999", "tan(PI / 2)", "(IN)", "(POSA 1)",
    "(MOTOR ON)", "SYSVAR", "PCD[1][2]", "(1)++", "{long}++ ++", "(GET)", "(long)", "(double)", "{func}({array}[])",
    "{array}[]", "(({long}))[1]", "SQRT(1, 2)", "ABS()", "PI(1)", "({long} = 1)", "(IN 1 2)", "(APOS 1)", "(INKEY)",
    "(CANIN 1 2 3 4 5)", "(ENCPOSOFFS 5)", "(ENCTGREAD 5)", "(IN X59/3)", "(IN x56/)", "X59/3",
]
CHAOS_STATEMENTS = [
    "GOSUB nosub", "GOTO nolabel", "LOOP {long} nolabel", "BREAK", "EXIT", "DIM late[5]", "#pragma IMPLICIT",
    "#pragma NOIMPLICIT", "long {long}", "double {long}", "long {func}", "long {sub}", "{func} = 1",
    "{long}[] = {long}[]", "{array}[] = {double}[]", "PCD[1].3 = 1", "SYSVAR[1].b2 = 4", "ON INT 1 GOSUB nosub",
    "ON DELETE 5 SETOUT 1", "ON -APOS 5 SETOUT 1 TOIN 2", "ON + IPOS 1 GOSUB {sub}", "ON TIME 1 GOSUB {func}",
    "DEFCORIGIN X({long})", "DEFCORIGIN X(2)", "{long}:", "{sub}:", "lbl_dup:", "lbl_dup:",
    "long f_bad(long a, long a) ;", "double {func}() ;", "long {func}(long[] z) ;", "long proto_only() ;",
    "{func}()", "SET NOTAPARAM 1", "OUT {array} 1", "SDOSTATE 1 {long}.3", "ENCTGREAD {long}", "SETCURVE {long}",
    "PRINT {array}", "PRINT {func}", "{long}++", "{double}--", "{array}++", "SYSVAR[1]++", "INKEY 0",
    "DELETE ARRAYS", "x = 1", "{long} = {func}", "{long} = {sub}", '{double} = "s"', "{long} = {long}[1]",
    "{double}[1] = 0", "label_only:", "GOTO label_only", "ON INT 0 GOSUB {sub}", "ON PERIOD 5 GOSUB {sub}",
    "ON COMBIT 40 GOSUB {sub}", "ON STATBIT 0 GOSUB {sub}", "ON CANINPUT 1 GOSUB {sub}", "ON TIME -1 GOSUB {sub}",
    "ON PERIOD {double} GOSUB {sub}", "ON APOS {double} GOSUB {sub}", "ON DELETE +APOS SETOUT 1",
    "ON DELETE -MAPOS GOSUB {sub}", "SDOSTATE 1 {dim}[1][1]", "ENCPOSOFFS {dim}[1][2]",
    "CANIN 1 2 3 {long} {array}[1]", "OUT X59/3 1", "OUT x59/1 {long}", "{long} = IN X59/3", "TESTSETDEST DYNMEM",
    "TESTSETDEST {array}", "LOOP -1 label_only", "LOOP {double} label_only", "SWITCH {double}\nCASE 1:\nENDSWITCH",
    "SWITCH 1\nCASE {long}:\nENDSWITCH", "SWITCH 1\nCASE 1:\nCASE 1:\nENDSWITCH", "SWITCH 1\nCASE 1.5:\nENDSWITCH",
    "IF 1 THEN ENDIF", "{long}.{long} = 1", "{long}.b({long}) = 2", "{dim}[1][1].3 = 1", "PDO[1].w2 = {double}",
    "DIM huge[2000][2000]", "POSA (1e308 * 10.0)", "DELAY {double}", "PRINT chr({double}), chr(1e308 * 10.0)",
    'PRINTDEV {double} "x"', "NOWAIT ON", "WAITI 1", "WAITI 1 OFF", "SET PID KPROP {double}",
    "SET KPROP (1e308 * 10.0)", 'LINKGPAR 1900 "" 0 100 0',
]
CHAOS_STATEMENTS_SYNTAX = [
    "RETURN", "return({long})", "long POSA", "APOS = 1", "POSA = 3", "PI = 3", "(v) = 1", "1 = 2", "{long}.3.2 = 1",
    "{func}(1).3 = 2", "ON FOO 1 GOSUB {sub}", "ON APOS GOSUB {sub}", "ON ERROR", "ON INT GOSUB {sub}",
    "SWITCH {double}", "SWITCH 1", "CASE 1:", "DEFAULT:", "ENDSWITCH", "ENDIF", "ELSE", "ENDWHILE", "UNTIL 1",
    "POSA x(2) 100", "POSA:", "THEN", "SUBPROG {sub}", "ENDPROG", "SUBMAINPROG", "{{", "}}", "{func}", "{long}",
    "{undef}", "MOTOR", "SAVE", "SET PID FOO 1", "SET PID KPROP", "SET 1900", "SET", "NOWAIT MAYBE", "NOWAIT",
    "WAITI 1 ON OFF", "OUT 1", "OUT 1 2 3", 'POSA "text"', "LINKGPAR 1900 5 0 100 0", "CANIN 1 2 3 4 5",
    "CANIN 1 2 3 {long} {func}(1)", "ENCPOSOFFS 5", "TESTSETINDEX", "CANINI 1,2,,3", "PRINT ,", "PRINT 1;;",
    "PRINT CHR()", "PRINTDEV", "{long} = {long} =", "IF 1 THEN", "WHILE 1 DO", "REPEAT",
    "IF {long} THEN GOTO nolabel", "{long} = INKEY", "DISABLE ERROR", "ENABLE", "DELETE", "MOTOR ON OFF",
    "POSA CURVEPOS 1", "X(1) = 2", "{long} = (long)", "{long}.b = 1", "{dim}[1] = {dim}[1][1][1]", "POSA X59/3",
    "SWITCH 1\nDEFAULT:\nDEFAULT:\nENDSWITCH", "IF 1 THEN\nELSE\nELSE\nENDIF",
    "IF 1 THEN\nELSE\nELSEIF 1 THEN\nENDIF", "IF 1 THEN\nELSE IF 1 THEN\nENDIF", "SWITCH\nENDSWITCH",
    "WHILE DO\nENDWHILE", "REPEAT\nUNTIL", "LOOP", "long x[0]", "long x[1][2][3]", "long x = 1", "DIM y",
    "SUBMAINPROG\nENDPROG",
]
# Program-level mistakes: duplicate definitions, mismatching prototypes, misplaced parts.
CHAOS_PARTS = [
    "long {func}(double z)\n{{\nreturn(1)\n}}", "long {func}()\n{{\n}}", "double {func}(long[] a) ;",
    "long fresh_fn(long a, long a)\n{{\nreturn(a)\n}}", "long {sub}()\n{{\n}}",
    "SUBMAINPROG\nSUBPROG {sub}\nRETURN\nENDPROG", "long late_decl\nlate_decl = 1",
    "long rec(long n)\n{{\nreturn(rec(n - 1))\n}}", "long noreturn()\n{{\n{long} = 1\n}}",
    "long used_before()\n{{\nreturn(later_fn(1))\n}}\nlong later_fn(long q)\n{{\nreturn(q)\n}}",
]
