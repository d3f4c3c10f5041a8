"""Getting data from the controller into curves, through a comms Link only (DG 4634-4712).

- FreeRun: the link streams a group's signals (PDO-like) at the group's interval; `samples` events are fed in.
- Polling: each curve is read (SDO-like) once per poll; the load this puts on the bus is estimated.
- SingleShot: the controller records (start_recording); on Stop the recording is uploaded at once.
- TESTSETP: finds the recordings a program made and uploads the chosen ones as curve sets.

Events from a threaded link arrive on the kernel thread; the Qt view routes them into the GUI thread itself
and calls `feed`, so these classes never subscribe on their own unless asked to (`subscribe=True`).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

import numpy as np

from motiontool.comms.client import RecordingInfo, RecordingStatus
from motiontool.comms.link import Link
from motiontool.comms.protocol import LinkEvent
from motiontool.scope.curves import Curve, Group, Scope, Source, signal_label
from motiontool.scope.select import apply, canonical, parse_selection, split_signal, with_suffix
from motiontool.scope.trigger import Capture, Trigger

Run = Callable[[Callable[[], Any]], Any]   # runs a link request and returns its answer


def _now(request: Callable[[], Any]) -> Any:
    return request()


SYS_CLOCK = "4119"          # SYSVAR sys_clock (docs/sysvar.md): a poll reads it to time-stamp its values
# Bus load of a poll (DG 5406-5418 gives no formula): every polled curve costs one expedited SDO upload,
# request + response = 2 CAN frames of at most 135 bits with stuffing. The load is the bus time those
# frames take per poll interval at the interface's bit rate.
SDO_BITS_PER_READ = 2 * 135


def polling_load(curves: int, poll_ms: float, bitrate: int) -> float:
    """Estimated bus load in % of polling `curves` SDOs every `poll_ms` at `bitrate` bit/s."""
    if poll_ms <= 0:
        raise ValueError(f"poll rate {poll_ms} ms: must be positive")
    return 100.0 * curves * SDO_BITS_PER_READ / bitrate / (poll_ms / 1000.0)


def new_curve(scope: Scope, signal: str, group: str, method: str, axis: int = 1, name: str | None = None,
              unit: str = "", select: str | None = None) -> Curve:
    """A curve of a link signal. A byte/word/bit selection comes from `select` or an APOSS suffix typed after
    the signal ("4104.b2", "APOS.3"); the default name then ends in it: "1: SYSVAR [4104].b2"."""
    signal, suffix = split_signal(str(signal))
    select = canonical(select) if select is not None else suffix
    curve = Curve(name or with_suffix(signal_label(signal, axis), select),
                  Source(method=method, signal=signal, group=group, select=select),
                  unit=unit or ("" if select else default_unit(signal)))
    return scope.add_curve(curve)


def default_unit(signal: str) -> str:
    s = str(signal).upper()
    if s in ("APOS", "CPOS", "TRACKERR"):
        return "UU"
    if s in ("AVEL", "CVEL"):
        return "UU/s"
    if s in ("4097", "4098", "4102", "0X01250001", "0X01250002", "0X01250006"):
        return "qc"
    return ""


class FreeRun:
    """One Free Run group streamed by the link (DG 4638-4648)."""

    def __init__(self, scope: Scope, link: Link, group: str, subscribe: bool = False):
        self.scope, self.link, self.group = scope, link, group
        self.running = False
        self.dropped = 0            # packets whose signals did not match the group (another stream)
        self.link_dropped: int | None = None  # values the link lost on the way, when it counts them (PDOs)
        self.received = 0
        self.last_event_time: float | None = None  # wall clock of the last packet (latency measurement)
        self._subscribed = subscribe
        self._signals: list[str] = []
        self._curves: list[Curve] = []
        # Triggered capture (beyond the manual): (curve name, Trigger); single = stop after one capture,
        # else re-arm and show the newest capture, like a scope's "normal" mode.
        self.trigger: tuple[str, Trigger] | None = None
        self.single = True
        self.capture: Capture | None = None
        self.captures = 0

    def curves(self) -> list[Curve]:
        return [c for c in self.scope.members(self.group) if c.active]

    def start(self, clear: bool = True, *, run: Run = _now) -> None:
        """`run(request)` makes the link request (a window runs it on a thread and paints meanwhile)."""
        group = self.scope.group(self.group)
        curves = self.curves()
        if not curves:
            raise ValueError(f"group '{self.group}' has no active curve")
        if clear:
            for c in curves:
                c.buffer.clear()
        self._curves = curves   # fixed for the run: columns of the stream
        self._signals = [c.source.signal for c in curves]
        self.capture = None
        if self.trigger is not None:
            name, trig = self.trigger
            column = [c.name for c in curves].index(name)  # ValueError: the trigger curve is not recorded
            trig.signal = column
            self.capture = Capture(trig, len(curves))
        if self._subscribed:
            self.link.subscribe(self._on_event)
        self.running = True    # before the request: packets that come while it is answered are the run's
        try:
            run(lambda: self.link.stream(self._signals, interval_ms=group.interval_ms))
        except BaseException:
            self.running = False
            raise

    def stop(self, *, run: Run = _now) -> None:
        if self.running:
            run(lambda: self.link.stream([], interval_ms=1))
            if self._subscribed:
                self.link.unsubscribe(self._on_event)
        self.running = False

    def _on_event(self, event: LinkEvent) -> None:
        if event.kind == "samples":
            self.feed(event.data)

    def feed(self, data: dict) -> None:
        """One `samples` packet {signals, time_ms, values}."""
        if not self.running:
            return
        if list(data.get("signals", [])) != self._signals:
            self.dropped += 1
            return
        if "dropped" in data:
            self.link_dropped = int(data["dropped"])
        t = np.asarray(data["time_ms"], dtype=float)
        v = np.asarray(data["values"], dtype=float).reshape(t.size, len(self._signals))
        # byte/word/bit curves: select before the trigger sees the values; read per packet, as Properties may
        # change a curve's selection while it runs
        selections = [parse_selection(c.source.select) for c in self._curves]
        if any(selections):
            v = v.copy()
            for j, sel in enumerate(selections):
                if sel is not None:
                    v[:, j] = sel.apply(v[:, j])
        self.received += 1
        self.last_event_time = time.monotonic()
        if self.capture is not None:
            self.capture.feed(t, v)
            if not self.capture.done:
                return
            t, v = self.capture.result()
            for c in self._curves:
                c.buffer.clear()
            self.captures += 1
            if self.single:
                self.capture = None
                self.stop()
            else:
                self.capture.reset()
        for j, curve in enumerate(self._curves):
            curve.buffer.extend(t, v[:, j])


class Polling:
    """Free Run in polling mode: "Polled (no group)" curves read once per poll (DG 4650-4660, 5406-5418)."""

    def __init__(self, scope: Scope, link: Link):
        self.scope, self.link = scope, link
        self.running = False
        self.polls = 0
        self.request_seconds = 0.0   # measured time the link needed for the reads
        self.runs = 0                # Start counts: a read of an earlier run that answers late is not taken
        self._last_time: float | None = None

    def curves(self) -> list[Curve]:
        return [c for c in self.scope.curves if c.source.method in ("polled", "variable") and c.active]

    @property
    def load(self) -> float:
        s = self.scope.settings
        return polling_load(len(self.curves()), s.poll_ms, s.bus_bitrate)

    def title(self) -> str:
        """The window-title suffix while recording: "[<poll ms>ms <load>%]" (DG 5416)."""
        return f"[{self.scope.settings.poll_ms}ms {self.load:.0f}%]"

    def start(self, clear: bool = True) -> None:
        if not self.curves():
            raise ValueError("no active polled curve")
        if clear:
            for c in self.curves():
                c.buffer.clear()
        self._last_time = None
        self.runs += 1
        self.running = True

    def stop(self) -> None:
        self.running = False

    def poll(self) -> None:
        """Read every polled curve once and add the values (a test, the CLI; the scope window reads on a thread
        of its own with `read` and adds with `take`)."""
        if self.running:
            self.take(*self.read())

    def read(self) -> tuple[list[Curve], list]:
        """The polled curves and their values, the controller's time last: the link requests only, no curve is
        touched (so a worker thread may ask them while the window draws)."""
        curves = self.curves()
        signals = [c for c in curves if c.source.method != "variable"]
        variables = [c for c in curves if c.source.method == "variable"]
        link = self.link
        if link is None:
            raise ValueError("no controller to poll")
        began = time.perf_counter()
        values = link.read_signals([c.source.signal for c in signals] + [SYS_CLOCK])
        if variables:  # program variables (DG 5552-5622) come from the debug read of the running program
            values[-1:-1] = link.read_variables([c.source.signal for c in variables])
        self.request_seconds += time.perf_counter() - began
        return signals + variables, values

    def take(self, curves: list[Curve], values: list) -> None:
        """Add one poll's values (`read`) to its curves."""
        now = float(values[-1])
        if now == self._last_time:   # the controller's clock stood since the last poll (a busy simulator host):
            return                   # the same instant twice is no new sample
        self._last_time = now
        for c, v in zip(curves, values[:-1], strict=True):
            c.buffer.append(now, float(v) if c.source.select is None else float(apply(c.source.select, [v])[0]))
        self.polls += 1


class SingleShot:
    """A Single Shot group: the controller records, Stop uploads (DG 4662-4674, 5287-5324, 5867-5869)."""

    def __init__(self, scope: Scope, link: Link, group: str):
        self.scope, self.link, self.group = scope, link, group
        self.running = False
        self.limit = 0

    def curves(self) -> list[Curve]:
        return [c for c in self.scope.members(self.group) if c.active]

    def start(self, *, run: Run = _now) -> None:
        g = self.scope.group(self.group)
        curves = self.curves()
        if not curves:
            raise ValueError(f"group '{self.group}' has no active curve")
        status = run(lambda: self.link.start_recording([c.source.signal for c in curves], interval_ms=g.interval_ms,
                                                       destination=g.destination, cyclic=g.cyclic, count=g.count))
        self.limit = status.limit
        for c in curves:
            c.buffer.clear()
            if c.buffer.capacity < self.limit:
                c.buffer.set_capacity(self.limit)
        self.running = True

    def status(self) -> RecordingStatus | None:
        return self.link.recording_status()

    def stop(self, *, run: Run = _now) -> int:
        """Upload the recording into the curves; returns the number of sets."""
        if not self.running:
            return 0
        self.running = False
        data = run(self.link.stop_recording)
        t = np.asarray(data.time_ms, dtype=float)
        v = np.asarray(data.samples, dtype=float).reshape(t.size, len(data.signals))
        for c, j in zip(self.curves(), range(v.shape[1]), strict=False):
            c.buffer.extend(t, apply(c.source.select, v[:, j]))
            c.source.info = {"recording": data.name, "interval_ms": data.interval_ms, "start_ms": data.start_ms}
        return int(t.size)


def list_testsetp(link: Link) -> list[RecordingInfo]:
    """The TESTSETP recordings on the controller (DG 5326-5347)."""
    return link.list_recordings()


def recorded_start(scope: Scope, exclude: Curve | None = None) -> float | None:
    """Where the recordings already in the scope start: the earliest first sample of its recorded curves."""
    starts = [c.raw()[0][0] for c in scope.curves
              if c is not exclude and c.source.method not in ("derived",) and len(c.buffer)]
    return min(starts) if starts else None


def load_testsetp(scope: Scope, link: Link, index: int, axis: int = 1, label: str = "", *,
                  run: Run = _now) -> list[Curve]:
    """Upload recording `index` and add one curve per recorded value, named "Axis: Name [Index]"; the first
    of the set gets the grey background (DG 5339-5345). A recording added to a scope that holds curves starts
    where they start, so runs lie over each other as in S23's difference of two runs (decision S15); the
    controller time of its first sample stays in the curve's Source info. `run` makes the request (on a thread in
    the IDE); the curves are made where this is called."""
    data = run(lambda: link.upload_recording(index))
    curves = []
    n = len(data.samples)
    first = data.first_ms
    start = recorded_start(scope)
    t = (first if start is None else start) + np.arange(n, dtype=float) * data.interval_ms
    values = np.asarray(data.samples, dtype=float).reshape(n, len(data.indices))
    for j, (idx, name) in enumerate(zip(data.indices, data.names, strict=True)):
        curve_name = f"{label}{axis}: {name} [{idx}]"
        curve = Curve(curve_name, Source(method="testsetp", signal=str(idx), group="", controller=1,
                                         info={"recording": data.name, "index": index,
                                               "interval_ms": data.interval_ms, "recorded_at_ms": first}),
                      unit=default_unit(str(idx)), first_of_set=j == 0)
        curve.buffer.set_capacity(max(n, 1))
        curve.buffer.extend(t, values[:, j])
        curves.append(scope.add_curve(curve))
    return curves


def reload_testsetp(scope: Scope, link: Link, curve: Curve, *, run: Run = _now) -> None:
    """Reload: fetch the curve's recording again (after the program re-ran) and replace the data."""
    name = curve.source.info.get("recording")
    if curve.source.method != "testsetp" or name is None:
        raise ValueError(f"curve '{curve.name}' has no recording to reload")
    same = [r.index for r in run(link.list_recordings) if r.name == name]  # the newest run of it
    if not same:
        raise ValueError(f"the controller has no recording '{name}' any more")
    data = run(lambda: link.upload_recording(same[-1]))
    curve.source.info["index"] = same[-1]
    n = len(data.samples)
    j = [str(i) for i in data.indices].index(curve.source.signal)
    first = data.first_ms
    start = curve.raw()[0][0] if len(curve.buffer) else recorded_start(scope, exclude=curve)
    t = (first if start is None else start) + np.arange(n, dtype=float) * data.interval_ms
    curve.source.info["recorded_at_ms"] = first
    curve.buffer.set_capacity(max(n, 1))
    curve.buffer.clear()
    curve.buffer.extend(t, np.asarray(data.samples, dtype=float).reshape(n, -1)[:, j])


def default_group(scope: Scope, method: str) -> Group:
    """The group a variant adds on start: "Test Group (Free Run)" / "Test Group (Single Shot)" (DG 5289)."""
    name = "Test Group (Free Run)" if method == "free_run" else "Test Group (Single Shot)"
    return scope.add_group(Group(name, method=method))
