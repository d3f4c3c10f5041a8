"""The one sampler the controller's side uses for Free Run (MCO and APC) and Single Shot (issue 27 item 4,
decision S33)."""

import pytest

from motiontool.comms.protocol import Request
from motiontool.controller.apc_service import ApcService
from motiontool.controller.service import ControllerService
from motiontool.sampling import BoundedStore, Sampler


def test_a_stream_samples_multiples_of_its_interval_and_a_recording_counts_from_its_start():
    """S7: Free Run on ticks whose time is a multiple of the interval; S8: Single Shot "in a TESTSETP array"
    (DG 4668), sampled from the first tick after its start."""
    stream_store, record_store = BoundedStore(100, False), BoundedStore(100, False)
    stream = Sampler([lambda: 0], 3, stream_store, aligned=True)
    record = Sampler([lambda: 0], 3, record_store, aligned=False)
    for now in range(5, 20):
        stream.tick(now)
        record.tick(now)
    assert list(stream_store.times) == [6, 9, 12, 15, 18]
    assert list(record_store.times) == [5, 8, 11, 14, 17]


def test_stop_when_full_keeps_the_first_sets_and_reads_no_more():
    """DG 5308: stop when full, new data is discarded (unlike Cyclic)."""
    reads = []
    store = BoundedStore(3, cyclic=False)
    sampler = Sampler([lambda: reads.append(1) or len(reads)], 1, store, aligned=False)
    for now in range(1, 10):
        sampler.tick(now)
    assert list(store.samples) == [[1], [2], [3]] and len(reads) == 3 and not sampler.running
    cyclic = BoundedStore(3, cyclic=True)
    sampler = Sampler([lambda: 7], 2, cyclic, aligned=False)
    for now in range(1, 12):
        sampler.tick(now)
    assert list(cyclic.times) == [7, 9, 11] and cyclic.taken == 6 and sampler.running


def test_single_shot_and_free_run_read_the_same_millisecond_alike():
    """Both sample after the controller's tick: a value read by Single Shot and by Free Run at the same time
    is the same value."""
    service = ControllerService()
    packets = []
    service.listeners.append(lambda e: packets.append(e.data) if e.kind == "samples" else None)
    assert service.handle(Request("stream", {"signals": ["4119", "CPOS"], "interval_ms": 2})).ok
    service.handle(Request("advance", {"ms": 1}))  # the recording's sets then fall on even milliseconds too
    assert service.handle(Request("start_recording", {"signals": ["4119", "CPOS"], "interval_ms": 2,
                                                      "destination": "DYNMEM", "cyclic": False, "count": 50})).ok
    service.handle(Request("advance", {"ms": 60}))
    streamed = {t: v for p in packets for t, v in zip(p["time_ms"], p["values"], strict=True)}
    recorded = service.handle(Request("stop_recording")).value
    both = [(t, v) for t, v in zip(recorded["time_ms"], recorded["samples"], strict=True) if t in streamed]
    assert len(both) >= 25
    assert all(streamed[t] == v and v[0] == t for t, v in both)


@pytest.mark.parametrize("service", [ControllerService, ApcService], ids=["mco", "apc"])
def test_a_refused_stream_request_leaves_the_running_stream_as_it_was(service):
    """A bad interval used to switch the stream's signals (and, with no stream yet, stopped the clock on a
    division by zero); now it changes nothing, as the unknown signal always did."""
    s = service()
    packets = []
    s.listeners.append(lambda e: packets.append(e.data) if e.kind == "samples" else None)
    refused = s.handle(Request("stream", {"signals": ["4119"], "interval_ms": "x"}))
    assert not refused.ok and "'x'" in refused.error
    assert s.handle(Request("advance", {"ms": 5})).ok and packets == []
    assert s.handle(Request("stream", {"signals": ["4119"], "interval_ms": 2})).ok
    assert not s.handle(Request("stream", {"signals": ["APOS" if service is ControllerService else "48"],
                                           "interval_ms": "x"})).ok
    assert s.handle(Request("advance", {"ms": 40})).ok
    times = [t for p in packets for t in p["time_ms"]]
    assert {tuple(p["signals"]) for p in packets} == {("4119",)}
    assert times == list(range(6, 46, 2))
