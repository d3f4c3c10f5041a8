"""Amplitude spectrum of a curve (FFT view, beyond the manual: peers.md "FFT and statistics on traces").

The samples between two times are resampled onto their median interval (recordings are equidistant; polled
curves nearly so), the mean removed, a Hann window applied, and the single-sided amplitude spectrum returned
in the curve's units, so a sine of amplitude A shows a peak of about A at its frequency.
"""

from __future__ import annotations

import numpy as np

MIN_SAMPLES = 8


def amplitude_spectrum(t_ms: np.ndarray, y: np.ndarray, t0: float | None = None,
                       t1: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """(frequencies in Hz, amplitudes) of y(t) between t0 and t1 (ms; None = the whole curve)."""
    t = np.asarray(t_ms, dtype=float)
    y = np.asarray(y, dtype=float)
    keep = np.ones(t.size, dtype=bool)
    if t0 is not None:
        keep &= t >= t0
    if t1 is not None:
        keep &= t <= t1
    t, y = t[keep], y[keep]
    if t.size < MIN_SAMPLES:
        raise ValueError(f"{t.size} samples in the range: an FFT needs at least {MIN_SAMPLES}")
    dt = float(np.median(np.diff(t)))
    if dt <= 0:
        raise ValueError("the samples have no time step")
    grid = t[0] + np.arange(int((t[-1] - t[0]) / dt) + 1) * dt
    yy = np.interp(grid, t, y)
    yy = yy - yy.mean()
    window = np.hanning(yy.size)
    spectrum = np.abs(np.fft.rfft(yy * window)) * 2 / window.sum()
    freqs = np.fft.rfftfreq(yy.size, dt / 1000.0)
    return freqs, spectrum
