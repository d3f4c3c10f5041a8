"""The Single Shot recording the oscilloscope configures over the link (DG 5287-5324)."""

import pytest

from motiontool.aposs.driver import compile_source
from motiontool.comms.protocol import LinkError
from motiontool.controller.embedded import EmbeddedLink


def image(source: str) -> bytes:
    result = compile_source(source, "p.m")
    assert result.ok, [d.format() for d in result.diagnostics]
    return result.image.to_bytes()


def test_fixed_count_stop_when_full_keeps_exactly_count_sets_at_the_interval():
    """DG 5318: "Fixed count … not more than that many sets of points (i.e. one point per curve)";
    DG 5322: the sample interval in ms between samples."""
    link = EmbeddedLink()
    status = link.call("start_recording", signals=["4097", "4098", "TRACKERR"], interval_ms=2,
                       destination="DYNMEM", cyclic=False, count=1000)
    assert status["limit"] == 1000 and status["running"]
    link.advance(2500)
    assert link.call("recording_status")["running"] is False
    data = link.call("stop_recording")
    assert len(data["samples"]) == 1000 and len(data["time_ms"]) == 1000
    assert all(len(row) == 3 for row in data["samples"])
    assert {b - a for a, b in zip(data["time_ms"], data["time_ms"][1:], strict=False)} == {2}
    assert link.call("recording_status") is None


def test_cyclic_keeps_the_newest_sets():
    """DG 5308: "If it is set to Cyclic, then new data will start to overwrite old data"."""
    link = EmbeddedLink()
    link.call("start_recording", signals=["4119"], interval_ms=1, destination="DYNMEM", cyclic=True, count=100)
    link.advance(250)
    data = link.call("stop_recording")
    assert len(data["samples"]) == 100 and data["taken"] == 250
    assert [row[0] for row in data["samples"]] == data["time_ms"] == list(range(151, 251))


def test_recording_into_a_user_array_fills_it_and_survives_the_program_end():
    """DG 5304: Array = "the specified user-defined array … must already have been defined by the user's
    application program"; DG 5859: "Aborting the program does not stop the Oscilloscope from recording"."""
    link = EmbeddedLink()
    link.download(image("DIM buf[20]\nDELAY 5\n"))
    link.start()
    link.advance(2)
    link.call("start_recording", signals=["4119", "4119"], interval_ms=1, destination="buf", cyclic=False, count=0)
    link.advance(50)
    assert link.status().program_state == "ended"
    data = link.call("stop_recording")
    assert len(data["samples"]) == 10  # fill: 20 elements / 2 values per set
    assert link.read_array(0)[:4] == [data["samples"][0][0]] * 2 + [data["samples"][1][0]] * 2


def test_bad_set_ups_are_refused_with_the_controller_errors():
    """DG 7121, 11400: more than 20 indices → error 195; too many sets for the memory → 194/171."""
    link = EmbeddedLink()
    with pytest.raises(LinkError) as e:
        link.call("start_recording", signals=["4097"] * 21, interval_ms=1, destination="DYNMEM", cyclic=False,
                  count=10)
    assert e.value.number == 195
    with pytest.raises(LinkError) as e:
        link.call("start_recording", signals=["4097"], interval_ms=1, destination="DYNMEM", cyclic=False,
                  count=10**9)
    assert e.value.number == 194
    with pytest.raises(LinkError, match="no array 'nope'"):
        link.call("start_recording", signals=["4097"], interval_ms=1, destination="nope", cyclic=False, count=1)
    with pytest.raises(LinkError, match="unknown signal 'NOPE'"):
        link.call("start_recording", signals=["NOPE"], interval_ms=1, destination="DYNMEM", cyclic=False, count=1)
    with pytest.raises(LinkError, match="no Single Shot recording"):
        link.call("stop_recording")


def test_testsetp_upload_gives_the_time_of_the_first_set():
    link = EmbeddedLink()
    link.download(image("DIM test[300]\nTESTSETP 1 4097 4098 0x01270001 test\nTESTSTART 0\nDELAY 200\n"
                        "TESTSTOP 0\n"))
    link.start()
    link.advance(400)
    (entry,) = link.call("list_recordings")
    assert entry["running"] is False
    data = link.call("upload_recording", index=0)
    assert len(data["samples"]) == 100
    assert data["first_ms"] == data["start_ms"] + 1
