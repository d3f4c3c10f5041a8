"""The master's side of CANopen (docs/protocols/canopen.md): the objects that carry the link's services and the
EDS the drive ships (objects.py), the CANopen link on python-canopen's RemoteNode (link.py) with its slcan TCP bus
(slcan.py) and Free Run PDOs (freerun.py). The drive's side is controller/canopen/."""
