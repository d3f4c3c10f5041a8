"""Garbage cycles holding Qt widgets are collected on the GUI thread, never in a worker thread.

A full test run crashed (segmentation fault in QApplication.topLevelWidgets()) when the cyclic collector, started
by the live-check thread, destroyed a widget while the GUI thread read the list of windows.
"""

from __future__ import annotations

import gc
import threading

from PySide6.QtWidgets import QWidget

from motiontool.ui.gui_gc import install


def garbage_widget(deaths: list[int]) -> None:
    """A parentless widget reachable only from itself (a cycle: only the cyclic collector frees it)."""
    widget = QWidget()
    widget.me = widget
    widget.destroyed.connect(lambda *_: deaths.append(threading.get_ident()))


def test_a_widget_in_a_garbage_cycle_dies_on_the_gui_thread(qapp, qtbot):
    collector = install(qapp)
    try:
        assert install(qapp) is collector  # one per application
        assert not gc.isenabled()
        deaths: list[int] = []
        garbage_widget(deaths)

        kept: list = []

        def allocate():  # far past every threshold: with automatic collection this thread would collect
            kept.extend([i] for i in range(5 * sum(gc.get_threshold())))

        worker = threading.Thread(target=allocate)
        worker.start()
        worker.join()
        assert deaths == []
        qtbot.waitUntil(lambda: deaths != [], timeout=5000)
        assert deaths == [threading.get_ident()]
        kept.clear()
    finally:
        collector.stop()
    assert gc.isenabled()


def test_gui_tests_collect_on_the_gui_thread_as_the_ide_does(qapp):
    """tests/conftest.py installs the collector for every GUI test, as ui/app.py does for the IDE: a worker
    thread's collection of an earlier test's widgets deadlocked a clean-clone run (the GIL against a Qt lock)."""
    from motiontool.ui.gui_gc import GuiThreadCollector

    assert not gc.isenabled()
    assert qapp.findChild(GuiThreadCollector) is not None
