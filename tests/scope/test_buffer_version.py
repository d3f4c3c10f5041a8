"""RingBuffer.version: caches of derived data (decimated lines) compare it, so it must never repeat."""

from motiontool.scope.buffer import RingBuffer


def test_version_strictly_increases_on_every_change_including_set_capacity():
    """A view that cached the version before a capacity change must see a new one afterwards, even when
    set_capacity drops samples or keeps none (DG 5995-6001: the oldest points are dropped)."""
    buf = RingBuffer(4)
    seen = [buf.version]

    def changed():
        assert buf.version > seen[-1], f"version {buf.version} after {seen[-1]}"
        seen.append(buf.version)

    buf.extend([0, 1, 2, 3, 4], [0, 1, 2, 3, 4])
    changed()
    buf.set_capacity(2)                 # drops samples
    changed()
    assert buf.arrays()[0].tolist() == [3.0, 4.0]
    buf.set_capacity(8)                 # keeps all
    changed()
    buf.clear()
    changed()
    buf.set_capacity(3)                 # empty: nothing re-written, still a change
    changed()
    buf.append(5, 5)
    changed()
