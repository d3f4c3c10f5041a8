"""An in-process CAN bus for the virtual drive: python-can buses on one named hub see each other's frames.

Like python-can's ``virtual`` interface, without what costs at 4 000 frames/s: ``virtual`` deep-copies every
message for every receiver and time-stamps it; here a message object is handed on as it is (nobody on the hub
changes one) and a receiver may say which identifiers it wants (`ids`), so the LocalNodes, which serve only SDO
and NMT, do not wake up for every PDO.
"""

from __future__ import annotations

import queue
import threading
from collections.abc import Callable

import can

_hubs: dict[str, list[HubBus]] = {}
_lock = threading.Lock()


class HubBus(can.BusABC):
    def __init__(self, channel: str, ids: set[int] | None = None, **kwargs):
        self.hub = channel
        self.ids = ids
        # a receiver that takes frames in the sender's thread (the drive's bridge into the simulation, whose inject
        # is a deque append): no thread woken per frame, which cost a flooded drive more than the frames did
        self.on_frame: Callable[[can.Message], None] | None = None
        self._queue: queue.SimpleQueue[can.Message] = queue.SimpleQueue()
        self.channel_info = f"motiontool hub {channel}"
        with _lock:
            self._peers = _hubs.setdefault(channel, [])
            self._peers.append(self)
        super().__init__(channel=channel, **kwargs)

    def send(self, msg: can.Message, timeout: float | None = None) -> None:
        can_id = msg.arbitration_id
        for peer in self._peers:      # a list that only grows or shrinks by whole assignments (see shutdown)
            # `ids` are CANopen's 11-bit identifiers: a 29-bit frame with the same number is not for a node that
            # asks for them (CiA 301 uses base frames; extended id 0 + 01 01 stopped node 1)
            if peer is not self and (peer.ids is None or can_id in peer.ids and not msg.is_extended_id):
                if peer.on_frame is not None:
                    peer.on_frame(msg)
                else:
                    peer._queue.put(msg)

    def _recv_internal(self, timeout: float | None) -> tuple[can.Message | None, bool]:
        try:
            return self._queue.get(timeout=timeout), False
        except queue.Empty:
            return None, False

    def shutdown(self) -> None:
        super().shutdown()
        with _lock:
            peers = [p for p in _hubs.get(self.hub, []) if p is not self]
            if peers:
                _hubs[self.hub] = peers
            else:
                _hubs.pop(self.hub, None)
            for peer in peers:
                peer._peers = peers
