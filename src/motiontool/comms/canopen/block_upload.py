"""An SDO block upload (CiA 301 §7.2.4.3.12) through python-canopen, with its missing abort mended.

When the server does not answer the end of a block upload (a drive stopped or stalled just then), python-canopen
2.4's `BlockUploadStream._end_upload` calls `self.abort`, which the stream does not have: the timeout came out as
an AttributeError, which no caller takes for a missing answer, and a `run --link` whose drive was stopped for a
few seconds died instead of pausing. Here that AttributeError is what it stands for: the abort the library meant
to send is sent (SDO abort code 0x05040000, "SDO protocol timed out") and the timeout is raised as the
SdoCommunicationError it was.
"""

from __future__ import annotations

from canopen.sdo import SdoClient, SdoCommunicationError
from canopen.sdo.client import BlockUploadStream

ABORT_TIMED_OUT = 0x05040000


def block_upload(sdo: SdoClient, index: int, subindex: int = 0) -> bytes:
    """The whole value of `index`:`subindex` by block upload; SdoCommunicationError for a missing answer."""
    try:
        with sdo.open(index, subindex, "rb", buffering=0, block_transfer=True) as raw:
            return b"".join(iter(lambda: raw.read(7), b""))
    except AttributeError as exc:
        timeout = exc.__context__
        if exc.name != "abort" or not isinstance(exc.obj, BlockUploadStream) \
                or not isinstance(timeout, SdoCommunicationError):
            raise
        sdo.abort(ABORT_TIMED_OUT)
        raise timeout from None
