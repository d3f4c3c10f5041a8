"""The Control Techniques Advanced Position Controller (Unidrive SP + SM-Applications) as a simulated
controller, beside the MCO 305 kernel; no Qt. The public API is documented in docs/apc.md.

    from motiontool.apc import ApcDrive, CTSyncLine
"""

from motiontool.apc.aliases import ALIASES
from motiontool.apc.ctsync import CTSyncLine
from motiontool.apc.drive import SIGNATURES, ApcDrive, Signature, signature
from motiontool.apc.plant import PlantConfig, SlotEncoder
from motiontool.apc.readpars import READ_PARAMETERS, parameter_number

__all__ = ["ALIASES", "CTSyncLine", "SIGNATURES", "READ_PARAMETERS", "ApcDrive", "PlantConfig", "Signature",
           "SlotEncoder", "parameter_number", "signature"]
