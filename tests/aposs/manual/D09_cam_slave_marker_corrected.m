// D9 (corrected copy) — CAM: slave synchronization with slave marker (curve "slavesync")
// Source: D:1725-1744 (MCO 305 Design Guide)
// OCR repairs:
// - D:1730-1732 left column lost: the HOME statement and the start of the three comments are missing ("ve axis performs a home run ...", "erwards, the slave ...", "nitted if an absolute ..."); restored as "HOME // Slave axis performs a home run ...", "// Afterwards, ...", "// (Omitted ...)" (identical text in D7 D:1477-1479 and D8 D:1553-1555)
// Correction (the manual's program itself, not OCR): as printed (D09_cam_slave_marker.m) the program ends right after
//   SYNCCSTART 1, and "If the program is closed without the explicit command SYNCCSTOP pnum slavepos, then the second
//   point pair will always be used for disengaging" (D:4054) — the conveyor never engages. This copy adds the empty
//   main loop of D7 ("start: // Empty main loop so that program will not be terminated", D:1488) at the end.

DIM slavesync[108]	// Number of elements from the title bar of the CAM-Editor
HOME	// Slave axis performs a home run (switch for zero position on top)
// Afterwards, the slave will be in the zero position (0 degrees)
// (Omitted if an absolute encoder is used)
DEFMCPOS 0	// Curve starts at master position 0
SET SYNCMSTART 2000	// Counting of the master pulse does not begin
	// until the next edge comes from the sensor
SETCURVE slavesync	// Set curve for the slave synchronization
CSTART	// Go to start
CVEL 10	// Go forward slowly until photoelectric beam appears
oldi = IPOS	// oldi = last marker position of the slave
WHILE (oldi == IPOS) DO	// Wait until box is detected
ENDWHILE
POSA (IPOS + 2900)	// Move box forward by 2900
SYNCCMS 0	// Synchronize in CAM-Mode
SYNCCSTART 1	// Engage with start-stop point pair 1
start:	// Empty main loop so that program will not be terminated (added, as D:1488)
GOTO start
