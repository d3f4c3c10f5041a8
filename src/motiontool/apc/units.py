"""APC internal units and the calculators of the manual (seed 004 §3.11.2 L686-742, §4.12 L2153-2305, §5.3
L4317-4470).

* Position: counts at the current resolution; with TB turns bits one revolution is 2^(32-TB) counts.
* Speed: 2^32 counts per revolution per 250 µs, i.e. ``speed = rpm·2^30/60000`` (L702-714).
* Acceleration: speed units per 250 µs, ``accel = speed·250/ramp_time_µs`` (L722-728).
* Jerk: acceleration units per 250 µs, ``jerk = accel·250/jerk_time_µs`` (L732-740).
* P gain: 0.01 (rad/s)/rad (L744); with TB turns bits one count of error asks for Kp·2^TB/400000 speed units
  (**derived** from the unit definitions, spec §1.15).
* User units (UPR N/D): N units per D revolutions; [96] = 2^(32-TB)·D, [97] = N (L2185-2195).
"""

from __future__ import annotations

from dataclasses import dataclass

from motiontool.apc.intmath import INT32_MAX, INT32_MIN, MULDIV, div_trunc, wrap32

TWO_30 = 1 << 30
QUARTERS_PER_S = 4000                 # 250 µs periods per second: the time base of speed, accel and jerk
POS_RATE_US = {1: 250, 2: 500, 3: 1000, 4: 2000, 5: 4000, 6: 8000}   # #81.12 code → POS period (L655-673)
SPEED_LIMIT = 715827883               # ±40000 rpm (L3424)
ACCEL_LIMIT = 4473924                 # 250 rpm per 250 µs (L3839)


def pos_rate_code(period_us: int) -> int:
    """#81.12 code of a POS period in µs (1 = 0.25 ms … 6 = 8 ms)."""
    for code, us in POS_RATE_US.items():
        if us == period_us:
            return code
    raise ValueError(f"POS period {period_us} µs: the APC runs at 250, 500, 1000, 2000, 4000 or 8000 µs")


def counts_per_rev(turns_bits: int) -> int:
    return 1 << (32 - turns_bits)


def rpm_to_speed(rpm: int) -> int:
    """APC speed units of `rpm` as the manual's DPL computes it: MULDIV(rpm, 2^30, 60000) (L712):
    2700 rpm → 48318382, 3000 → 53687091, 300 → 5368709, 1 → 17895."""
    return MULDIV(rpm, TWO_30, 60000)


def speed_to_rpm(speed: int) -> float:
    return speed * 60000 / TWO_30


def speed_to_rpm_x10(speed: int) -> int:
    """[135] in rpm×10, to the nearest 0.1 rpm (**inferred**: 600 rpm reads 6000, not 5999) (APCGetOutputSpeedRpmx10;
    the "0.01 rpm" of L2459 is read as a slip, spec §9.9)."""
    return round_div(speed * 600000, TWO_30)


def accel_from_ramp(speed: int, ramp_time_us: int) -> int:
    """Acceleration that reaches `speed` in `ramp_time_us`: MULDIV(speed, 250, time) (L728).
    1000 rpm in 0.2 s → 22369 (the default, 5000 rpm/s)."""
    return MULDIV(speed, 250, ramp_time_us)


def jerk_from_time(accel: int, jerk_time_us: int) -> int:
    """Jerk that builds `accel` up in `jerk_time_us`: MULDIV(accel, 250, time) (L740)."""
    return MULDIV(accel, 250, jerk_time_us)


def kp_speed(kp: int, error_counts: int, turns_bits: int) -> int:
    """P-path speed in APC units for a following error (**derived**, spec §1.15): Kp in 0.01 (rad/s)/rad means
    error·Kp/100 revolutions per second, i.e. error·Kp·2^TB/400000 speed units (2500 and 1 count: ≈410)."""
    return div_trunc(kp * error_counts << turns_bits, 400000)[0]


def _round_div(a: int, b: int) -> int:
    """a/b rounded to the nearest integer, halves away from zero (b > 0)."""
    q, r = divmod(abs(a), b)
    if 2 * r >= b:
        q += 1
    return q if a >= 0 else -q


def round_div(a: int, b: int) -> int:
    """a/b to the nearest integer (halves away from zero); b may be negative."""
    return _round_div(a, b) if b > 0 else _round_div(-a, -b)


@dataclass(frozen=True)
class UserUnits:
    """N user units per D revolutions at TB turns bits (SetUPRNumeratorAndDenominator, L2165-2247).

    Position: ``UU = round(APC·N/[96])``, ``Rem = APC·N − UU·[96]`` (L2236-2247); the remainder makes the
    round trip exact. Speeds and accelerations are rounded to the nearest unit/s, unit/s² (L2199-2201).
    """

    numerator: int = 1
    denominator: int = 1
    turns_bits: int = 16

    @property
    def conv_n(self) -> int:
        """[96] = 2^(32−TB)·D (named for the user→APC direction: APC = UU·[96]/[97])."""
        return counts_per_rev(self.turns_bits) * self.denominator

    @property
    def conv_d(self) -> int:
        """[97] = N."""
        return self.numerator

    @staticmethod
    def check(numerator: int, denominator: int, turns_bits: int) -> str | None:
        """Why N/D is refused at this resolution, or None. The tighter denominator bound of the command page
        (L4326, L2191-2195) is used, not 2^31−1 of the quick reference (spec §9.14)."""
        if not 1 <= numerator <= INT32_MAX:
            return f"numerator {numerator} outside 1..2147483647"
        dmax = (1 << (turns_bits - 1)) - 1
        if not 1 <= denominator <= max(dmax, 1):
            return f"denominator {denominator} outside 1..{max(dmax, 1)} at {turns_bits} turns bits"
        if numerator > counts_per_rev(turns_bits) * denominator:
            return f"{numerator}/{denominator} units per revolution exceeds 2^{32 - turns_bits}"
        return None

    # --- positions ----------------------------------------------------------------------------------------
    def to_user(self, counts: int) -> tuple[int, int]:
        """(UU, Rem) of a position in counts."""
        total = counts * self.numerator
        uu = round_div(total, self.conv_n)
        return uu, total - uu * self.conv_n

    def to_counts(self, uu: int, rem: int = 0) -> tuple[int, int]:
        """(counts, internal remainder [171]) of a user position with remainder: APC·N = UU·[96] + Rem."""
        total = uu * self.conv_n + rem
        counts = round_div(total, self.numerator)
        return counts, total - counts * self.numerator

    # --- speed, acceleration, jerk: one more factor 4000 (250 µs per second) each ------------------------------
    def _scale(self, order: int) -> tuple[int, int]:
        """(num, den) so that APC = UU·num/den for speed (order 1), accel (2) and jerk (3)."""
        return self.denominator << 32, self.numerator * QUARTERS_PER_S ** order

    def to_apc_rate(self, value: int, order: int) -> int:
        num, den = self._scale(order)
        return round_div(value * num, den)

    def to_user_rate(self, value: int, order: int) -> int:
        num, den = self._scale(order)
        return round_div(value * den, num)


def fits32(value: int) -> bool:
    return INT32_MIN <= value <= INT32_MAX


class EmbeddedConverter:
    """The embedded APC converter blocks UserToAPC*/APCToUser* (L4319-4396): position, velocity (units/s) and
    acceleration (units/s²) with a units-per-revolution ratio. Status 0 and value 0 when the result does not
    fit 32 bits (L4345-4394). SetUPR(UPR) is the legacy single-value form used by §8.3.1 (L6795)."""

    def __init__(self) -> None:
        self.numerator = 65536      # units per `denominator` revolutions (**inferred** default: counts at 16 bits)
        self.denominator = 1

    def _units(self, turns_bits: int) -> UserUnits:
        return UserUnits(self.numerator, self.denominator, turns_bits)

    @staticmethod
    def _result(value: int) -> tuple[int, int]:
        return (value, 1) if fits32(value) else (0, 0)

    def user_to_apc_position(self, value: int, turns_bits: int) -> tuple[int, int]:
        u = self._units(turns_bits)
        return self._result(round_div(value * u.conv_n, u.conv_d))

    def apc_to_user_position(self, value: int, turns_bits: int) -> tuple[int, int]:
        return self._result(self._units(turns_bits).to_user(value)[0])

    def user_to_apc_rate(self, value: int, order: int, turns_bits: int) -> tuple[int, int]:
        return self._result(self._units(turns_bits).to_apc_rate(value, order))

    def apc_to_user_rate(self, value: int, order: int, turns_bits: int) -> tuple[int, int]:
        return self._result(self._units(turns_bits).to_user_rate(value, order))


class UserDefinedConverter:
    """SetConverterNumerator/Denominator, ConvertForwards (×N/D) and ConvertBackwards (×D/N) (L4474-4495);
    254/10 converts inches to millimetres. Truncated toward zero like MULDIV (**inferred**)."""

    def __init__(self) -> None:
        self.numerator = 1
        self.denominator = 1

    def forwards(self, value: int) -> int:
        return MULDIV(value, self.numerator, self.denominator) if self.denominator else 0

    def backwards(self, value: int) -> int:
        return MULDIV(value, self.denominator, self.numerator) if self.numerator else 0


def counts_to_window(word48: int, turns_bits: int) -> int:
    """The APC's signed 32-bit view of a 48-bit turns|coarse|fine source word (L2803-2835): with TB turns
    bits the window holds TB turns bits, 16 coarse bits and 16−TB fine bits, i.e. bits TB..TB+31."""
    return wrap32(word48 >> turns_bits)
