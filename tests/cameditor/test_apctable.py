"""APC CAM tables in the CAM editor: the model, its checks, DPL export and import, MCO conversion."""

from __future__ import annotations

from fractions import Fraction

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from motiontool.apc.calculators import trapezoid_from_slave
from motiontool.cameditor.apcconvert import curve_to_table, table_to_curve
from motiontool.cameditor.apcdpl import DplImportError, import_dpl, table_program, table_to_dpl
from motiontool.cameditor.apctable import ApcCamTable, ApcSegment, ApcTableError
from motiontool.dpl.driver import check_source
from tests.dpl.manual import PROGRAMS

# The worked example of §4.7.2 (L1261-1376): master 100 rpm, slave to 200 rpm in 1 s, 2 s steady, 0.5 s down.
WORKED = ApcCamTable("Cam", (ApcSegment(109227, 109227, 2), ApcSegment(218454, 436908, 0),
                             ApcSegment(54613, 54613, 3)))


def test_the_worked_example_cycle_and_its_continuous_speed():
    """"109227, 546135, 600748" (L1259) and "slope 2 at every join" (spec §2.3); cyclic: rest at the wrap."""
    assert (WORKED.master_length, WORKED.slave_travel) == (382294, 600748)
    assert [WORKED.slave_at(m) for m in (109227, 327681, 382294)] == [109227, 546135, 600748]
    assert [s.end_speed() for s in WORKED.segments] == [2, 2, 0]
    assert [s.start_speed() for s in WORKED.segments] == [0, 2, 2]
    assert WORKED.check() == []
    assert WORKED.mode == -1


def test_the_calculators_give_a_table_without_speed_steps():
    """§4.7.11 (L1624-1655): master distances from the slave distances; all three speed ratios equal."""
    trapezoid, ratios = trapezoid_from_slave(382294, 600748, 109227, 54613)
    assert len(set(ratios)) == 1
    table = ApcCamTable("T", tuple(ApcSegment(x, y, law) for x, y, law in
                                   zip(trapezoid.master, trapezoid.slave, (2, 0, 3), strict=True)))
    assert [f.message for f in table.check()] == []


def test_checks_find_speed_steps_and_the_delta_segment_limit():
    table = ApcCamTable("Steps", (ApcSegment(1000, 1000, 0), ApcSegment(500, 2000, 1), ApcSegment(10, 0, 0)),
                        delta_seg_limit=4)
    messages = [(f.severity, f.segment, f.message) for f in table.check(master_speed=50_000)]
    assert messages == [
        ("warning", 1, "speed step between segments 0 and 1: 1 → 0 slave counts per master count"),
        ("warning", 0, "speed step between segments 2 and 0: 0 → 1 slave counts per master count"),
        ("error", 2, "at 50000 master counts/s one 1 ms sample moves 50 counts: 5 segments of segment 2's length, "
                     "over the delta-segment limit 4 (Stop and Tr81)"),
    ]
    assert ApcSegment(3, 7, 4).end_speed() == Fraction(14, 3)


@pytest.mark.parametrize("kwargs, field", [
    ({"segments": ()}, "segments"),
    ({"segments": (ApcSegment(0, 10),)}, "segments"),
    ({"segments": (ApcSegment(10, 10, 6),)}, "segments"),
    ({"segments": (ApcSegment(10, 10),), "size": 2}, "size"),
    ({"segments": (ApcSegment(10, 10),), "size": 0}, "size"),
    ({"segments": (ApcSegment(10, 10),), "start": 1}, "start"),
    ({"segments": (ApcSegment(10, 10),), "ratio": (1, 0)}, "ratio"),
    ({"segments": (ApcSegment(10, 10),), "name": "a b"}, "name"),
])
def test_tables_the_apc_cannot_run_are_refused_naming_the_field(kwargs, field):
    with pytest.raises(ApcTableError) as info:
        ApcCamTable(**kwargs)
    assert info.value.field == field


def test_export_is_valid_dpl_and_imports_back_unchanged():
    for table in (WORKED, ApcCamTable("Lin", (ApcSegment(100, 50), ApcSegment(100, 150, 0, slave2=10)),
                                      start=1, size=1, ratio=(7, 3), single_shot=True)):
        for const in (False, True):
            program = "Initial {\n" + table_to_dpl(table, const=const) + "}\n"
            checked = check_source(program, "cam.dpl")
            assert checked.ok, [d.format() for d in checked.diagnostics]
            assert import_dpl(program) == table
    text = table_to_dpl(WORKED)
    assert "CamStatus% = APCCamInitialise2(CamIn%, CamOut%, CamInt%)" in text
    assert "CamStatus% = APCSetCAMInterpolationMode(APC_ARRAY_CAM)" in text


def test_the_manuals_cam_programs_import_as_tables():
    """§7.3's six segments (L5606-5634) and §6.4.8's cosine CAM (L4905-4920) read from their programs."""
    cam73 = import_dpl((PROGRAMS / "s7_3_cam.dpl").read_text(encoding="utf-8"))
    assert [s.law for s in cam73.segments] == [2, 0, 3, 4, 0, 5]
    assert [s.master for s in cam73.segments] == [764587 * k for k in (2, 5, 3, 2, 5, 3)]
    assert cam73.slave_travel == 764587 + 3822935 + 1146880 and (cam73.start, cam73.used) == (0, 3)
    cam648 = import_dpl((PROGRAMS / "s6_4_cam.dpl").read_text(encoding="utf-8"))
    assert [(s.slave, s.law) for s in cam648.segments] == [(65536, 1), (131072, 1), (-196608, 1)]
    assert cam648.mode == 1 and cam648.name == "InArray"
    with pytest.raises(DplImportError, match="calls no APCCamInitialise"):
        import_dpl("Initial {\nx% = 1\n}\n")
    with pytest.raises(DplImportError, match=r"cam.dpl:2:6: error"):
        import_dpl("Initial {\nx% = Nope\n}\n", "cam.dpl")


def test_apc_to_mco_and_back_within_the_reported_errors():
    """spec §7.2: APC → MCO fix points (the spline's error falls with the square of the point density) → APC:
    the laws come back where the spline follows them within the tolerance; the ends are exact."""
    errors = [table_to_curve(WORKED, points_per_segment=n).max_error for n in (8, 16, 32)]
    assert errors[0] > 3.5 * errors[1] > 3.5 * 3.5 * errors[2] and errors[2] < 20   # counts of 600748
    back = curve_to_table(table_to_curve(WORKED, points_per_segment=32).curve, tolerance=20)
    assert back.max_error <= 20 + errors[2]
    assert back.table.segments[:2] == WORKED.segments[:2]            # Square1 and Linear found again
    assert back.table.slave_travel == WORKED.slave_travel and back.table.master_length == WORKED.master_length


@settings(max_examples=40, deadline=None, derandomize=True, database=None)
@given(st.lists(st.tuples(st.integers(1, 10_000), st.integers(-20_000, 20_000), st.integers(0, 5),
                          st.integers(-500, 500)), min_size=1, max_size=8),
       st.integers(1, 9), st.integers(1, 9))
def test_the_reference_is_whole_segments_plus_the_law_and_the_ratio_never_drifts(rows, n, d):
    """Property: at every segment end the slave is the sum of the travels; over k cycles the reference is exactly
    ⌊N·k·ΣY/D⌋ (the remainder is carried, L1546-1552); export → import gives the same table."""
    table = ApcCamTable("P", tuple(ApcSegment(*row) for row in rows), ratio=(n, d))
    position = 0
    for i, s in enumerate(table.segments):
        position += s.master
        assert table.slave_at(position) == sum(t.slave + t.slave2 for t in table.segments[:i + 1])
    for cycles in (1, 3):
        assert table.reference(cycles * table.master_length) == (cycles * table.slave_travel * n) // d
    assert import_dpl("Initial {\n" + table_to_dpl(table) + "}\n") == table


def test_a_table_program_checks_clean():
    checked = check_source(table_program(WORKED, master_rpm=100), "run.dpl")
    assert checked.ok and not checked.diagnostics


def test_an_exported_table_runs_in_the_simulator_and_its_trace_equals_the_drawing():
    """Issue 20: "a CAM table exported from the editor runs in the simulator and its trace equals the editor's
    drawing" — every sample of the CAM reference [117] equals the editor's reference at that master position."""
    from motiontool.apc import ApcDrive
    from motiontool.dpl.runtime import DplRuntime

    table = ApcCamTable("Cam", WORKED.segments, ratio=(3, 2))
    drive = ApcDrive()
    runtime = DplRuntime(drive, check_source(table_program(table, master_rpm=100), "run.dpl"))
    runtime.start()
    runtime.advance(1)
    trace = []
    for _ in range(int(2.2 * table.master_length / 109)):     # 2.2 cycles at 100 rpm (109 counts per ms)
        runtime.advance(1)
        trace.append((drive.read("APC_RF_POS"), drive.read("APC_PROF_OUT_POS")))
    engaged_at = trace[0][0] - 109
    assert runtime.state == "running" and len(trace) > 7000
    assert [slave for _, slave in trace] == [table.reference(master - engaged_at) for master, _ in trace]
