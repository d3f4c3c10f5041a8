"""CANopen for motiontool (docs/protocols/canopen.md): the drive's object dictionary as an EDS (eds.py), the objects
that carry the link's services (objects.py), the CANopen link on python-canopen's RemoteNode and the virtual drive's
LocalNodes behind an slcan TCP server."""
