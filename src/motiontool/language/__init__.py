"""What the APOSS and DPL compilers share (issue 27 item 6): source locations and GCC-style diagnostics
(`diagnostics`), the token (`tokens`), the syntax tree's base node (`ast`) and bounded source reading (`source`).
No Qt; nothing of either language, so that DPL needs nothing of APOSS."""
