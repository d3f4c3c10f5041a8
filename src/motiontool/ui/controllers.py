"""The controllers this IDE session can reach, by ID (ide-spec 2.5, 2.8-2.12). For now these are embedded
simulated MCO 305s; a controller keeps running its program when a window selects another one."""

from __future__ import annotations

from motiontool.comms.embedded import EmbeddedLink
from motiontool.comms.link import Link

SIMULATED_IDS = (1, 2, 3, 4)


class ControllerRegistry:
    def __init__(self, realtime_factor: float = 1.0):
        self.realtime_factor = realtime_factor
        self.links: dict[int, Link] = {}

    def link(self, controller_id: int) -> Link:
        """The link to a controller, opened on first use."""
        if controller_id not in SIMULATED_IDS:
            raise ValueError(f"no controller {controller_id} on the simulated interface")
        link = self.links.get(controller_id)
        if link is None or not getattr(link, "alive", True):  # a dead link is replaced, not reused
            if link is not None:
                link.close()
            self.links[controller_id] = EmbeddedLink(realtime_factor=self.realtime_factor)
        return self.links[controller_id]

    def close(self, *, controller_id: int | None = None) -> None:
        """Close Interface (one controller) or Close All Interfaces (None)."""
        for cid in ([controller_id] if controller_id is not None else list(self.links)):
            link = self.links.pop(cid, None)
            if link is not None:
                link.close()

    def open_links(self) -> list[tuple[int, Link]]:
        return sorted(self.links.items())
