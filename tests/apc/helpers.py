"""Set-ups shared by the APC tests."""

from motiontool.apc import ApcDrive
from motiontool.apc.intmath import UnsignedBottomWord, UnsignedTopWord


def enabled_drive(**kwargs) -> ApcDrive:
    """A drive with the APC enabled and the output channel driving the plant (#1.21, as the examples do)."""
    d = ApcDrive(**kwargs)
    d.APCSetupOutputChannel(2, 0, 0)
    d.APCEnableOutputChannel()
    d.APCSetRunMode(2)
    d.tick()
    d.tick()
    return d


class VirtualMaster:
    """A user-program reference source counting `per_sample` counts every POS sample (§8.4)."""

    def __init__(self, drive: ApcDrive, per_sample: int = 0):
        self.drive = drive
        self.per_sample = per_sample
        self.counter = 0
        drive.APCSetReferenceSource(4)
        drive.pos0 = self.pos0

    def pos0(self) -> None:
        self.counter += self.per_sample
        self.drive.APCSetReferencePosition(UnsignedTopWord(self.counter), UnsignedBottomWord(self.counter), 0)
