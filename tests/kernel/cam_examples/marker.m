/****** DG 1553-1566: Printing of Cardboard Boxes with Marker Correction (Synchronization with Marker) ******/
DIM marker[112]         // Number of elements from the title bar of the CAM-Editor
HOME                    // Slave axis performs a home run (switch for zero position on top)
                        // Afterwards, the slave will be in the zero position (0 degrees)
SETCURVE marker         // Set stamp curve with marker
dist = GET SYNCMPULSM   // Distance to sensor
DEFMCPOS (1000-dist)    // This is the location that corresponds to the sensor signal
SET SYNCMSTART 2000     // Counting of the master pulse does not begin
                        // until the next edge comes from the sensor
SYNCCMM 0               // Synchronize in CAM-Mode until motor stop
SYNCCSTART 1            // Engage roller with start point pair 1
// Synchronous operation
WAITI 4 ON              // Wait for input signal when conveyor belt is being switched off
SYNCCSTOP 2 0           // Disengage roller with stop point pair 2 and stop at position 0 degrees
