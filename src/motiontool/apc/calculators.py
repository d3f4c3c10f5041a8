"""The manual's calculators: CAM coordinates from a speed diagram (§4.7.2 L1261-1376), from slave positions
(§4.7.11 L1624-1655) and from times (§4.7.12 L1657-1704), and the S-ramp closed forms (§8.6 L7053-7132). Pure
maths for the CAM editor, the CLI and tests; exact fractions, rounded once where the manual prints counts.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction


def round_half_down(value: Fraction) -> int:
    """Nearest integer, halves toward zero: the worked example's 218454 × 0.5 / 2 = 54613.5 is printed 54613."""
    value = Fraction(value)
    sign = -1 if value < 0 else 1
    q, r = divmod(abs(value.numerator), value.denominator)
    if 2 * r > value.denominator:
        q += 1
    return sign * q


def counts_per_second(rpm, counts_per_rev: int) -> int:
    """(rpm/60) × counts/rev, rounded: 100 rpm at 65536 → 109227 cps (L1283-1287)."""
    return round_half_down(Fraction(rpm) * counts_per_rev / 60)


def ramp_counts(cps, seconds) -> int:
    """A linear ramp from or to rest: (cps × time)/2 (L1311-1323): 218454 cps over 1 s → 109227."""
    return round_half_down(Fraction(cps) * Fraction(seconds) / 2)


def steady_counts(cps, seconds) -> int:
    """Constant speed: cps × time (L1325-1331): 218454 cps over 2 s → 436908."""
    return round_half_down(Fraction(cps) * Fraction(seconds))


@dataclass(frozen=True)
class Trapezoid:
    """Master and slave coordinates of a three-segment trapezoid (accel, steady, decel)."""

    master: tuple[int, int, int]
    slave: tuple[int, int, int]


def trapezoid_from_slave(pmt: int, pst: int, psa: int, psd: int) -> tuple[Trapezoid, tuple[Fraction, ...]]:
    """§4.7.11: master distances from the master total Pmt and the slave total, accel and decel distances.
    Returns the coordinates and the three slave/master speed ratios of the manual's check (equal when right)."""
    pss = pst - psa - psd
    psf = 2 * psa + pss + 2 * psd
    pma = Fraction(2 * psa, psf) * pmt
    pms = Fraction(pss, psf) * pmt
    pmd = Fraction(2 * psd, psf) * pmt
    checks = tuple(x for x in (Fraction(2 * psa) / pma if pma else None, Fraction(pss) / pms if pms else None,
                               Fraction(2 * psd) / pmd if pmd else None) if x is not None)
    master = (round_half_down(pma), round_half_down(pms), round_half_down(pmd))
    return Trapezoid(master, (psa, pss, psd)), checks


def trapezoid_from_times(a1, a2, a3, pst: int, vm) -> Trapezoid:
    """§4.7.12: accel, constant and decel times (s), the slave total (counts) and the master speed (counts/s)."""
    a1, a2, a3, vm = Fraction(a1), Fraction(a2), Fraction(a3), Fraction(vm)
    at = a1 / 2 + a2 + a3 / 2
    psa, pss, psd = a1 / at * pst / 2, a2 / at * pst, a3 / at * pst / 2
    amt = a1 + a2 + a3
    pmt = amt * vm
    pma, pms, pmd = a1 / amt * pmt, a2 / amt * pmt, a3 / amt * pmt
    return Trapezoid((round_half_down(pma), round_half_down(pms), round_half_down(pmd)),
                     (round_half_down(psa), round_half_down(pss), round_half_down(psd)))


@dataclass(frozen=True)
class SRamp:
    """§8.6 Case A, one acceleration from rest to V_target with A_max and J_max (any consistent units)."""

    v_target: float
    t_l: float      # linear-ramp time V/A
    t_s: float      # each jerk phase A/J
    t_a: float      # constant-acceleration time T_L − T_S
    v1: float
    v2: float
    p1: float
    p2: float
    p3: float       # T_S·V − J·T_S³/6 (the printed second form A³/(4J²) is wrong, spec §9.3)
    p_total: float  # (V/2)·(V/A + A/J)

    def move_distance(self, cruise_time: float) -> float:
        """A full move: two ramps and a cruise, 2·P_total + V·T_V (L7112-7114)."""
        return 2 * self.p_total + self.v_target * cruise_time


def s_ramp(v_target: float, a_max: float, j_max: float) -> SRamp:
    """The §8.6 closed forms; valid while V ≥ A²/J (T_A ≥ 0), as the manual assumes (symmetric jerk)."""
    t_l = v_target / a_max
    t_s = a_max / j_max
    t_a = t_l - t_s
    if t_a < 0:
        raise ValueError(f"V {v_target} < A²/J = {a_max * a_max / j_max}: the acceleration never reaches A_max "
                         f"and §8.6's formulas do not apply")
    v1 = j_max * t_s * t_s / 2
    v2 = v1 + a_max * t_a
    p1 = j_max * t_s ** 3 / 6
    p2 = v1 * t_a + (v2 - v1) * t_a / 2
    p3 = t_s * v_target - j_max * t_s ** 3 / 6
    return SRamp(v_target, t_l, t_s, t_a, v1, v2, p1, p2, p3, v_target / 2 * (v_target / a_max + a_max / j_max))


def s_ramp_from_time(v_target: float, t_total: float, s_percent: float) -> tuple[float, float]:
    """§8.6 Case B: (A_max, J_max) for a ramp of fixed time with S% of it in jerk (L7116-7130)."""
    t_s = t_total * s_percent / 200
    t_a = t_total - 2 * t_s
    a_max = v_target / (t_s + t_a)
    return a_max, (a_max / t_s if t_s > 0 else float("inf"))
