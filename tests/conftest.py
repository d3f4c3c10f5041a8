import importlib.util
import os
from pathlib import Path

import pytest
from hypothesis import settings

from motiontool.controller import schemes

# Every test runs without a screen; Qt renders offscreen.
os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

# Hypothesis fails an example that takes longer than its deadline (200 ms of wall time). On a shared, loaded
# machine that measures the load, not the code: the CAM maths examples of tests/cameditor/test_editing.py
# (about 1 ms each) take up to 27 ms at load 9 and failed the deadline at load 10-14. No property test here
# is about speed (performance targets live in benchmarks/), so examples have no deadline; what each property
# checks is unchanged.
settings.register_profile("motiontool", deadline=None)
settings.load_profile("motiontool")

# The test session is a composition root, as the `motiontool` command is: `sim` and `apcsim` links open the
# simulators (controller/schemes.py; the IDE's side never imports them).
schemes.register()


TESTS = Path(__file__).resolve().parent


def pytest_addoption(parser):
    # qt_api (pyproject.toml) is pytest-qt's; the environment without Qt (make test-headless) has no pytest-qt
    if importlib.util.find_spec("pytestqt") is None:
        parser.addini("qt_api", "the Qt binding of pytest-qt (unused without it)")


def pytest_collection_modifyitems(config, items):
    """A test that needs Qt is a `gui` test: everything in a `ui` test package and every test using qtbot (the
    others run without Qt installed, `make test-headless`). The longest tests are handed out first, so that with
    several workers (pytest-xdist) none of them starts last while the others are idle."""
    for item in items:
        if "qtbot" in getattr(item, "fixturenames", ()) or "ui" in item.path.relative_to(TESTS).parts[:-1]:
            item.add_marker(pytest.mark.gui)
    weight = {"soak": 0, "slow": 1}
    items.sort(key=lambda item: min((w for m, w in weight.items() if item.get_closest_marker(m)), default=2))


@pytest.fixture(autouse=True)
def _garbage_collected_on_the_gui_thread(request):
    """A GUI test runs as the IDE does (ui/app.py): Python's cyclic collector only on the GUI thread
    (ui/gui_gc.py). With automatic collection, a worker thread (the embedded controller's kernel, a link job)
    that passed an allocation threshold destroyed garbage widgets of an earlier test; their destructor waited for
    the GIL while holding a Qt lock that the GUI thread, holding the GIL, waited for: a clean-clone run hung for
    5 minutes in two workers (py-spy: the kernel thread in gc_collect_main -> QObject::~QObject -> GilState::acquire,
    the GUI thread in Shiboken's runDeletionInMainThread -> QObject::~QObject -> QBasicMutex::lockInternal)."""
    if request.node.get_closest_marker("gui") is not None:
        from motiontool.ui.gui_gc import install

        install(request.getfixturevalue("qapp"))
    yield
