"""Points of a sweep: the grid of --vary, --random with a seed, --points files (docs/sweep.md)."""

import pytest

from motiontool.sweep.points import MAX_POINTS, SweepError, grid, parse_vary, random_points, read_points


def test_grid_runs_the_first_vary_outermost_and_includes_hi():
    varies = [parse_vary("32-60=20:80:20"), parse_vary("32-61=0:200:100", 2)]
    assert grid(varies) == [(20, 0), (20, 100), (20, 200), (40, 0), (40, 100), (40, 200), (60, 0), (60, 100),
                            (60, 200), (80, 0), (80, 100), (80, 200)]


def test_grid_stops_at_the_last_step_below_hi():
    assert grid([parse_vary("KPROP=20:80:25")]) == [(20,), (45,), (70,)]


@pytest.mark.parametrize("text, where", [
    ("32-60", "(number 1), position 1: give KEY=LO:HI:STEP"),
    ("32-60=20:x:5", "position 10: 'x' is not a whole number"),
    ("32-60=20:80:0", "position 13: '0' is not a whole number from 1"),
    ("32-60=80:20:5", "position 10: HI 20 is below LO 80"),
    ("32-60=20:80:5:1", "position 7: give LO:HI:STEP"),
    ("32 60=1:2:1", "position 1: '32 60' is no parameter"),
    ("KPROP=٥:9:1", "position 7: '٥' is not a whole number"),
    ("KPROP=1:99999999999999999999999:1", "position 9"),
])
def test_a_bad_vary_names_the_option_and_the_position(text, where):
    with pytest.raises(SweepError) as caught:
        parse_vary(text)
    assert str(caught.value).startswith(f"--vary '{text}' (number 1)")
    assert where in str(caught.value)
    assert "\n" not in str(caught.value)


def test_a_grid_needs_steps_and_a_bounded_size():
    with pytest.raises(SweepError, match="a grid needs a STEP"):
        grid([parse_vary("KPROP=1:9")])
    with pytest.raises(SweepError, match=f"more than {MAX_POINTS} points"):
        grid([parse_vary("KPROP=0:1000:1"), parse_vary("KDER=0:1000:1", 2)])


def test_random_points_are_reproducible_and_inside_the_ranges():
    varies = [parse_vary("KPROP=20:80"), parse_vary("KDER=0:200:50", 2)]
    points = random_points(varies, 200, seed=7)
    assert points == random_points(varies, 200, seed=7)
    assert points != random_points(varies, 200, seed=8)
    assert {p[0] for p in points} <= set(range(20, 81)) and {20, 80} <= {p[0] for p in points}
    assert {p[1] for p in points} == {0, 50, 100, 150, 200}


def test_points_file(tmp_path):
    path = tmp_path / "points.csv"
    path.write_text("32-60, 32-61\n20,0\n\n80, 200\n", encoding="utf-8")
    assert read_points(path) == (["32-60", "32-61"], [(20, 0), (80, 200)])
    path.write_text("32-60,32-61\n20,0\n80,x\n", encoding="utf-8")
    with pytest.raises(SweepError, match=r"--points .*points.csv, line 3, column 2: 'x' is not a whole number"):
        read_points(path)
    path.write_text("32-60,32-61\n20\n", encoding="utf-8")
    with pytest.raises(SweepError, match="line 2: 1 values for 2 parameters"):
        read_points(path)
    with pytest.raises(SweepError, match="No such file"):
        read_points(tmp_path / "missing.csv")
