import os

# Every test runs without a screen; Qt renders offscreen.
os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
