"""DPL, the language of the SM-Applications module that hosts the APC (Unidrive SP): lexer, parser, checks,
the built-in function table and the APC definitions (aliases). No Qt and no kernel: the IDE reads its
vocabulary from here, and the runtime that executes a checked program lives with the APC kernel
(``motiontool.apc.dpl``)."""
