"""DPL programs on a simulated APC behind a Link: the DPL host (``motiontool.dpl.host``) attached to the APC
Link service, its run-time errors and program state turned into the Link's events, its arrays shown to the
array editor. `dpl_link()` is the embedded APC controller the CLI and the IDE run DPL programs on."""

from __future__ import annotations

from motiontool.comms.protocol import LinkEvent
from motiontool.controller.apc_service import ApcService
from motiontool.controller.embedded import EmbeddedLink
from motiontool.dpl.host import DplHost


class DplProgram(DplHost):
    """The program side of one APC service."""

    def __init__(self, service: ApcService):
        super().__init__(service.drive, notify=self._event)
        self.service = service
        self.publish = service.publish       # the service sets it again when it attaches us

    def op_download(self, image, number=None, name="") -> None:
        super().op_download(image, number, name)
        self.service.arrays[:] = self.arrays()

    def _event(self, kind: str, details: dict) -> None:
        if kind == "error":  # as the MCO service reports a program error: the message, then the state
            self.publish(LinkEvent("error", self.service.time_ms, f"{details['file']}:{details['line']}:"
                                   f"{details['col']}: error: {details['text']}", 0, details["line"]))
            self.publish(LinkEvent("program", self.service.time_ms, "program error"))
        else:
            self.publish(LinkEvent("program", self.service.time_ms, details["text"]))


def dpl_link(*, realtime_factor: float | None = None, service: ApcService | None = None) -> EmbeddedLink:
    """An embedded link to a simulated APC that runs DPL programs: synchronous (advance) by default, paced at
    real time × `realtime_factor` when given (the IDE)."""
    service = service or ApcService()
    service.attach_program(DplProgram(service))
    return EmbeddedLink(realtime_factor=realtime_factor, service=service)


def dpl_line(node_count: int, *, four_wire: bool = False):
    """A CTSync line of `node_count` simulated APCs running DPL programs, one Link per node (1..N), one clock;
    2-wire (8 nodes at most) unless `four_wire` (16, L2078)."""
    from motiontool.apc.drive import ApcDrive
    from motiontool.controller.apc_bus import ApcLineBus

    bus = ApcLineBus([ApcDrive() for _ in range(node_count)], four_wire=four_wire)
    for link in bus.links.values():
        link.service.attach_program(DplProgram(link.service))
    return bus

