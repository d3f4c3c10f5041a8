"""Hypothesis strategies for valid curves."""

from __future__ import annotations

from hypothesis import strategies as st

from motiontool.camcurve import Curve, CurveType, FixPoint, StartStopPair


@st.composite
def type_sequences(draw, n: int) -> list[str]:
    """Fix point types obeying the pairing rules: T pairs (closed by T, CZ or C3), CZ/C3 only between lines."""
    types = ["C"] * n
    i = draw(st.integers(0, 1))
    while i + 1 < n - 1 or (i + 1 == n - 1 and draw(st.booleans())):
        if draw(st.booleans()):
            types[i] = "T"
            closer = "T"
            # CZ/C3 closers need another straight section right after their segment
            if i + 3 < n and draw(st.booleans()):
                closer = draw(st.sampled_from(["CZ", "C3"]))
                types[i + 1] = closer
                types[i + 2] = "T"
                types[i + 3] = "T"
                i += 4 + draw(st.integers(0, 1))
                continue
            types[i + 1] = closer
            i += 2 + draw(st.integers(0, 1))
        else:
            i += 1
    return types


@st.composite
def curves(draw, integral: bool = False, min_points: int = 2) -> Curve:
    n = draw(st.integers(min_points, 9))
    intervals = draw(st.integers(1, 12))
    step = draw(st.integers(1, 50)) * intervals if integral else None
    if integral:
        cells = sorted(draw(st.sets(st.integers(1, 40), min_size=n - 2, max_size=n - 2)))
        length = 41 * step // intervals * intervals if step else 0
        masters = [0] + [c * length // 41 for c in cells] + [length]
        if len(set(masters)) != n:
            masters = [k * (length // (n - 1)) for k in range(n - 1)] + [length]
        slaves = [draw(st.integers(-5000, 5000)) for _ in range(n)]
    else:
        gaps = [draw(st.floats(1.0, 1000.0)) for _ in range(n - 1)]
        masters = [0.0]
        for g in gaps:
            masters.append(masters[-1] + g)
        length = masters[-1]
        slaves = [draw(st.floats(-5000, 5000)) for _ in range(n)]
    types = draw(type_sequences(n))
    ctype = draw(st.sampled_from(list(CurveType)))
    interpolation = integral and draw(st.booleans())
    pairs = [StartStopPair(0, 0)]
    if integral:
        isz = length // intervals
        for _ in range(draw(st.integers(0, 3))):
            pairs.append(StartStopPair(draw(st.integers(0, intervals)) * isz, draw(st.integers(0, intervals)) * isz))
    return Curve("c" * draw(st.integers(0, 16)), length, [FixPoint(x, y, t) for x, y, t in
                                                          zip(masters, slaves, types, strict=True)],
                 interpolation=interpolation, intervals=intervals, curve_type=ctype, start_stop_pairs=pairs,
                 start_gradient=draw(st.integers(-3, 3)) if integral else draw(st.floats(-3, 3)),
                 end_gradient=draw(st.integers(-3, 3)) if integral else draw(st.floats(-3, 3)))
