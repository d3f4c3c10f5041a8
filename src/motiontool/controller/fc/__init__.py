"""The virtual drive's slave side of the Danfoss FC protocol (the master's side is comms/fc/)."""
