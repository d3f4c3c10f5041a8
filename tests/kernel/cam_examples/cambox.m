// DG 1748-1772: CAM box. After a cardboard box has been printed, the fresh print is dried in the air stream.
// The stamping set-up of DG 1474-1494 runs the curve; ON MCPOS needs SETCURVE or DEFMCPOS first (CR 2894).
DIM stamping[92]
SETCURVE stamping
DEFMCPOS 1000
POSA CURVEPOS
ON MCPOS 2500 GOSUB drier   // Call up a subprogram when the master position 2500 is passed in positive direction
ON MCPOS 1500 SETOUT 2      // CR 2985-3016: output 2 is on while the stamp prints (1500 ... 2500)
ON MCPOS 2500 SETOUT -2
SYNCC 0
SYNCCSTART 0
start:
GOTO start

SUBMAINPROG
SUBPROG drier
  OUT 1 1               // Turn on drier
  DELAY 300             // Dry for 300 ms
  OUT 1 0               // Turn off drier
RETURN
ENDPROG
