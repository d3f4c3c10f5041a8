"""APC CAM tables (seed 004 §4.7, L1224-1704; spec §2), the CAM editor's second curve kind — Qt-free.

An APC CAM is a list of segments, each a master length X (``InArray%``), a slave travel Y (``OutArray1%``), an
interpolation law (``InterpolationArray%``, 0 Linear … 5 Cosine2) and an optional linear second slave travel
(``OutArray2%``); all are relative increments in counts. A start index and a size choose the segments used; an
output ratio N/D scales the slave with its remainder carried. The slave inside a segment is the kernel's own
`camlaws.law_value`, so what the editor draws is what the simulated APC produces, count for count.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from fractions import Fraction

from motiontool.apc.camlaws import LAW_NAMES, law_value

INT32_MAX = (1 << 31) - 1
INDEX_MAX = 65535                     # start index and size (L3500-3522)
# Slave speed relative to the average Y/X at the start and at the end of a segment, per law (L1393-1498):
# Linear Y/X; Cosine from rest to rest; Square1/Cosine1 end at 2Y/X; Square2/Cosine2 start there.
_START = (Fraction(1), Fraction(0), Fraction(0), Fraction(2), Fraction(0), Fraction(2))
_END = (Fraction(1), Fraction(0), Fraction(2), Fraction(0), Fraction(2), Fraction(0))
MODE_ARRAY, MODE_LINEAR, MODE_COSINE = -1, 0, 1


class ApcTableError(ValueError):
    """A table that cannot be used; `field` names what is wrong, `segment` the 0-based segment if any."""

    def __init__(self, field: str, message: str, segment: int | None = None):
        super().__init__(f"{field}: {message}")
        self.field, self.message, self.segment = field, message, segment


@dataclass(frozen=True)
class ApcSegment:
    master: int       # X: master counts (InArray%)
    slave: int        # Y: slave counts (OutArray1%)
    law: int = 0      # interpolation code 0..5 (InterpolationArray%)
    slave2: int = 0   # additive linear slave counts (OutArray2%)

    def start_speed(self) -> Fraction:
        """Slave counts per master count at the start of the segment."""
        return (_START[self.law] * self.slave + self.slave2) / self.master

    def end_speed(self) -> Fraction:
        return (_END[self.law] * self.slave + self.slave2) / self.master


@dataclass(frozen=True)
class Finding:
    severity: str     # "error" | "warning"
    message: str
    segment: int | None = None


@dataclass(frozen=True)
class ApcCamTable:
    """One APC CAM: its segments and the settings that go with them (names as the DPL calls)."""

    name: str = "Cam"
    segments: tuple[ApcSegment, ...] = field(default_factory=tuple)
    start: int = 0                      # APCSetCAMStartIndex
    size: int | None = None             # APCSetCAMSize; None = every segment from the start
    ratio: tuple[int, int] = (1000, 1000)   # APCSetCAMOutRatioNumerator / Denominator
    single_shot: bool = False
    delta_seg_limit: int = 256          # APCSetCAMDeltaSegLimit

    def __post_init__(self) -> None:
        object.__setattr__(self, "segments", tuple(self.segments))
        if self.size is not None and self.start + self.size == len(self.segments):
            object.__setattr__(self, "size", None)  # one form for "to the end", so equal tables compare equal
        self.validate()

    # --- structure -------------------------------------------------------------------------------------------
    def validate(self) -> None:
        """Raise ApcTableError for a table the APC could not run (sizes, zero-length segments, ranges)."""
        if not self.name.isidentifier() or not self.name.isascii():
            raise ApcTableError("name", f"{self.name!r}: letters, digits and '_' (it names the DPL arrays)")
        if not self.segments:
            raise ApcTableError("segments", "a CAM needs at least one segment")
        for i, s in enumerate(self.segments):
            for attr in ("master", "slave", "law", "slave2"):
                value = getattr(s, attr)
                if not isinstance(value, int) or isinstance(value, bool):
                    raise ApcTableError("segments", f"segment {i}: {attr} must be a whole number of counts", i)
            if s.master <= 0:
                raise ApcTableError("segments", f"segment {i}: master length {s.master}: every segment needs a "
                                                "master length of at least one count", i)
            if not -INT32_MAX <= s.slave <= INT32_MAX or not -INT32_MAX <= s.slave2 <= INT32_MAX \
                    or s.master > INT32_MAX:
                raise ApcTableError("segments", f"segment {i}: values must fit in 32 bits", i)
            if not 0 <= s.law < len(LAW_NAMES):
                raise ApcTableError("segments", f"segment {i}: law {s.law} (0 Linear … 5 Cosine2)", i)
        if not 0 <= self.start <= INDEX_MAX or self.start >= len(self.segments):
            raise ApcTableError("start", f"start index {self.start} outside the {len(self.segments)} segments")
        size = self.used
        if not 1 <= size <= INDEX_MAX or self.start + size > len(self.segments):
            raise ApcTableError("size", f"size {size} from index {self.start}: the arrays have {len(self.segments)} "
                                        "elements (size 0 selects Stop, 90.49 = 3)")
        n, d = self.ratio
        if not 0 <= n <= INT32_MAX or not 1 <= d <= INT32_MAX:
            raise ApcTableError("ratio", f"{n}/{d}: numerator 0 … 2^31-1, denominator 1 … 2^31-1")
        if not 0 <= self.delta_seg_limit <= INDEX_MAX:
            raise ApcTableError("delta_seg_limit", f"{self.delta_seg_limit} (0 … 65535)")

    @property
    def used(self) -> int:
        return len(self.segments) - self.start if self.size is None else self.size

    @property
    def window(self) -> tuple[ApcSegment, ...]:
        return self.segments[self.start:self.start + self.used]

    @property
    def mode(self) -> int:
        """The interpolation mode to select: linear or cosine when every segment has that law, else per array."""
        laws = {s.law for s in self.window}
        if laws == {0}:
            return MODE_LINEAR
        if laws == {1}:
            return MODE_COSINE
        return MODE_ARRAY

    @property
    def has_slave2(self) -> bool:
        return any(s.slave2 for s in self.segments)

    @property
    def master_length(self) -> int:
        """Master counts of one cycle (ΣIn over the window)."""
        return sum(s.master for s in self.window)

    @property
    def slave_travel(self) -> int:
        """Slave counts of one cycle before the ratio (ΣOut1 + ΣOut2); the worked example's 600748 (L1259)."""
        return sum(s.slave + s.slave2 for s in self.window)

    def with_segments(self, segments) -> ApcCamTable:
        return replace(self, segments=tuple(segments))

    # --- what the APC does with it ---------------------------------------------------------------------------
    def slave_at(self, master: int) -> int:
        """Slave counts (before the ratio) after `master` counts from the start of the window, in the cycle
        0 … master_length: whole segments plus the law inside the current one, as the kernel computes it."""
        if not 0 <= master <= self.master_length:
            raise ValueError(f"master {master} outside the cycle 0 … {self.master_length}")
        total = 0
        for s in self.window:
            if master < s.master:
                return total + law_value(s.law, master, s.master, s.slave) + law_value(0, master, s.master, s.slave2)
            total += s.slave + s.slave2
            master -= s.master
        return total

    def reference(self, master: int) -> int:
        """The CAM reference after `master` counts from a zero-reset engagement, cycles repeating (single shot:
        holding at the end), after the output ratio with its remainder carried: ⌊N·slave/D⌋."""
        length = self.master_length
        if self.single_shot:  # one cycle, then the slave stays where it ended
            cycles, within = 0, min(max(master, 0), length)
        else:
            cycles, within = divmod(master, length)
        slave = cycles * self.slave_travel + self.slave_at(within)
        n, d = self.ratio
        return (slave * n) // d

    def samples(self, points: int = 1000, cycles: int = 1) -> tuple[list[int], list[int]]:
        """(master, reference) at `points` evenly spread master positions over `cycles` cycles (the drawing)."""
        total = self.master_length * cycles
        masters = [round(total * k / (points - 1)) for k in range(points)]
        return masters, [self.reference(m) for m in masters]

    # --- engineering checks ----------------------------------------------------------------------------------
    def check(self, master_speed: float | None = None, pos_period_ms: float = 1.0) -> list[Finding]:
        """What a user should look at before running the table: speed steps at the joins of the segments (also
        from the last to the first in a cyclic CAM), and with the maximum master speed (counts/s) whether one POS
        sample could cross more segments than the delta-segment limit allows (Stop and Tr81, L3524-3546)."""
        findings: list[Finding] = []
        window = self.window
        joins = list(zip(range(len(window)), range(1, len(window)), strict=False))
        if not self.single_shot and len(window) > 1:
            joins.append((len(window) - 1, 0))
        for a, b in joins:
            end, start = window[a].end_speed(), window[b].start_speed()
            if end != start:
                findings.append(Finding("warning", f"speed step between segments {self.start + a} and "
                                                   f"{self.start + b}: {float(end):.4g} → {float(start):.4g} "
                                                   "slave counts per master count", self.start + b))
        if master_speed is not None:
            per_sample = abs(master_speed) * pos_period_ms / 1000
            shortest = min(window, key=lambda s: s.master)
            crossed = per_sample / shortest.master
            if crossed > self.delta_seg_limit:
                i = self.start + window.index(shortest)
                findings.append(Finding("error", f"at {master_speed:g} master counts/s one {pos_period_ms:g} ms "
                                                 f"sample moves {per_sample:g} counts: {crossed:.3g} segments of "
                                                 f"segment {i}'s length, over the delta-segment limit "
                                                 f"{self.delta_seg_limit} (Stop and Tr81)", i))
        return findings
