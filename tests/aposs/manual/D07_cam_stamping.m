// D7 — CAM: stamping of boxes with use-by date (curve "stamping")
// Source: D:1472-1490 (MCO 305 Design Guide)
// OCR repairs:
// - D:1476-1489 code and comments split into two tab-separated columns (comment text broken as "the slave	will be", "a box is	positioned"); rejoined
// - D:1478-1479, 1486 "<pre>"/"</pre>" HTML debris removed

DIM stamping[92]	// Number of elements from the title bar of the CAM-Editor
HOME	// Slave axis performs a home run (switch for zero position on top)
// Afterwards, the slave will be in the zero position (0 degrees)
// (Omitted if an absolute encoder is used)
SETCURVE stamping	// Set stamp curve
// Assumption: A box is positioned at the processing point with its front edge and the master stands idle
DEFMCPOS 1000	// 1000 corresponds to this position (front edge of box)
POSA CURVEPOS	// Bring slave to the curve position that corresponds to the master position
SYNCC 0	// Change into and remain in CAM-Mode
SYNCCSTART 0	// Engage roller immediately with the set maximum velocity
// This does not cause any movement since the master is idle and in the correct position
// Now the master can be started
start: // Empty main loop so that program will not be terminated
// Additional processing could take place here
GOTO start
