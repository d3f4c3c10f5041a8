"""Start the Qt application: the GUI mode of the `motiontool` command."""

from __future__ import annotations

import contextlib
import importlib
import os
import sys
from pathlib import Path

NO_DISPLAY_HELP = """\
motiontool: no display found (neither DISPLAY nor WAYLAND_DISPLAY is set), so the IDE window cannot open.
  - On a machine without a screen, render the window offscreen and save a picture of it:
        QT_QPA_PLATFORM=offscreen motiontool --screenshot window.png
  - Or work headless with the sub-commands:  motiontool params | check | compile | run   (--help for each)
  - Or start a virtual display:  xvfb-run motiontool
"""


def has_display() -> bool:
    """True when Qt can open windows: a display server, or an explicitly chosen platform plugin."""
    if sys.platform in ("win32", "darwin"):
        return True
    return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY")
                or os.environ.get("QT_QPA_PLATFORM"))


def run_gui(open_file: Path | None = None, screenshot: Path | None = None) -> int:
    """Show the main window; with `screenshot`, save a PNG once it has painted and exit."""
    if not has_display():
        if screenshot is None:
            sys.stderr.write(NO_DISPLAY_HELP)
            return 1
        os.environ["QT_QPA_PLATFORM"] = "offscreen"  # a screenshot needs no screen
    from PySide6.QtCore import QTimer
    from PySide6.QtWidgets import QApplication

    from motiontool.ui.main_window import MainWindow

    app = QApplication.instance() or QApplication(sys.argv[:1])
    app.setApplicationName("motiontool")
    app.setOrganizationName("motiontool")
    from motiontool.ui.gui_gc import install as collect_on_gui_thread

    collect_on_gui_thread(app)  # never destroy a widget from a worker thread
    if screenshot is not None:  # a screenshot is reproducible: default settings, default size
        import tempfile

        from PySide6.QtCore import QSettings

        scratch = tempfile.TemporaryDirectory()
        window = MainWindow(settings=QSettings(f"{scratch.name}/settings.ini", QSettings.Format.IniFormat))
        window.ask_to_save = False
    else:
        from PySide6.QtCore import QSettings

        from motiontool.ui.language import install

        app.translator = install(app, QSettings())  # Settings → Language, from this start on (DG 3113-3115)
        window = MainWindow()
    if open_file is not None:
        try:
            if open_file.suffix.lower() == ".m":
                window.open_file(open_file)
            else:
                from motiontool.ui.documents import open_document

                window.new_file()
                open_document(window, open_file)
        except OSError as exc:
            sys.stderr.write(f"motiontool: cannot open {open_file}: {exc.strerror}\n")
            return 1
    elif window.open_last_file() is None:
        window.new_file()
    window.development.connect_default()  # the IDE starts on the embedded simulated controller
    window.show()
    if screenshot is None:  # only autosaves of IDEs that are gone (decisions R8), asked over the open window
        from motiontool.ui.recovery import offer_recovery

        offer_recovery(window)
    if screenshot is None:
        _preload_curve_maths()
        code = app.exec()
        window.controllers.close()
        return code

    result = {"code": 1}

    def grab() -> None:
        screenshot.parent.mkdir(parents=True, exist_ok=True)
        ok = window.grab().save(str(screenshot), "PNG")
        result["code"] = 0 if ok else 1
        if not ok:
            sys.stderr.write(f"motiontool: could not write {screenshot}\n")
        app.quit()

    # Grab after the event loop has run a few paint cycles so the picture is complete.
    QTimer.singleShot(300, grab)
    app.exec()
    window.controllers.close()
    return result["code"]


def _preload_curve_maths() -> None:
    """Import the curve maths (scipy, ~1.3 s of the CAM-Editor's first opening, issue 23 item 10) on a worker
    thread while the user looks at the window, so Tools ▸ CAM-Editor and a first SETCURVE do not wait for it.
    Only Qt-free modules: nothing Qt is imported off the GUI thread. A failure here shows again, with its
    message, where the module is really used."""
    import threading

    def work() -> None:
        for module in ("motiontool.camcurve.layout", "motiontool.cameditor.transfer", "motiontool.formats.zbc",
                       "motiontool.formats.dat", "motiontool.cameditor.apcconvert", "motiontool.cameditor.apcdpl"):
            with contextlib.suppress(Exception):
                importlib.import_module(module)  # cached in sys.modules for the editor's own import

    threading.Thread(target=work, name="preload curve maths", daemon=True).start()
