"""The Tune oscilloscope (ide-spec 6.60, DG 4704-4712): a test move recorded and measured, repeated with other
PID parameters (32-6*), runs overlaid.

The manual only names the pieces (a "Default Test Configuration", an optional state-machine program, 32-68
REVERS, the 32-6* PID parameters). Decision: a built-in APOSS test program (VEL/ACC/DEC, POSR distance, WAITAX,
a settle delay) is downloaded as the temporary program and started; the scope records CPOS, APOS, TRACKERR
and AVEL as a Single Shot at 1 ms; when the program has ended the recording is uploaded and measured:
- overshoot: how far APOS passes the target in the direction of the move (UU, ≥ 0);
- settling time: from the end of the commanded profile (CPOS reaches the target) until APOS stays inside
  ±band of the target for the rest of the run, at least 100 ms (None if it never settles);
- peak tracking error: max |TRACKERR|.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field

import numpy as np

from motiontool.aposs.driver import compile_source
from motiontool.comms.link import Link
from motiontool.scope.acquisition import Run, _now, recorded_start
from motiontool.scope.curves import Curve, Group, Scope, Source

SIGNALS = ("CPOS", "APOS", "TRACKERR", "AVEL")
PID_PARAMETERS = ("KPROP", "KDER", "KINT", "KILIM", "BANDWIDTH", "FFVEL", "FFACC")  # 32-60 … 32-66


@dataclass
class TestConfiguration:
    """Settings → Oscilloscope → Default Test Configuration (DG 6003-6005)."""
    distance: int = 50_000      # UU, relative move; negative moves backwards
    velocity: int = 100         # VEL (% of VELMAX)
    acceleration: int = 100     # ACC and DEC (% of the shortest ramp)
    settle_ms: int = 500        # recorded after the profile ends
    band: float = 10.0          # settling band ± UU
    max_ms: int = 30_000        # the recording's limit (4 values × 30 000 fit the dynamic memory)

    def validate(self) -> None:
        if self.distance == 0:
            raise ValueError("test distance 0: the axis would not move")
        for name in ("velocity", "acceleration"):
            value = getattr(self, name)
            if not 1 <= value <= 100:
                raise ValueError(f"test {name} {value}: 1..100")
        if self.settle_ms < 0 or self.band <= 0:
            raise ValueError("settle time ≥ 0 ms and band > 0 UU")

    def program(self) -> str:
        return (f"// Tune test move (motiontool)\nVEL {self.velocity}\nACC {self.acceleration}\n"
                f"DEC {self.acceleration}\nPOSR {self.distance}\nWAITAX\nDELAY {self.settle_ms}\n")


@dataclass
class TuneResult:
    run: int
    parameters: dict[str, int]
    overshoot: float
    settling_ms: float | None
    peak_tracking_error: float
    samples: int
    curves: list[str] = field(default_factory=list)

    def to_dict(self) -> dict:
        return asdict(self)


def measure(t: np.ndarray, cpos: np.ndarray, apos: np.ndarray, trackerr: np.ndarray, target: float,
            direction: float, band: float, hold_ms: float = 100.0) -> tuple[float, float | None, float]:
    """(overshoot, settling time ms, peak |tracking error|) of one recorded move. Settled means inside the
    band for the rest of the recording and at least `hold_ms`; an axis still ringing at the end has None."""
    overshoot = max(0.0, float(np.max((apos - target) * direction))) if apos.size else 0.0
    at_target = np.nonzero(np.abs(cpos - target) < 0.5)[0]
    settling = None
    if at_target.size:
        t_end = t[at_target[0]]
        outside = np.nonzero(np.abs(apos - target) > band)[0]
        if not outside.size:
            settling = 0.0
        elif t[-1] - t[outside[-1]] >= hold_ms:  # inside for long enough before the recording ends
            settling = max(0.0, float(t[outside[-1] + 1] - t_end))
    peak = float(np.max(np.abs(trackerr))) if trackerr.size else 0.0
    return overshoot, settling, peak


class Tune:
    """Runs test moves on the link and keeps every run's curves in the scope, overlaid (time from the run's
    start). The caller moves time: `begin()`, then `finished()` until true, then `finish()`."""

    def __init__(self, scope: Scope, link: Link, config: TestConfiguration | None = None):
        self.scope, self.link = scope, link
        self.config = config or TestConfiguration()
        self.results: list[TuneResult] = []
        self._start_cpos = 0.0
        self._parameters: dict[str, int] = {}
        self.running = False

    def read_parameters(self) -> dict[str, int]:
        return {name: int(self.link.read_parameter(name)) for name in PID_PARAMETERS}

    @property
    def run_parameters(self) -> dict[str, int]:
        """The gains read at the start of the last run (after the panel's writes)."""
        return dict(self._parameters)

    def write_parameters(self, values: dict[str, int]) -> None:
        for name, value in values.items():
            self.link.write_parameter(name, int(value))

    def begin(self) -> None:
        cfg = self.config
        cfg.validate()
        result = compile_source(cfg.program(), "tune.m")
        if not result.ok:  # the built-in program always compiles; a failure is a bug worth naming
            raise RuntimeError("tune program: " + "; ".join(d.format() for d in result.diagnostics))
        assert result.image is not None  # compile_source leaves it None only with an error
        if self.link.status().program_state == "running":
            raise ValueError("the controller is executing a program: stop it before a test move")
        self._start_cpos = float(self.link.read_signals(["CPOS"])[0])
        self._parameters = self.read_parameters()
        self.link.download(result.image.to_bytes())
        self.link.start()
        self.link.start_recording(list(SIGNALS), interval_ms=1, destination="DYNMEM", cyclic=False,
                                  count=cfg.max_ms)
        self.running = True

    def finished(self) -> bool:
        status = self.link.status()
        if status.program_state in ("ended", "error", "idle"):
            return True
        rec = self.link.recording_status()
        return rec is None or not rec.running

    def finish(self, *, run: Run = _now) -> TuneResult:
        """`run` makes the upload request (on a thread in the IDE); the curves are made where this is called."""
        self.running = False
        data = run(self.link.stop_recording)
        t = np.asarray(data.time_ms, dtype=float)
        v = np.asarray(data.samples, dtype=float).reshape(t.size, len(SIGNALS))
        recorded_at = float(t[0]) if t.size else None
        if t.size:
            t = t - t[0]
        cfg = self.config
        number = len(self.results) + 1
        # positions relative to where the run started, so runs overlay; later runs share run 1's axes
        v[:, 0] -= self._start_cpos
        v[:, 1] -= self._start_cpos
        first_run = self.results[0].curves if self.results else None
        # the commanded end position is the target (POSR counts from the simulator's actual position)
        target = float(v[-1, 0]) if t.size else float(cfg.distance)
        overshoot, settling, peak = measure(t, v[:, 0], v[:, 1], v[:, 2], target, np.sign(cfg.distance),
                                            cfg.band)
        # on the time base of what the scope holds (a TESTSETP set sits at its controller time, decision S15)
        t = t + (recorded_start(self.scope) or 0.0)
        group = self.scope.add_group(Group(f"Tune run {number}", method="single_shot", interval_ms=1,
                                           count=cfg.max_ms))
        names = []
        for j, signal in enumerate(SIGNALS):
            curve = Curve(f"Run {number}: {signal}", Source(method="single_shot", signal=signal, group=group.name,
                                                          info={"run": number, "recorded_at_ms": recorded_at}),
                          unit="UU/s" if signal == "AVEL" else "UU", first_of_set=j == 0)
            curve.buffer.set_capacity(max(t.size, 1))
            curve.buffer.extend(t, v[:, j])
            if first_run is not None and first_run[j] in {c.name for c in self.scope.curves}:
                curve.axis.share = first_run[j]
            names.append(self.scope.add_curve(curve).name)
        result = TuneResult(number, dict(self._parameters), overshoot, settling, peak, int(t.size), names)
        self.results.append(result)
        return result

    def run_synchronously(self, step_ms: int = 100) -> TuneResult:
        """For a synchronous embedded link (tests, CLI): move virtual time until the test is done."""
        self.begin()
        for _ in range(self.config.max_ms // step_ms + 1):
            if self.finished():
                break
            self.link.advance(step_ms)
        return self.finish()
