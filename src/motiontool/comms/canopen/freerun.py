"""Free Run (PDO) over CANopen: the oscilloscope's signals mapped into TxPDOs by SDO and received with the
controller's time stamps (DG 4638-4648, 5386-5397, 5432; issue 15 item 3).

Each signal gets a TxPDO of its own carrying the controller clock's low 16 bits (0x2500 sub 0xF0) and the signal
(decision S30): the time of every value is exact and a gap in one TxPDO's stamps is a counted drop, whatever the
transport does to the frames' order or timing. At most four signals: the CAN TxPDOs 1-4, used from 4 downwards so
that PDO 1, the application's default one, stays free as long as possible. The TxPDOs' previous configuration is
read before and written back after the run.

Values are published as the link's ordinary ``samples`` events ({signals, time_ms, values, dropped}), one about
every 20 ms of controller time, rows in time order; a row one of whose values was lost is dropped and counted.
"""

from __future__ import annotations

import struct
import threading
import time
from collections.abc import Callable

from motiontool.comms.protocol import LinkError, LinkEvent
from motiontool.paramdb import ParameterError, database

MAX_SIGNALS = 4
STAMP_OBJECT = (0x2500, 0xF0, 16)
SYS_CLOCK = (0x2500, 23)
PACKET_MS = 20
NOT_VALID = 0x80000000
FORMATS = {8: "b", 16: "h", 32: "i"}


def signal_object(od, name: str) -> tuple[int, int, int, bool]:
    """(index, sub, bits, signed) of the object a scope signal is read from: a link signal (0x2510, named in the
    EDS), a SYSVAR index (4097 … = 0x2500 sub n, 0x01iiiiss = the object) or a parameter (0x2000 + number)."""
    key = str(name).strip()
    if key.upper() in _signal_subs(od):
        index, sub = 0x2510, _signal_subs(od)[key.upper()]
    elif key.isdigit() or key.lower().startswith("0x"):
        number = int(key, 0)
        if 4096 < number <= 4096 + 255:
            index, sub = 0x2500, number - 4096
        elif number >> 24 == 1:
            index, sub = (number >> 8) & 0xFFFF, number & 0xFF
        else:
            raise LinkError(f"signal {key}: SYSVAR {number} is no object of the dictionary; poll it instead")
    else:
        try:
            index, sub = 0x2000 + database().get(key).index, 0
        except ParameterError:
            raise LinkError(f"unknown signal '{key}'") from None
    try:
        var = od[index] if sub == 0 and not hasattr(od[index], "subindices") else od[index][sub]
    except KeyError:
        raise LinkError(f"signal {key}: object 0x{index:04X} sub {sub} is not in the dictionary") from None
    if not var.pdo_mappable or len(var) not in FORMATS:
        raise LinkError(f"signal {key}: object 0x{index:04X} sub {sub} cannot be mapped into a PDO")
    return index, sub, len(var), var.data_type in (0x2, 0x3, 0x4)


def _signal_subs(od) -> dict[str, int]:
    record = od.get(0x2510)
    return {} if record is None else {var.name.upper(): sub for sub, var in record.subindices.items() if sub}


class PdoStream:
    """One Free Run stream of a CanopenLink: `start(signals, interval_ms)`, frames via `on_frame`, `stop()`."""

    def __init__(self, sdo, network, node_id: int, od, publish: Callable[[LinkEvent], object]):
        self.sdo, self.network, self.node_id, self.od, self.publish = sdo, network, node_id, od, publish
        self.signals: list[str] = []
        self.interval = 1
        self.received = 0
        self.dropped = 0               # values lost on the way (gaps in a TxPDO's time stamps)
        self.rows_dropped = 0          # rows not published because a value was missing
        self.published_rows = 0
        self._lock = threading.Lock()
        self._saved: dict[int, dict] = {}
        self._subscriptions: list[tuple[int, Callable]] = []
        self._reset_rows()

    def _reset_rows(self) -> None:
        self._last: list[int | None] = []
        self._base = 0
        self._pending: dict[int, list] = {}
        self._rows: list[tuple[int, list]] = []
        self._newest_complete = -1
        self._rows_started = False
        self._last_publish = time.monotonic()

    @property
    def running(self) -> bool:
        return bool(self.signals)

    # --- set-up by SDO -----------------------------------------------------------------------------------------
    def start(self, signals: list[str], interval_ms: int) -> None:
        self.stop()
        if not signals:
            return
        if len(signals) > MAX_SIGNALS:
            raise LinkError(f"{len(signals)} signals: a CANopen Free Run takes at most {MAX_SIGNALS} per controller "
                            "(one TxPDO each); poll the others")
        objects = [signal_object(self.od, s) for s in signals]
        interval = max(1, int(interval_ms))
        first = MAX_SIGNALS - len(signals) + 1
        with self._lock:
            self._reset_rows()
            self._last = [None] * len(signals)
            self._formats = [struct.Struct("<H" + (FORMATS[bits] if signed else FORMATS[bits].upper()))
                             for _, _, bits, signed in objects]
            self._base = int.from_bytes(self.sdo.upload(*SYS_CLOCK)[:4], "little")
        for column, (obj, pdo) in enumerate(zip(objects, range(first, MAX_SIGNALS + 1), strict=True)):
            cob = self._configure(pdo, obj, interval)
            callback = self._receiver(column)
            self.network.subscribe(cob, callback)
            self._subscriptions.append((cob, callback))
        self.signals, self.interval = [str(s) for s in signals], interval

    def _configure(self, pdo: int, obj: tuple[int, int, int, bool], interval: int) -> int:
        comm, mapping = 0x1800 + pdo - 1, 0x1A00 + pdo - 1
        sdo = self.sdo
        saved = {"cob": _u32(sdo.upload(comm, 1)), "type": sdo.upload(comm, 2), "inhibit": sdo.upload(comm, 3),
                 "event": sdo.upload(comm, 5), "count": sdo.upload(mapping, 0)}
        saved["map"] = [sdo.upload(mapping, k) for k in range(1, saved["count"][0] + 1)]
        self._saved[pdo] = saved
        cob = saved["cob"] & 0x7FF
        index, sub, bits, _ = obj
        stamp_index, stamp_sub, stamp_bits = STAMP_OBJECT
        sdo.download(comm, 1, _pack32(cob | NOT_VALID))
        sdo.download(mapping, 0, bytes([0]))
        sdo.download(mapping, 1, _pack32(stamp_index << 16 | stamp_sub << 8 | stamp_bits))
        sdo.download(mapping, 2, _pack32(index << 16 | sub << 8 | bits))
        sdo.download(mapping, 0, bytes([2]))
        sdo.download(comm, 2, bytes([255]))
        sdo.download(comm, 3, (0).to_bytes(2, "little"))
        sdo.download(comm, 5, interval.to_bytes(2, "little"))
        sdo.download(comm, 1, _pack32(cob))
        return cob

    def stop(self) -> None:
        for cob, callback in self._subscriptions:
            self.network.unsubscribe(cob, callback)
        self._subscriptions = []
        if self.signals:
            with self._lock:
                self._flush(force=True)
        self.signals = []
        saved, self._saved = self._saved, {}
        for pdo, old in saved.items():   # the previous configuration back, in CiA 301 order
            comm, mapping = 0x1800 + pdo - 1, 0x1A00 + pdo - 1
            try:
                self.sdo.download(comm, 1, _pack32(old["cob"] | NOT_VALID))
                self.sdo.download(mapping, 0, bytes([0]))
                for k, entry in enumerate(old["map"], start=1):
                    self.sdo.download(mapping, k, entry)
                self.sdo.download(mapping, 0, old["count"])
                for sub, key in ((2, "type"), (3, "inhibit"), (5, "event")):
                    self.sdo.download(comm, sub, old[key])
                self.sdo.download(comm, 1, _pack32(old["cob"]))
            except Exception:  # noqa: BLE001 - the drive may be gone; the stream is stopped either way
                pass

    # --- reception (python-can's notifier thread) ----------------------------------------------------------
    def _receiver(self, column: int) -> Callable:
        def on_frame(can_id: int, data: bytes, timestamp: float) -> None:
            fmt = self._formats[column]
            if len(data) < fmt.size:
                return
            stamp, value = fmt.unpack_from(data)
            with self._lock:
                self._take(column, stamp, value)
        return on_frame

    def _take(self, column: int, stamp: int, value: int) -> None:
        self.received += 1
        delta = ((stamp - self._base + 0x8000) & 0xFFFF) - 0x8000   # the 16-bit stamp unwrapped near the base
        t = self._base + delta
        self._base = max(self._base, t)
        last = self._last[column]
        if last is not None and t - last > self.interval:
            self.dropped += (t - last) // self.interval - 1
        self._last[column] = t if last is None else max(last, t)
        row = self._pending.setdefault(t, [None] * len(self._last))
        row[column] = value
        if all(v is not None for v in row):
            del self._pending[t]
            self._rows.append((t, row))
            self._newest_complete = max(self._newest_complete, t)
            for old in [k for k in self._pending if k < self._newest_complete]:
                del self._pending[old]          # a value of that row was lost: the row cannot be completed
                if self._rows_started:          # (rows before the first complete one predate the last TxPDO)
                    self.rows_dropped += 1
            self._rows_started = True
        self._flush()

    def _flush(self, force: bool = False) -> None:
        rows = self._rows
        if not rows:
            return
        if not force and rows[-1][0] - rows[0][0] < PACKET_MS - self.interval and \
                time.monotonic() - self._last_publish < PACKET_MS / 1000:
            return
        rows.sort(key=lambda r: r[0])
        self._rows = []
        self._last_publish = time.monotonic()
        self.published_rows += len(rows)
        data = {"signals": list(self.signals), "time_ms": [t for t, _ in rows], "values": [v for _, v in rows],
                "dropped": self.dropped}
        self.publish(LinkEvent("samples", rows[-1][0], data=data))


def _pack32(value: int) -> bytes:
    return (value & 0xFFFFFFFF).to_bytes(4, "little")


def _u32(data: bytes) -> int:
    return int.from_bytes(bytes(data)[:4].ljust(4, b"\0"), "little")
