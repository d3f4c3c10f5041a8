"""Hypothesis properties of the controller: limits hold, reruns are identical."""

from hypothesis import given, settings
from hypothesis import strategies as st

from .helpers import start

moves = st.lists(st.tuples(st.integers(-200_000, 200_000), st.integers(5, 100), st.integers(5, 100),
                           st.integers(5, 100)), min_size=1, max_size=3)


def program(steps) -> str:
    lines = []
    for target, vel, acc, dec in steps:
        lines += [f"VEL {vel}", f"ACC {acc}", f"DEC {dec}", f"POSA {target}"]
    return "\n".join(lines) + "\n"


def commanded_trace(steps, ramp_type: int, max_ms: int = 30_000):
    """CPOS (qc, unrounded) and APOS of every tick until the program ends."""
    run = start(program(steps), settings={"RAMPTYPE": ramp_type})
    c = run.controller
    cpos, apos = [], []
    for _ in range(max_ms):
        c.tick()
        cpos.append(c.axis.cpos)
        apos.append(c.axis.apos)
        if c.program_state != "running":
            break
    assert c.program_state == "ended"
    return c, cpos, apos


@settings(max_examples=10, deadline=None, derandomize=True)
@given(moves, st.sampled_from([0, 2]))
def test_commanded_acceleration_and_jerk_never_exceed_their_limits(steps, ramp_type):
    """DG 8959-9006: acceleration within ACC/DEC of VELMAX/RAMPMIN; with RAMPTYPE 2 the change of
    acceleration within max. acceleration / JERKMIN per ms (DG 9044-9086)."""
    c, cpos, _ = commanded_trace(steps, ramp_type)
    amax = c.axis.scaling.amax
    acc = [cpos[i + 1] - 2 * cpos[i] + cpos[i - 1] for i in range(1, len(cpos) - 1)]
    assert max((abs(a) for a in acc), default=0.0) <= amax * (1 + 1e-6)
    if ramp_type == 2:
        jmax = amax / c.params["JERKMIN"]
        jerk = [acc[i + 1] - acc[i] for i in range(len(acc) - 1)]
        assert max((abs(j) for j in jerk), default=0.0) <= jmax * (1 + 1e-6) + 1e-9


@settings(max_examples=5, deadline=None, derandomize=True)
@given(moves, st.sampled_from([0, 2]))
def test_reruns_give_identical_traces(steps, ramp_type):
    """Same program, same inputs ⇒ identical traces (issue 4)."""
    _, cpos1, apos1 = commanded_trace(steps, ramp_type)
    _, cpos2, apos2 = commanded_trace(steps, ramp_type)
    assert cpos1 == cpos2 and apos1 == apos2
