"""One POS sample of the simulated APC, fused (issue 30 item 1: a CTSync line of 8 CAM drives ≥ 60× real time).

`steady_tick` is KernelCore.tick for the state nearly every sample of a CAM or CTSync line is in: run mode 2,
a POS0 writing the user-program reference source, the drive encoder as feedback, no option module, the CAM
walking inside its segment and the output channel on the speed reference (#1.21). Its steps are those of
KernelCore.tick, Plant.step, Source.refresh, Cam.step, ProfileGenerator.bypass, PositionLoop.run and
_latch_output, written out in one function with the same integer and floating-point operations in the same order
(a call costs as much as a line of them, and a line of 8 drives ticks 8000 times per simulated second); where the
state leaves the common case at any step, that step calls the general code. tests/apc/test_trace_identity.py holds
the traces to those of the APC before this module, row for row, and this tick to the general one (decisions K128).
"""

from __future__ import annotations

from math import floor as _floor

from motiontool.apc.cam import CamError
from motiontool.apc.camlaws import INTERIOR, linear
from motiontool.apc.driveparams import MAX_SPEED
from motiontool.apc.plant import WORD48
from motiontool.apc.sources import USER_PROGRAM

STOP, CAM = 0, 3     # core's (core imports this module and asserts that they agree)

# The int32 tests compare with ±0x3FFFFFFF first: CPython 3.11 compares one-digit ints (below 2^30) on a fast path,
# ±2^31 are two-digit numbers and take the general comparison, needed only by larger values. `x < 0 and x < -clamp`:
# the negation makes a new int each time (decisions K128, round 2).


def steady_tick(d) -> bool:
    """KernelCore.tick of a drive in run mode 2 with a POS0 and a user-program reference source, drive encoder
    feedback, no slot encoder and no held output; False, having changed nothing, in any other state."""
    ref, fb, pos0 = d.ref, d.fb, d.pos0
    if (d.run_mode != 2 or pos0 is None or ref.selector != USER_PROGRAM or fb.selector or d._held is not None
            or d.slots.fitted):
        return False
    d.samples += 1
    t_prev = d.time_ns
    d.time_ns = t_prev + d.period_ns
    # Plant.step: the first 250 µs at the older demand, the rest at the newer one
    plant = d.plant
    before = plant.position
    v = plant.speed
    if d.drive_enabled and not d.trip:
        old = d._demand3
        e, g = plant._first
        dv = v - old
        pos = before + old + dv * g
        v = old + dv * e
        q = plant.quarters - 1
        if q:
            new = d._demand2
            e, g = plant._rest
            dv = v - new
            pos += new * q + dv * g
            v = new + dv * e
    else:
        e, g = plant._coast
        pos = before + v * g
        v *= e
    plant.position = pos
    plant.speed = v
    step = plant._step
    if step:
        # int(pos // step) as floor(pos / step): the step is a power of two (it divides 2^32), so the quotient is
        # exact, except a negative position so near 0 that it underflows to -0.0
        k = _floor(pos / step)
        if not k and pos < 0.0:
            k = -1
        word = plant.word = (k * step) & WORD48
    else:
        word = plant.word = plant._quantised()
    lo, hi = plant._mark_window
    if pos < lo or pos >= hi:
        d._markers_passed(before, t_prev)
    # the sample's first reads: the user-program source after POS0 only; the drive encoder (Source.refresh)
    tb = d.turns_bits
    ref.sample_start_position, ref.sample_start_integrated = ref.position, ref.integrated
    if fb.input_disabled or fb.inverted:
        fb.refresh(word, tb, True)
    else:
        fb.sample_start_position = fb.position
        fb.sample_start_integrated = integrated = fb.integrated
        fb.word = word
        adjust = fb.marker_adjust
        position = (word + adjust if adjust else word) >> tb
        if not 0 <= position <= 0x3FFFFFFF:         # else already its low 32 bits, read as a signed number
            position &= 0xFFFFFFFF
            if position > 0x7FFFFFFF:
                position -= 0x100000000
        fb.position = position
        delta = position - fb.input
        if not (-0x3FFFFFFF <= delta <= 0x3FFFFFFF or -0x80000000 <= delta <= 0x7FFFFFFF):
            delta = ((delta + 0x80000000) & 0xFFFFFFFF) - 0x80000000
        fb.input = position
        total = integrated + delta
        if not (-0x3FFFFFFF <= total <= 0x3FFFFFFF or -0x80000000 <= total <= 0x7FFFFFFF):
            total = ((total + 0x80000000) & 0xFFFFFFFF) - 0x80000000
        fb.integrated = total
    d.task = "pos0"
    pos0()
    # what POS0 wrote counts in this sample
    if ref.selector == USER_PROGRAM:
        if ref.input_disabled or ref.inverted:
            ref.refresh(ref.user_word, tb, False)
        else:
            word = ref.word = ref.user_word
            adjust = ref.marker_adjust
            position = (word + adjust if adjust else word) >> tb
            if not 0 <= position <= 0x3FFFFFFF:
                position &= 0xFFFFFFFF
                if position > 0x7FFFFFFF:
                    position -= 0x100000000
            ref.position = position
            delta = position - ref.input
            if not (-0x3FFFFFFF <= delta <= 0x3FFFFFFF or -0x80000000 <= delta <= 0x7FFFFFFF):
                delta = ((delta + 0x80000000) & 0xFFFFFFFF) - 0x80000000
            ref.input = position
            total = ref.integrated + delta
            if not (-0x3FFFFFFF <= total <= 0x3FFFFFFF or -0x80000000 <= total <= 0x7FFFFFFF):
                total = ((total + 0x80000000) & 0xFFFFFFFF) - 0x80000000
            ref.integrated = total
    elif ref.input_disabled:
        ref.refresh(ref.word, tb, False)
    if fb.selector == USER_PROGRAM:
        fb.refresh(fb.user_word, tb, False)
    elif fb.input_disabled:
        fb.refresh(fb.word, tb, False)
    if ref.events or fb.events:
        d._capture(t_prev)
    if d.run_mode != 2 or not d._was_enabled or d._reset_request:
        d._kernel()
    elif d._active != CAM or d.reference != CAM or d.offset_select or (opg := d.opg).position or opg.speed:
        d._enabled_sample()
    else:   # _enabled_sample with the CAM running and no offsets
        ref_now = ref.integrated
        d_ref = ref_now - d._ref_last
        if not (-0x3FFFFFFF <= d_ref <= 0x3FFFFFFF or -0x80000000 <= d_ref <= 0x7FFFFFFF):
            d_ref = ((d_ref + 0x80000000) & 0xFFFFFFFF) - 0x80000000
        d._ref_last = ref_now
        pg, cam, q = d.pg, d.cam, d.quarters
        out = None
        if d_ref > 0 and not cam.single_shot:
            seg = cam.segment
            in_array = cam.in_array
            big_x = in_array[seg]
            x = cam.position + d_ref
            ratio = cam.ratio
            if x < big_x and ratio.numerator == ratio.denominator and not ratio.remainder:
                code = cam.mode
                if code == -1:
                    code = cam.interp[seg] if cam.interp is not None else 0
                y = cam.out1[seg]
                if code == 2:                     # camlaws.square1, square2 and linear, inline
                    a, b = y * x * x, big_x * big_x
                elif code == 3:
                    a, b = y * x * (2 * big_x - x), big_x * big_x
                elif code == 0 or not 0 <= code < 6:
                    a, b = y * x, big_x
                else:
                    a, b = 0, 0
                if b:
                    now = (2 * a + b) // (2 * b) if a >= 0 else -((b - 2 * a) // (2 * b))
                else:                             # the trigonometric laws
                    now = INTERIOR[code](x, big_x, y)
                if cam.out2 is not None:
                    now += linear(x, big_x, cam.out2[seg])
                out = now - cam._done_here
                cam.wrapped = 0
                cam.position, cam._done_here = x, now
        if out is None:
            try:
                out = cam.step(d_ref)
            except CamError as exc:
                d.apc_error(exc.code, str(exc))
                out = None
        if out is not None:
            # ProfileGenerator.bypass
            old = pg.position
            position = old + out
            if not (-0x3FFFFFFF <= position <= 0x3FFFFFFF or -0x80000000 <= position <= 0x7FFFFFFF):
                position = ((position + 0x80000000) & 0xFFFFFFFF) - 0x80000000
            step = position - old
            if not (-0x3FFFFFFF <= step <= 0x3FFFFFFF or -0x80000000 <= step <= 0x7FFFFFFF):
                step = ((step + 0x80000000) & 0xFFFFFFFF) - 0x80000000
            pg.input_position = pg.position = pg.base = position
            pg.prev_speed = pg.speed
            pg.speed = step / q
            if pg.mode != "bypass":
                pg.acceleration = pg.jerk_out = pg.offset = 0.0
                pg.mode, pg._planned = "bypass", None
            if cam.complete and cam.rearm:     # single-shot freeze re-arm (L1605-1622)
                d.reference = STOP
                ref.reset_freeze()
        # PositionLoop.run
        loop = d.loop
        ref_pos = loop.position_ref = loop.ext_position if loop.ext_pos_selected else pg.position
        if loop.ext_speed_selected:
            speed = loop.speed_ref = loop.ext_speed
        elif tb >= 5 and out is not None:
            # round(pg.speed · 2^tb) exactly: pg.speed = step / q with q = 1, 2, 4 … 32 quarters (a power of two)
            speed = loop.speed_ref = (step << tb) // q
        else:
            speed = loop.speed_ref = round(pg.speed * (1 << tb))
        error = ref_pos - fb.integrated
        if not (-0x3FFFFFFF <= error <= 0x3FFFFFFF or -0x80000000 <= error <= 0x7FFFFFFF):
            error = ((error + 0x80000000) & 0xFFFFFFFF) - 0x80000000
        loop.error = error
        if error:
            p = loop.kp * error << tb
            p = p // 400000 if p >= 0 else -(-p // 400000)
            clamp = loop.p_clamp
            if p > clamp:
                p = clamp
            elif p < 0 and p < -clamp:
                p = -clamp
        else:
            p = 0
        gain = loop.ff_gain
        if gain != 1000:
            speed *= gain
            speed = speed // 1000 if speed >= 0 else -(-speed // 1000)
        out = speed + p
        num, den = loop.ratio_num, loop.ratio_den
        if num != den:
            out *= num
            out = out // den if out >= 0 else -(-out // den)
        clamp = loop.output_clamp
        if out > clamp:
            out = clamp
        elif out < 0 and out < -clamp:
            out = -clamp
        loop.output = out
        d.enabled = 1
        d.reset_status = 0
    if d.pos1 is not None:
        d.task = "pos1"
        d.pos1()
    d.task = None
    # _latch_output on the speed reference (#1.21)
    channel = d.channel
    if not channel.enabled or channel.mode != 2:
        d._latch_output()
        return True
    speed = d.loop.output if d.enabled else 0
    rpm = d.params.values.get(MAX_SPEED, 3000)
    if rpm != d._limit_rpm:
        d._latch_output()
        return True
    limit = d._limit
    if speed > limit or speed < 0 and speed < -limit:
        speed = d._clamp_output(speed, limit)
    channel.sent = speed
    d._demand3, d._demand2, d._demand1 = d._demand2, d._demand1, speed
    return True

