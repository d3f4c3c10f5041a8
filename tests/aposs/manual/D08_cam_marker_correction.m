// D8 — CAM: printing of cardboard boxes with master-marker correction (curve "marker")
// Source: D:1547-1565 (MCO 305 Design Guide)
// OCR repairs:
// - D:1551 banner split into columns ("Cardboa	rd Boxes"); rejoined
// - D:1552 "DIM marker[112]	<pre>ker[112] // ..." duplicated column text and HTML debris removed -> "DIM marker[112] // ..."
// - D:1553 "HOME" spelt with Cyrillic look-alike letters (U+041D U+041E U+041C U+0415) -> ASCII "HOME"
// - D:1554-1563 comments split into columns ("absolute	e encoder", "edge con	mes"); rejoined, "<pre>" debris removed, stray "1" after "Synchronous operation" dropped

/****** Printing of Cardboard Boxes with Marker Correction (Synchronization with Marker) ******/
DIM marker[112] // Number of elements from the title bar of the CAM-Editor
HOME	// Slave axis performs a home run (switch for zero position on top)
// Afterwards, the slave will be in the zero position (0 degrees)
// (Omitted if an absolute encoder is used)
SETCURVE marker	// Set stamp curve with marker
dist = GET SYNCMPULSM	// Distance to sensor
DEFMCPOS (1000-dist)	// This is the location that corresponds to the sensor signal
SET SYNCMSTART 2000	// Counting of the master pulse does not begin
// until the next edge comes from the sensor
SYNCCMM 0	// Synchronize in CAM-Mode until motor stop
SYNCCSTART 1	// Engage roller with start point pair 1
// Synchronous operation
WAITI 4 ON	// Wait for input signal when conveyor belt is being switched off
SYNCCSTOP 2 0	// Disengage roller with stop point pair 1 and stop at position 0 degrees
