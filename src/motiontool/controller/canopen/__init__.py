"""The virtual drive on CAN: the drive's object dictionary as an EDS (eds.py), its controllers as CANopen slaves
(node.py, sdoblock.py) on an in-process bus (hub.py) behind an slcan TCP server (slcan_server.py, server.py). The
master's side is comms/canopen/."""
