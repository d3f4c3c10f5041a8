"""The main window fixture of tests/ui, for tests that drive the oscilloscope from the IDE."""

from tests.ui.conftest import window  # noqa: F401
