/****** DG 1725-1746: Program Example: Slave Synchronization with Marker ******/
// In order to determine the master position, a switch on the master is required that indicates the zero position.
// The slave is moved forward to the photoelectric beam (beginning of the box = 1000) and then by 2900
// (= marker distance 3900 - 1000): the box is in front of the processing point, i.e. at slave position 0.
// OCR repairs: DG 1728-1730 "," / "ve axis performs a home run" -> HOME with its comment (as in DG 1477-1480).
DIM slavesync[108]      // Number of elements from the title bar of the CAM-Editor
HOME                    // Slave axis performs a home run (switch for zero position on top)
                        // Afterwards, the slave will be in the zero position (0 degrees)
                        // (Omitted if an absolute encoder is used)
DEFMCPOS 0              // Curve starts at master position 0
SET SYNCMSTART 2000     // Counting of the master pulse does not begin
                        // until the next edge comes from the sensor
SETCURVE slavesync      // Set curve for the slave synchronization
CSTART                  // Go to start
CVEL 10                 // Go forward slowly until photoelectric beam appears
oldi = IPOS             // oldi = last marker position of the slave
WHILE (oldi == IPOS) DO // Wait until box is detected
ENDWHILE
POSA (IPOS + 2900)      // Move box forward by 2900
SYNCCMS 0               // Synchronize in CAM-Mode
SYNCCSTART 1            // Engage with start-stop point pair 1
