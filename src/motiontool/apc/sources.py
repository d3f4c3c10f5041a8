"""Reference and feedback sources: counters, integrators, freeze and marker capture (seed 004 §4.3 L920-1166,
§5.2.2 L2683-3240).

Per side (reference = master, feedback = slave):

    source word (48-bit turns|coarse|fine) --turns-bit window--> source position [20]/[40]
      --invert [27]/[47]--> input [31]/[51] (or written by the program when disabled, [32]/[52])
      --delta per refresh integrated--> integrated (main) position [28]/[48]

The manual places the invert "after the source counter [20], but before the integrated counter [28]"
(L3042-3047); that it acts before the input point [31] is **inferred** (spec §1.4). The integrators add each
refresh's position change, so presetting them never disturbs the source (L439-441, L948-957). Sources are
refreshed before POS0 and again at the end of POS0, so POS0 edits act in the same sample (V01.03.03,
L7219-7222).

Freeze and marker: two single-shot pairs latching the source and the integrated value together (L1026-1046),
flags latched until reset (L1080-1084), a capture needs its enable (90.45-90.48). An event between two samples
captures the positions interpolated linearly at the event time (the drive latches within 1 µs, L1046; the
interpolation between the two sampled values is **inferred**: the simulation knows nothing finer).
Marker reset (L1090-1135) zeroes the position within the turn by the 180° rule and excludes marker capture;
the integrator does not see the jump (**inferred**: a reset of the source must not move the axis).
"""

from __future__ import annotations

from motiontool.apc.intmath import wrap32

UNCONFIGURED = 5
USER_PROGRAM = 4


class Source:
    """One side's source counter, input, integrator and capture latches."""

    def __init__(self, name: str):
        self.name = name                 # "reference" | "feedback"
        self.selector = 0                # 0 drive, 1-3 slots, 4 user program, 5 unconfigured
        self.user_word = 0               # 48-bit word from APCSet…Position
        self.word = 0                    # present 48-bit source word (before marker alignment)
        self.marker_adjust = 0           # 48-bit correction from marker resets
        self.position = 0                # [20] / [40]
        self.inverted = False            # [27] / [47]
        self.input_disabled = False      # [32] / [52]
        self.user_input = 0              # value written by APCSetRefInput / APCSetFbckInput
        self.input = 0                   # [31] / [51]
        self.integrated = 0              # [28] / [48]
        self.sample_start_position = 0   # [20] and the integrator at the end of the previous sample: the
        self.sample_start_integrated = 0  # sample's change gives the speed and the capture interpolation
        # capture latches
        self.freeze_enabled = False      # 90.47 / 90.48
        self.freeze_flag = 0             # [22] / [42]
        self.freeze_position = 0         # [21] / [41]
        self.freeze_integrated = 0       # [29] / [49]
        self.marker_enabled = False      # 90.45 / 90.46
        self.marker_flag = 0             # [24] / [44]
        self.marker_position = 0         # [23] / [43]
        self.marker_integrated = 0       # [30] / [50]
        self.marker_reset = False        # [25] / [45]
        self.events: list[tuple[int, str]] = []   # (time in ns, "freeze" | "marker") waiting for their sample

    # --- refresh ----------------------------------------------------------------------------------------------
    def refresh(self, word: int, turns_bits: int, first: bool) -> None:
        """Read the source word and pass the change on to the input and the integrator; `first` (the first
        read of a sample) keeps the previous values as the sample's start."""
        if first:
            self.sample_start_position = self.position
            self.sample_start_integrated = self.integrated
        self.word = word
        w = ((word + self.marker_adjust) >> turns_bits) & 0xFFFFFFFF
        position = self.position = (w ^ 0x80000000) - 0x80000000          # as a signed 32-bit number
        if self.input_disabled:
            new_input = wrap32(self.user_input)
        elif self.inverted:
            new_input = wrap32(-position)
        else:
            new_input = position
        delta = new_input - self.input
        if (delta + 0x80000000) >> 32:      # outside int32: the counter wrapped
            delta = wrap32(delta)
        self.input = new_input
        total = self.integrated + delta
        self.integrated = wrap32(total) if (total + 0x80000000) >> 32 else total

    def start_sample(self) -> None:
        self.sample_start_position = self.position
        self.sample_start_integrated = self.integrated

    def speed(self, turns_bits: int, quarters: int) -> int:
        """[26] / [46]: this sample's change of [20] in APC units (**inferred**: the manual gives the unit, L7719,
        not the filter)."""
        d = wrap32(self.position - self.sample_start_position)
        return (d << turns_bits) // quarters

    # --- capture -----------------------------------------------------------------------------------------------
    def capture_events(self, t_start: int, t_end: int, turns_bits: int) -> list[tuple[str, int]]:
        """Latch the freeze/marker events of (t_start, t_end] at positions interpolated between the sample's
        start and present values. Returns the captures made: ("freeze" | "marker", integrated position)."""
        if not self.events:
            return []
        due = [e for e in self.events if e[0] <= t_end]
        self.events = [e for e in self.events if e[0] > t_end]
        if not (self.freeze_enabled and not self.freeze_flag or self.marker_enabled and not self.marker_flag):
            return []   # neither latch armed: nothing below can change (every motor turn passes a marker)
        made = []
        span = max(t_end - t_start, 1)
        d_src = wrap32(self.position - self.sample_start_position)
        d_int = wrap32(self.integrated - self.sample_start_integrated)
        for when, kind in sorted(due):
            frac_num = min(max(when - t_start, 0), span)
            src = wrap32(self.sample_start_position + _interp(d_src, frac_num, span))
            main = wrap32(self.sample_start_integrated + _interp(d_int, frac_num, span))
            if kind == "freeze":
                if self.freeze_enabled and not self.freeze_flag:
                    self.freeze_flag, self.freeze_position, self.freeze_integrated = 1, src, main
                    made.append(("freeze", main))
            elif self.marker_enabled and not self.marker_flag:
                self.marker_flag = 1
                if self.marker_reset:
                    self._align_to_marker(src, turns_bits)
                else:
                    self.marker_position, self.marker_integrated = src, main
                    made.append(("marker", main))
        return made

    def _align_to_marker(self, position_at_marker: int, turns_bits: int) -> None:
        """Marker reset: less than half a turn past the zero → jump down to it, else up to the next turn's
        zero; the turns count is not cleared (L1096-1104)."""
        per_rev = 1 << (32 - turns_bits)
        within = position_at_marker % per_rev
        jump = -within if within < per_rev // 2 else per_rev - within
        self.marker_adjust += jump << turns_bits
        self.position = wrap32(self.position + jump)
        self.sample_start_position = wrap32(self.sample_start_position + jump)
        if not self.input_disabled:   # the input moves with the source, so the integrator sees no change
            self.input = wrap32(self.input + (-jump if self.inverted else jump))

    def reset_freeze(self) -> None:
        self.freeze_flag = 0

    def reset_marker(self) -> None:
        self.marker_flag = 0


def _interp(delta: int, num: int, den: int) -> int:
    """round(delta·num/den), halves away from zero."""
    q, r = divmod(abs(delta) * num, den)
    if 2 * r >= den:
        q += 1
    return q if delta >= 0 else -q


def user_word(turns: int, position: int, fine: int) -> int:
    """The 48-bit word of APCSetReferencePosition/APCSetFeedbackPosition: the lower 16 bits of each argument
    (L3093-3122; the examples pass UnsignedTopWord/UnsignedBottomWord of a 32-bit counter, L6947-6950)."""
    return ((turns & 0xFFFF) << 32) | ((position & 0xFFFF) << 16) | (fine & 0xFFFF)
