// D6 — Marker synchronizing (packaging with varying product distance) with marker-distance measurement
// Source: D:1203-1340 (MCO 305 Design Guide)
// OCR repairs:
// - D:1203-1257 text split into 3-4 columns with pieces lost or repeated cumulatively (D:1247-1257 repeat the left column of all previous lines); lines rebuilt by joining the column pieces, duplicates dropped
// - D:1203, 1213, 1216, 1220, 1222, 1226, 1241, 1243 banner comments split across columns / lost their start; rejoined and closed with "/"
// - D:1204-1212 header comment lines split ("2 M | leasure slave marker dis | stance", "1 | 8 C | lear Error"); rejoined, "//" restored on D:1209 and D:1213
// - D:1214 "ON ERROR GC | SUB errh | andle" -> "ON ERROR GOSUB errhandle"
// - D:1217-1219 comments of VEL/ACC/DEC partly lost; completed with the wording of D4/D5
// - D:1221 only '"uring velocity" 0 100 0' survives -> LINKGPAR 1900 "Measuring velocity" 0 100 0 (GET 1900 is the measuring velocity, D:1246)
// - D:1223-1224 "SET SYNCMTY ... ker type to external" / "SET SYNCMTY // Set slave marke" -> "SET SYNCMTYPM 2" / "SET SYNCMTYPS 2" (type 2 = external marker, cf. D:1527, D:1706, C:2294)
// - D:1225 LaTeX debris "$sync_flag = 0$" -> "sync_flag = 0"
// - D:1230, 1233 "sync_flag =  - 1" / "sync_flag = = 0" -> "sync_flag = 1" / "sync_flag = 0"
// - D:1232 "MOTOR STO" + tab + U+042D U+0420 (Cyrillic look-alikes of "OP") -> "MOTOR STOP"
// - D:1236 "GOSUB slav" -> "GOSUB slave_measure"; D:1244 "SUBPROG slav" -> "SUBPROG slave_measure" (name lost; chosen to match master_measure)
// - D:1237 "_ D (sync_flag == 0) THE N" -> "ELSEIF (IN 3 == 1) AND (sync_flag == 0) THEN" (input 3 = "Measure master marker distance", D:1206)
// - D:1238 "GOSUB ma" -> "GOSUB master_measure" (SUBPROG at D:1279)
// - D:1246-1253 "OUT 2 1", "CVEL GET 1900", "CSTART", "old_ipos = IPOS", "marker_number = 0", "total_dist = 0", "skip_first = 0", "WHILE (IN 2 == 1) DO" rejoined from the pieces ("marker_nut | mber = 0", "2 == 1) [ | DO")
// - D:1255-1256 "IF (new | _ipos != 0 | old_ipos) THEN" -> "IF (new_ipos != old_ipos) THEN"; "new_mark ... nce = new_ipos - old_ip os" -> "marker_distance = new_ipos - old_ipos"
// - D:1257 "IF (r marker_di ... ange sign if negative" -> "IF (marker_distance < 0) THEN"; the next two lines are lost at the page break and reconstructed from master_measure (D:1300-1301): "marker_distance = (marker_distance * -1)", "ENDIF"
// - D:1262, 1289, 1302, 1303 "skip first" -> "skip_first"; D:1284 "marker number" -> "marker_number"; D:1286 "total dist" -> "total_dist" (spaces for underscores)
// - D:1307, 1331 "FNDIF" -> "ENDIF"
// - D:1336 "svnc flag = 0" -> "sync_flag = 0"
// - D:1338 unterminated "/********" banner closed with "/"
// Not repaired (the manual's own slip, see the corrected copy): "IF (IN 1 == 1) AND (sync_flag == 0) THEN … sync_flag = 1
//   ELSE MOTOR STOP … sync_flag = 0" takes the ELSE branch on the next pass while input 1 stays high (sync_flag is
//   1 then) and re-arms the IF for the pass after: SYNCM and MOTOR STOP alternate and the slave hardly moves.

/******************** Marker synchronizing sample program *********************/
// Inputs:   1 Start/stop synchronization
//           2 Measure slave marker distance
//           3 Measure master marker distance
//           5 Master marker
//           6 Slave marker
//           8 Clear Error
// Outputs:  1 Within synchronizing accuracy, set accuracy window in parameter 33-13
//           2 Marker measurement active
//           8 Error
/*************************** Interrupts ************************************/
ON ERROR GOSUB errhandle
// In case of error go to error handler routine, this must always be included
/****************************** Basic settings ************************************/
VEL 100 // Sets maximum slave velocity related to parameter 32-80 Maximum velocity
ACC 100 // Sets slave acceleration related to parameter 32-81 Shortest ramp
DEC 100 // Sets slave deceleration related to parameter 32-81 Shortest ramp
/**************************** Define application parameters ************************************/
LINKGPAR 1900 "Measuring velocity" 0 100 0
/***************************** Define parameters and flags *********************************/
SET SYNCMTYPM 2 // Set master marker type to external
SET SYNCMTYPS 2 // Set slave marker type to external
sync_flag = 0
/*************************************** main loop ************************************/
MAIN:
IF (IN 1 == 1) AND (sync_flag == 0) THEN // Start synchronizing once when input 1 is high.
SYNCM // Start marker synchronizing mode
sync_flag = 1 // Set done flag
ELSE
MOTOR STOP // Stop when input 1 is low.
sync_flag = 0 // Reset sync_flag after stop.
ENDIF
IF (IN 2 == 1) AND (sync_flag == 0) THEN // Start measuring slave marker distance
GOSUB slave_measure // Note: Slave motor will rotate
ELSEIF (IN 3 == 1) AND (sync_flag == 0) THEN // Start measuring slave marker distance,
GOSUB master_measure // master must run.
ENDIF
GOTO MAIN
/******************************* Sub programs start ***********************************/
SUBMAINPROG
/**************************** Measure slave marker distance *******************************/
SUBPROG slave_measure
OUT 2 1 // Set "Marker measurement active" output
CVEL GET 1900 // Set measuring velocity
CSTART // Start constant velocity mode
old_ipos = IPOS // Read "old" marker position
marker_number = 0 // Reset variable
total_dist = 0 // Reset variable
skip_first = 0 // Reset variable
WHILE (IN 2 == 1) DO // Stay in measuring mode while input 2 high
new_ipos = IPOS // Read "new" marker position
IF (new_ipos != old_ipos) THEN // Check if a new marker was detected
marker_distance = new_ipos - old_ipos // Calculate marker distance
IF (marker_distance < 0) THEN // Change sign if negative
marker_distance = (marker_distance * -1)
ENDIF
IF (skip_first == 0) THEN
                               // Do not use first value as it might be invalid
          skip_first = 1
       ELSE
          marker_number = marker_number + 1 // Increment counter
          total_dist = total_dist + marker_distance // Summarize marker distances
       ENDIF
       old_ipos = new_ipos // Set "old" marker position to "new" marker position
     ENDIF
  ENDWHILE
  CSTOP
                                // Stop when leaving slave marker measurement
  SET SYNCMPULSS (total_dist rnd marker_number)
                                             // calculate average marker distance and set par.
  OUT 2 0
                                // Reset "Marker measurement active" output
RETURN
SUBPROG master_measure
                                // Set "Marker measurement active" output
  OUT 2 1
  old_mipos = MIPOS
                                // Read "old" marker position
  marker_number = 0
                                // Reset variable
  total_dist = 0
                                // Reset variable
                                // Reset variable
  skip_first = 0
  WHILE (IN 2 == 1) DO
                               // Stay in measuring mode while input 2 high
    new_mipos = MIPOS
                               // Read "new" marker position
    IF (new_mipos != old_mipos) THEN
                                             // Check if a new marker was detected
       marker_distance = new_mipos - old_mipos
                                             // Calculate marker distance
       IF (marker_distance < 0) THEN
                                              // Change sign if negative
          marker_distance = (marker_distance * -1)
       ENDIF
       IF (skip_first == 0) THEN // Do not use first value as it might be invalid
          skip_first = 1
       ELSE
          marker_number = marker_number + 1 // Increment counter
          total_dist = total_dist + marker_distance // Summarize marker distances
       ENDIF
       old_mipos = new_mipos // Set "old" marker position to "new" marker position
    ENDIF
  ENDWHILE
  SET SYNCMPULSM (total_dist rnd marker_number)
                                              // calculate average marker distance and set par.
  OUT 2 0
                                // Reset "Marker measurement active" output
RETURN
SUBPROG errhandle
  err = 1
                     // Set error flag to remain in error handler until error is reset.
  OUT 8 1
                    // Set error output
  OUT 2 0
                    // Reset "Marker measurement active" output in case of error
                                  // Remain in error handler until the reset is received
  WHILE err DO
    IF (IN 8) AND NOT (IN 2) THEN
                                   // Reset error when Input 8 is high and input 2+3 low
       ERRCLR
                                   // Clear error
       err=0
                                   // Reset error flag
    ENDIF
  ENDWHILE
  OUT 8 0
                     // Reset error output
                     // Reset sync_flag after error
  sync_flag = 0
RETURN
/********/
            ENDPROG
