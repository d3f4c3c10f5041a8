"""Sample storage for one curve: a FIFO of (time ms, value) pairs in numpy, and min/max decimation.

The FIFO is the curve's "max number of samples" (DG 5995-6001: the oldest points are dropped). Each sample is
written twice, at i and i + capacity, so the newest `n` samples are always one contiguous slice: the view gets
them without copying, however often the buffer has wrapped.
"""

from __future__ import annotations

import numpy as np

DEFAULT_CAPACITY = 10_000   # the manual's example "max number of samples" (DG 5995-6001)


class RingBuffer:
    def __init__(self, capacity: int = DEFAULT_CAPACITY):
        self.version = 0        # changes on every write: caches of derived data compare it
        self._allocate(capacity)

    def _allocate(self, capacity: int) -> None:
        if capacity < 1:
            raise ValueError(f"sample limit {capacity}: at least 1")
        self.capacity = int(capacity)
        self._t = np.zeros(2 * self.capacity)
        self._y = np.zeros(2 * self.capacity)
        self._head = 0          # next write position in [0, capacity)
        self.count = 0

    def __len__(self) -> int:
        return self.count

    def clear(self) -> None:
        self._head = 0
        self.count = 0
        self.version += 1

    def extend(self, t, y) -> None:
        t = np.asarray(t, dtype=float).ravel()
        y = np.asarray(y, dtype=float).ravel()
        if t.shape != y.shape:
            raise ValueError(f"{t.size} times for {y.size} values")
        if t.size > self.capacity:  # only the newest fit
            t, y = t[-self.capacity:], y[-self.capacity:]
        n = t.size
        if n == 0:
            return
        cap, head = self.capacity, self._head
        first = min(n, cap - head)
        for arr, src in ((self._t, t), (self._y, y)):
            arr[head:head + first] = src[:first]
            arr[head + cap:head + cap + first] = src[:first]
            if first < n:
                arr[:n - first] = src[first:]
                arr[cap:cap + n - first] = src[first:]
        self._head = (head + n) % cap
        self.count = min(cap, self.count + n)
        self.version += 1

    def append(self, t: float, y: float) -> None:
        self.extend([t], [y])

    def arrays(self) -> tuple[np.ndarray, np.ndarray]:
        """(times, values), oldest first: read-only views, valid until the next write."""
        end = self._head + self.capacity   # every sample also lives at i + capacity
        start = end - self.count
        t, y = self._t[start:end], self._y[start:end]
        t.flags.writeable = False
        y.flags.writeable = False
        return t, y

    def set_capacity(self, capacity: int) -> None:
        """Change the sample limit keeping the newest samples."""
        t, y = (a.copy() for a in self.arrays())
        self._allocate(capacity)
        self.extend(t, y)
        self.version += 1       # never back to an old value: a view cached by version would stay stale


def visible_slice(t: np.ndarray, x0: float, x1: float) -> slice:
    """Indices of samples inside [x0, x1] plus one on each side, so lines reach the edges."""
    i0 = max(int(np.searchsorted(t, x0, side="left")) - 1, 0)
    i1 = min(int(np.searchsorted(t, x1, side="right")) + 1, t.size)
    return slice(i0, i1)


def decimate_minmax(t: np.ndarray, y: np.ndarray, bins: int) -> tuple[np.ndarray, np.ndarray]:
    """At most 2·bins points that draw like the full data at `bins` pixels: per pixel column its first
    time with the column's minimum and maximum in time order (an "envelope"; peaks are never lost)."""
    n = t.size
    if n <= 2 * bins or bins < 1:
        return t, y
    per = int(np.ceil(n / bins))
    full = (n // per) * per
    yb = y[:full].reshape(-1, per)
    tb = t[:full].reshape(-1, per)
    imin = yb.argmin(axis=1)
    imax = yb.argmax(axis=1)
    rows = np.arange(yb.shape[0])
    first = np.minimum(imin, imax)
    second = np.maximum(imin, imax)
    tt = np.empty(2 * rows.size)
    yy = np.empty(2 * rows.size)
    tt[0::2], tt[1::2] = tb[rows, first], tb[rows, second]
    yy[0::2], yy[1::2] = yb[rows, first], yb[rows, second]
    if full < n:
        tt = np.concatenate([tt, t[full:][[0, -1]]])
        rest = y[full:]
        yy = np.concatenate([yy, [rest.min(), rest.max()]])
    return tt, yy


class MinMaxPyramid:
    """Min/max of blocks of 8, 64, 512 … samples of a fixed data set, so browsing 10 M samples costs about
    the same per frame as browsing 10 k (peers.md 2.9: a cached min/max pyramid keeps decimation constant)."""

    FACTOR = 8

    def __init__(self, t: np.ndarray, y: np.ndarray):
        self.t, self.y = t, y
        self.levels: list[tuple[int, np.ndarray, np.ndarray]] = []  # (block size, min, max)
        lo = hi = y
        block = 1
        while lo.size >= 2 * self.FACTOR:
            full = (lo.size // self.FACTOR) * self.FACTOR
            lo = lo[:full].reshape(-1, self.FACTOR).min(axis=1)
            hi = hi[:full].reshape(-1, self.FACTOR).max(axis=1)
            block *= self.FACTOR
            self.levels.append((block, lo, hi))

    def window(self, x0: float, x1: float, bins: int) -> tuple[np.ndarray, np.ndarray]:
        """Envelope of the samples in [x0, x1] at about `bins` columns (times are each block's start)."""
        s = visible_slice(self.t, x0, x1)
        n = s.stop - s.start
        if n <= 4 * bins:
            return self.t[s], self.y[s]
        chosen = None
        for block, lo, hi in self.levels:
            if n // block >= 2 * bins:
                chosen = (block, lo, hi)
        if chosen is None:
            return decimate_minmax(self.t[s], self.y[s], bins)
        block, lo, hi = chosen
        b0, b1 = s.start // block, min(-(-s.stop // block), lo.size)
        lo, hi = lo[b0:b1], hi[b0:b1]
        per = max(1, lo.size // bins)
        full = (lo.size // per) * per
        lo = lo[:full].reshape(-1, per).min(axis=1)
        hi = hi[:full].reshape(-1, per).max(axis=1)
        starts = self.t[np.minimum((b0 + np.arange(lo.size) * per) * block, self.t.size - 1)]
        tt = np.repeat(starts, 2)
        yy = np.empty(2 * lo.size)
        yy[0::2], yy[1::2] = lo, hi
        return tt, yy
