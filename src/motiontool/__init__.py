"""motiontool — an open engineering IDE for motion controllers (MCO 305 / APOSS)."""

__version__ = "0.1.0"
