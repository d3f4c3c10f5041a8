"""The embedded link: the same requests as a wire link, synchronous or on a paced kernel thread."""

import time

import pytest

from motiontool.aposs.driver import compile_source
from motiontool.comms.protocol import LinkError, Request
from motiontool.controller.embedded import EmbeddedLink


def image(source: str, debug: bool = False) -> bytes:
    result = compile_source(source, "p.m", debug=debug)
    assert result.ok, [d.format() for d in result.diagnostics]
    return result.image.to_bytes()


def test_parameters_through_the_link():
    link = EmbeddedLink()
    assert link.read_parameter("KPROP") == 30
    assert link.read_parameter("32-60") == 30
    link.write_parameter(3260, 55)
    assert link.read_parameter("kprop") == 55
    with pytest.raises(LinkError, match="112"):
        link.read_parameter("NOPE")
    with pytest.raises(LinkError) as e:
        link.write_parameter("KPROP", 200000)  # a link write is validated against the range
    assert "32-60 KPROP" in str(e.value)


def test_unknown_operation_is_refused():
    link = EmbeddedLink()
    with pytest.raises(LinkError, match="unknown operation"):
        link.request(Request("format_disk", {}, 1))


def test_arrays_and_messages():
    link = EmbeddedLink()
    prints = []
    link.subscribe(lambda e: prints.append(e.text) if e.kind == "print" else None)
    link.download(image("DIM a[3]\na[2] = 7\nPRINT a[2]\n"))
    link.start()
    link.advance(10)
    assert prints == ["7"]
    assert link.call("list_arrays") == [{"index": 0, "name": "a", "size": 3}]
    assert link.read_array(0) == [0, 7, 0]
    link.write_array(0, [1, 2, 3])
    assert link.read_array(0) == [1, 2, 3]


def test_break_and_continue_complete_the_interrupted_move():
    """DG 2410-2418: [Esc] stops with maximum deceleration; Continue completes the interrupted positioning."""
    link = EmbeddedLink()
    link.download(image("VEL 100\nACC 100\nDEC 100\nPOSA 204800\nPRINT CPOS\n"))
    prints = []
    link.subscribe(lambda e: prints.append(e.text) if e.kind == "print" else None)
    link.start()
    link.advance(1500)
    link.break_program()
    link.advance(1000)
    stopped = link.status()
    assert stopped.program_state == "break" and stopped.cpos < 204800
    link.continue_program()
    link.advance(5000)
    assert prints == ["204800"]


def test_breakpoints_single_step_and_variables():
    """DG 3344-3460: a debug build stops before a statement with a breakpoint; variables can be read and
    modified; Singlestep runs one statement."""
    link = EmbeddedLink()
    link.download(image("a = 1\nb = 2\nc = a + b\nPRINT c\n", debug=True))
    link.call("set_breakpoints", lines=[3])
    prints = []
    link.subscribe(lambda e: prints.append(e.text) if e.kind == "print" else None)
    link.start()
    link.advance(10)
    status = link.status()
    assert status.program_state == "break" and status.line == 3
    assert link.call("read_variables", names=["a", "b"]) == [1, 2]
    link.call("write_variable", name="b", value=40)
    link.call("step")
    link.advance(5)
    assert link.status().program_state == "break"
    link.continue_program()
    link.advance(5)
    assert prints == ["41"]


def test_start_with_step_stops_before_the_first_statement():
    """DG 2432-2434: Prepare Singlestep downloads the debug build "but does not start" it: the program
    stands before its first executable statement."""
    link = EmbeddedLink()
    link.download(image("// first\nDIM a[2]\nx = 5\nPRINT x\n", debug=True))
    link.start(step=True)
    link.advance(10)
    status = link.status()
    assert status.program_state == "break" and status.line == 3
    assert link.call("read_variables", names=["x"]) == [0]


def test_threaded_link_paces_virtual_time():
    """Decision K10: the IDE's link runs the kernel on its own thread at real time × factor."""
    link = EmbeddedLink(realtime_factor=1.0)
    try:
        t0 = link.status().time_ms
        time.sleep(0.3)
        elapsed = link.status().time_ms - t0
        assert 150 <= elapsed <= 600
        link.download(image("PRINT \"hi\"\n"))
        got = []
        link.subscribe(lambda e: got.append(e.text) if e.kind == "print" else None)
        link.start()
        deadline = time.monotonic() + 5
        while not got and time.monotonic() < deadline:
            time.sleep(0.01)
        assert got == ["hi"]
    finally:
        link.close()


def test_streaming_sends_samples():
    link = EmbeddedLink()
    packets = []
    link.subscribe(lambda e: packets.append(e.data) if e.kind == "samples" else None)
    link.call("stream", signals=["APOS", "CPOS", "KPROP"], interval_ms=2)
    link.advance(100)
    times = [t for p in packets for t in p["time_ms"]]
    assert times[:3] == [2, 4, 6] and len(times) >= 45
    assert packets[0]["signals"] == ["APOS", "CPOS", "KPROP"]
    assert packets[0]["values"][0][2] == 30


def test_master_position_and_velocity_are_signals():
    """CR 3574-3611: PULSVEL drives the virtual master; MAPOS/MAVEL (master qc, qc/s) can be streamed and
    traced like APOS, so a CAM trace can be overlaid against the master (issue 6)."""
    link = EmbeddedLink()
    packets = []
    link.subscribe(lambda e: packets.append(e.data) if e.kind == "samples" else None)
    link.download(image("PULSACC 100000\nPULSVEL 1000\nWAITT 100000\n"))
    link.start()
    link.call("stream", signals=["MAPOS", "MAVEL"], interval_ms=1)
    link.advance(200)
    rows = [v for p in packets for v in p["values"]]
    assert rows[-1][0] > rows[len(rows) // 2][0] > 0                # the master counter runs
    assert rows[-1][1] == pytest.approx(4000, rel=0.01)       # 1000 lines/s = 4000 qc/s (decision K15)
