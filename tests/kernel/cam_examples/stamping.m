// DG 1470-1494: Program Example: Stamping of Boxes with Use-by Date
DIM stamping[92]        // Number of elements from the title bar of the CAM-Editor
HOME                    // Slave axis performs a home run (switch for zero position on top)
                        // Afterwards, the slave will be in the zero position (0 degrees)
SETCURVE stamping       // Set stamp curve
// Assumption: A box is positioned at the processing point with its front edge and the master stands idle
DEFMCPOS 1000           // 1000 corresponds to this position (front edge of box)
POSA CURVEPOS           // Bring slave to the curve position that corresponds to the master position
SYNCC 0                 // Change into and remain in CAM-Mode
SYNCCSTART 0            // Engage roller immediately with the set maximum velocity
// This does not cause any movement since the master is idle and in the correct position
// Now the master can be started
start:                  // Empty main loop so that program will not be terminated
// Additional processing could take place here
GOTO start
