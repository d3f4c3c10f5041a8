"""Several nodes' events over a wire come out in (time, node) order, as the embedded bus prints them."""

from hypothesis import given
from hypothesis import strategies as st

from motiontool.comms.eventorder import TimeOrder
from motiontool.comms.protocol import LinkEvent

# per node: a non-decreasing list of event times (a link delivers its own node's events in order)
node_times = st.lists(st.integers(0, 30), max_size=12).map(sorted)


@given(st.lists(node_times, min_size=1, max_size=4), st.randoms(use_true_random=False),
       st.lists(st.integers(0, 40), max_size=6).map(sorted))
def test_held_events_are_released_in_time_then_node_order_whatever_the_links_arrival(times, rnd, watermarks):
    events = {n: [LinkEvent("print", t, f"{n}/{k}") for k, t in enumerate(ts)] for n, ts in enumerate(times, 1)}
    out: list[tuple[int, LinkEvent]] = []
    order = TimeOrder(lambda n, e: out.append((n, e)))
    # the links deliver in any interleaving; a watermark is released only once every event up to it has arrived
    queues = {n: list(es) for n, es in events.items()}
    released = []
    for mark in watermarks:
        while any(q and q[0].time_ms <= mark for q in queues.values()):
            n = rnd.choice([n for n, q in queues.items() if q and q[0].time_ms <= mark])
            order.add(n, queues[n].pop(0))
        # some later events may already be there: they must be held
        for n, q in queues.items():
            if q and rnd.random() < 0.5:
                order.add(n, q.pop(0))
        order.release(mark)
        released.append((mark, len(out)))
        assert all(e.time_ms <= mark for _, e in out)
    for n, q in queues.items():
        for e in q:
            order.add(n, e)
    order.release()
    expected = sorted(((n, e) for n, es in events.items() for e in es), key=lambda ne: (ne[1].time_ms, ne[0]))
    assert [(n, e.text) for n, e in out] == [(n, e.text) for n, e in expected]


def test_two_nodes_printing_in_the_same_millisecond_come_out_lowest_node_first():
    out = []
    order = TimeOrder(lambda n, e: out.append(f"{n}: {e.text}"))
    order.add(2, LinkEvent("print", 1000, "slave"))      # node 2's link was polled first
    order.add(1, LinkEvent("print", 999, "early"))
    order.release(999)
    order.add(1, LinkEvent("print", 1000, "master"))
    order.release(1000)
    assert out == ["1: early", "1: master", "2: slave"]
