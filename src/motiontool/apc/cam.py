"""The CAM reference (seed 004 §4.7 L1224-1704, §5.2.4.5 L3435-3697).

Segments of relative increments: master length X = InArray[i], slave travel Y = OutArray1[i] (plus an optional
linear OutArray2[i]); one cycle advances the slave by the sum of the Y (Table 4-10: 109227 + 436908 + 54613 =
600748). The CAM is monotonic in the master: forward along the table when the master moves forward, backward
when it reverses (L1259). Six interpolation laws per segment (`camlaws.py`), evaluated from the master position
in the segment, so the end of every segment is exactly Y and a cycle exactly ΣY. The output ratio [80]/[81]
applies to the increments with its remainder carried (L1546-1552). The walk across segments per sample is
spec §2.13's proposal (**inferred**): the segments crossed in one sample count against the delta-segment limit
[76].
"""

from __future__ import annotations

from collections.abc import Sequence

from motiontool.apc.camlaws import (
    ERR_ABS_RESET,
    ERR_ARRAY_TOO_SMALL,
    ERR_SEGMENT_OVERRUN,
    ERR_SIZE_ZERO,
    INTERIOR,
    linear,
)
from motiontool.apc.intmath import Ratio


class CamError(Exception):
    def __init__(self, code: int, text: str):
        super().__init__(text)
        self.code = code


class Cam:
    """The CAM reference's arrays, settings ([74]-[89]) and walk state."""

    def __init__(self) -> None:
        self.in_array: Sequence[int] | None = None
        self.out1: Sequence[int] | None = None
        self.out2: Sequence[int] | None = None
        self.interp: Sequence[int] | None = None
        self.start_index = 0        # [74]
        self.size = 0               # [75]
        self.seg_limit = 256        # [76]
        self.mode = 0               # [77] -1 array, 0 linear, 1 cosine
        self.single_shot = False    # [78]
        self.absolute_reset = False  # [79]
        self.ratio = Ratio(1000, 1000)   # [80]/[81]
        self.segment = 0            # [82]
        self.position = 0           # [83]
        self.reset_index = 0        # [85]
        self.reset_position = 0     # [86]
        self.complete = 0           # [87]
        self.rearm = False          # [88]
        self.wrapped = 0            # [89]
        self.active_start = 0       # the window in use; [74]/[75] apply at the next wrap or restart (L1520)
        self.active_size = 0
        # [74]/[75] written in a POS task: that task pass (sample, task) and the window before it; a CAM selected
        # in the same pass starts with that earlier window (L3505-3508, decision A37)
        self.window_pass: tuple[int, str] | None = None
        self.window_before = (0, 0)
        self._done_here = 0         # slave travel already output inside the present segment
        self._travel = 0            # single shot: net master travel since the start
        self._forward_room = 0
        self._backward_room = 0

    @property
    def array_size(self) -> int:   # [84]
        return len(self.in_array) if self.in_array is not None else 0

    def initialise(self, in_array: Sequence[int], out1: Sequence[int], out2: Sequence[int] | None = None,
                   interp: Sequence[int] | None = None) -> None:
        """APCCamInitialise*: register the arrays (they are read live, so edits act at once, L1528-1531)."""
        self.in_array, self.out1, self.out2, self.interp = in_array, out1, out2, interp

    def _inseg(self, seg: int, x: int) -> int:
        """Slave travel after x master counts of segment `seg` (Out1 by its law plus a linear Out2)."""
        in_array, out1 = self.in_array, self.out1
        assert in_array is not None and out1 is not None  # engage() found In and Out1 arrays (_check_window)
        big_x = in_array[seg]
        if x <= 0:
            return 0
        if x >= big_x:
            return self._total(seg)
        code = self.mode
        if code == -1:
            code = self.interp[seg] if self.interp is not None else 0
        value = (INTERIOR[code] if 0 <= code < 6 else linear)(x, big_x, out1[seg])
        if self.out2 is not None:
            value += linear(x, big_x, self.out2[seg])
        return value

    def _total(self, seg: int) -> int:
        out1 = self.out1
        assert out1 is not None  # engage() found the arrays
        return out1[seg] + (self.out2[seg] if self.out2 is not None else 0)

    def _check_window(self, start: int, size: int) -> None:
        if size <= 0:
            raise CamError(ERR_SIZE_ZERO, "CAM size 0 selects Stop (90.49 = 3)")
        n = min(len(a) for a in (self.in_array, self.out1) if a is not None) if self.in_array is not None else 0
        for extra in (self.out2, self.interp if self.mode == -1 else None):
            if extra is not None:
                n = min(n, len(extra))
        if self.in_array is None or start + size > n:
            raise CamError(ERR_ARRAY_TOO_SMALL, f"CAM window {start}..{start + size - 1} is beyond the arrays "
                                                f"({n} elements, 90.49 = 1)")

    # --- engagement -------------------------------------------------------------------------------------------
    def engage(self, window: tuple[int, int] | None = None) -> None:
        """Start (selection, restart) in `window` (start index, size; by default [74]/[75]): zero reset at the start
        index, absolute reset at [85]/[86] within the window (L1573-1587); the single-shot room follows from where
        it starts (L3664)."""
        self.active_start, self.active_size = window or (self.start_index, self.size)
        self._check_window(self.active_start, self.active_size)
        start, end = self.active_start, self.active_start + self.active_size
        in_array = self.in_array
        assert in_array is not None  # _check_window raised without it
        if self.absolute_reset:
            seg, pos = self.reset_index, self.reset_position
            if not start <= seg < end or not 0 <= pos < max(in_array[seg], 1):
                raise CamError(ERR_ABS_RESET, f"CAM absolute reset at segment {seg}, position {pos} is outside "
                                              f"the CAM (90.49 = 4)")
        else:
            seg, pos = start, 0
        self.segment, self.position = seg, pos
        self._done_here = self._inseg(seg, pos)
        self.ratio.reset()
        self.complete = 0
        self.wrapped = 0
        self.finish_cycle()

    def finish_cycle(self) -> None:
        """Single shot selected while running cyclically: finish the present cycle (L1567-1569)."""
        start, end = self.active_start, self.active_start + self.active_size
        in_array = self.in_array
        assert in_array is not None  # called on an engaged CAM only
        length = sum(in_array[k] for k in range(start, end))
        offset = sum(in_array[k] for k in range(start, self.segment)) + self.position
        self._travel = 0
        self._forward_room = length - offset
        self._backward_room = offset if offset > 0 else length

    # --- the walk ---------------------------------------------------------------------------------------------
    def step(self, master_delta: int) -> int:
        """Follow `master_delta` counts of the reference this sample; the slave increment after the ratio.
        Raises CamError on a delta-segment-limit breach (Stop plus the trip, L3524-3546)."""
        self.wrapped = 0
        in_array = self.in_array
        assert in_array is not None  # the kernel steps an engaged CAM only
        pos = self.position + master_delta
        if master_delta > 0 and not self.single_shot:
            seg = self.segment
            big_x = in_array[seg]
            if pos < big_x:
                # inside the present segment (the common case): _inseg's interior without its call and end checks
                code = self.mode
                if code == -1:
                    code = self.interp[seg] if self.interp is not None else 0
                out1 = self.out1
                assert out1 is not None
                now = (INTERIOR[code] if 0 <= code < 6 else linear)(pos, big_x, out1[seg])
                if self.out2 is not None:
                    now += linear(pos, big_x, self.out2[seg])
                out = now - self._done_here
                self.position, self._done_here = pos, now
                ratio = self.ratio
                return out if ratio.numerator == ratio.denominator and not ratio.remainder else ratio.step(out)
        if self.single_shot:
            if self.complete:
                return 0
            room_hi, room_lo = self._forward_room - self._travel, -self._backward_room - self._travel
            if master_delta >= room_hi:
                master_delta, self.complete = room_hi, 1
            elif master_delta <= room_lo:
                master_delta, self.complete = room_lo, 1
            self._travel += master_delta
        if master_delta == 0:
            return self.ratio.step(0) if self.ratio.remainder else 0
        limit = self.seg_limit
        seg, pos = self.segment, self.position + master_delta
        done = self._done_here
        out = 0
        crossed = 0
        while pos >= in_array[seg] and master_delta > 0:
            out += self._total(seg) - done
            pos -= in_array[seg]
            done = 0
            seg += 1
            crossed += 1
            if crossed >= limit:
                raise CamError(ERR_SEGMENT_OVERRUN, f"the master crossed {crossed} CAM segments in one sample "
                                                    f"(limit {limit})")
            if seg >= self.active_start + self.active_size:
                seg = self._wrap()
        while pos < 0:
            out -= done
            seg -= 1
            crossed += 1
            if crossed >= limit:
                raise CamError(ERR_SEGMENT_OVERRUN, f"the master crossed {crossed} CAM segments in one sample "
                                                    f"(limit {limit})")
            if seg < self.active_start:
                seg = self._wrap(backward=True)
            pos += in_array[seg]
            done = self._total(seg)
        now = self._inseg(seg, pos)
        out += now - done
        self.segment, self.position, self._done_here = seg, pos, now
        ratio = self.ratio
        if ratio.numerator == ratio.denominator and not ratio.remainder:
            return out
        return ratio.step(out)

    def _wrap(self, backward: bool = False) -> int:
        """Past either end of the window: the next start index and size take effect here (L1520-1526)."""
        self.wrapped = 1
        start, size = self.start_index, self.size
        self._check_window(start, size)
        self.active_start, self.active_size = start, size
        return start + size - 1 if backward else start
