"""The APOSS main window (ide-spec 1.1-1.50, 2.1-2.15): program tabs with the CodeEditor, Communication pane,
outline, status bar with the controller, the manual's menus and shortcuts. A controller is reached only
through the LinkBridge (a comms Link)."""

from __future__ import annotations

import sys
from pathlib import Path

from PySide6.QtCore import QSettings, Qt, QTimer
from PySide6.QtGui import QAction, QKeySequence
from PySide6.QtWidgets import (
    QDockWidget,
    QLabel,
    QListWidget,
    QListWidgetItem,
    QMainWindow,
    QMessageBox,
    QTabWidget,
)

from motiontool import __version__
from motiontool.aposs.driver import CompileResult
from motiontool.dpl.driver import is_dpl
from motiontool.resources import resources_path
from motiontool.session.prompts import Prompts
from motiontool.ui.bridge import LinkBridge
from motiontool.ui.development import Development
from motiontool.ui.editor.bookmarks import BookmarkStore
from motiontool.ui.editor.code_editor import CodeEditor
from motiontool.ui.editor.macros import MacroSlots
from motiontool.ui.messages import MessagesPane
from motiontool.ui.prompts import QtPrompts
from motiontool.ui.recovery import Autosave, Recovery

LIVE_CHECK_MS = 600   # live diagnostics after this pause in typing
MAX_RECENT = 8
PROGRAM_FILTER = "APOSS programs (*.m);;DPL programs (*.dpl)"


class MainWindow(QMainWindow):
    """The APOSS window: edit tabs, Communication pane, outline, status bar with line:column and controller."""

    ask_to_save = True  # tests and scripted runs switch the "Save changes?" question off

    def __init__(self, settings: QSettings | None = None, realtime_factor: float = 1.0, controllers=None,
                 prompts: Prompts | None = None, macros: MacroSlots | None = None) -> None:
        super().__init__()
        self.settings = settings or QSettings()
        self.prompts: Prompts = prompts or QtPrompts(self)   # what commands ask the user goes through this
        self.realtime_factor = realtime_factor
        self.setWindowTitle("motiontool — APOSS")
        self.resize(1180, 760)
        self.actions_by_text: dict[str, QAction] = {}
        from motiontool.ui.connection import new_registry

        self.controllers = controllers or new_registry(self.settings, realtime_factor)  # shared by its windows
        self.bridge = LinkBridge(self)
        self.development = Development(self)
        self.bookmark_store = BookmarkStore(Path(self._config_dir()) / "bookmarks.json")
        self.recovery = Recovery(Path(self._config_dir()) / "recovery")

        self.tabs = QTabWidget(self)
        self.tabs.setTabsClosable(True)
        self.tabs.setDocumentMode(True)
        self.tabs.setMovable(True)
        self.tabs.tabCloseRequested.connect(self.close_tab)
        self.tabs.currentChanged.connect(self._current_changed)
        self.setCentralWidget(self.tabs)

        self.messages = MessagesPane(self)
        self.messages.locationActivated.connect(self._show_location)
        # the IDE's macros, shared by its editors and windows and kept in the settings file (DG L2204)
        self.macros = macros if macros is not None else MacroSlots.kept_in(self.settings, self.messages.ide)
        messages_dock = self._dock("Communication", self.messages, Qt.DockWidgetArea.BottomDockWidgetArea)
        self.outline = QListWidget(self)
        self.outline.itemActivated.connect(self._outline_jump)
        self.outline.itemClicked.connect(self._outline_jump)
        outline_dock = self._dock("Outline", self.outline, Qt.DockWidgetArea.LeftDockWidgetArea)
        self.resizeDocks([outline_dock], [170], Qt.Orientation.Horizontal)
        self.resizeDocks([messages_dock], [160], Qt.Orientation.Vertical)

        self.cursor_label = QLabel("1:1")
        self.controller_label = QLabel("Controller: not connected")
        self.statusBar().addPermanentWidget(self.controller_label)
        from motiontool.ui.connection import Connection

        self.connection = Connection(self)
        self.statusBar().addPermanentWidget(self.cursor_label)

        from motiontool.ui.debugger import Debugger
        from motiontool.ui.menus import build_menus

        self.debugger = Debugger(self)
        self.addDockWidget(Qt.DockWidgetArea.BottomDockWidgetArea, self.debugger.watch)
        self.debugger.watch.hide()
        build_menus(self)
        from motiontool.ui.toolbar import build_toolbar

        self.toolbar = build_toolbar(self)
        from motiontool.ui.pending_error import PendingError

        self.pending_error = PendingError(self)  # the red "Error N" and Clear Error in the status bar
        self.pending_error.attach()
        self.bridge.printed_lines.connect(lambda cid, texts: self.messages.controller_lines(cid, texts))
        self.bridge.controller_error.connect(self._controller_error)
        self.bridge.program_event.connect(self._program_event)
        self._last_error: dict[int, tuple[int, str, int | None]] = {}  # controller ID → number, text, line
        self.bridge.status_changed.connect(self._status_changed)
        self.bridge.connection_changed.connect(self._connection_changed)

        self._live = QTimer(self)
        self._live.setSingleShot(True)
        self._live.setInterval(LIVE_CHECK_MS)
        self._live.timeout.connect(self.live_check)
        from motiontool.ui.live_check import LiveCheck

        self.checker = LiveCheck(self, self.show_diagnostics)
        self.autosaver = Autosave(self, self.recovery)  # a moment after typing stops (decisions R8)
        self.messages.ide(f"motiontool {__version__} — APOSS programming for the MCO 305")
        self.restoreGeometry(self.settings.value("window/geometry", b""))
        self.restoreState(self.settings.value("window/state", b""))

    def _config_dir(self) -> str:
        path = Path(self.settings.fileName()).parent / "motiontool"
        path.mkdir(parents=True, exist_ok=True)
        return str(path)

    def _dock(self, title: str, widget, area) -> QDockWidget:
        dock = QDockWidget(title, self)
        dock.setObjectName(title.lower())
        dock.setWidget(widget)
        self.addDockWidget(area, dock)
        return dock

    # --- editors ----------------------------------------------------------------------------------------
    def current_editor(self) -> CodeEditor | None:
        widget = self.tabs.currentWidget()
        return widget if isinstance(widget, CodeEditor) else None

    def editors(self) -> list[CodeEditor]:
        return [self.tabs.widget(i) for i in range(self.tabs.count())]

    def new_file(self) -> CodeEditor:
        """A new tab "Untitled", then "Untitled 2", "Untitled 3" while the others are open (two tabs both called
        Untitled could not be told apart, issue 23)."""
        taken = {e.property("untitled") for e in self.editors() if not e.property("path")}
        name = next(f"Untitled {n}" if n > 1 else "Untitled" for n in range(1, len(taken) + 2)
                    if (f"Untitled {n}" if n > 1 else "Untitled") not in taken)
        editor = self._add_editor(name, "", None)
        editor.setProperty("untitled", name)
        return editor

    def open_file(self, path: Path) -> CodeEditor:
        """Open a program in a new tab; a program already open is brought to the front (ide-spec 1.1)."""
        path = Path(path).resolve()
        for editor in self.editors():
            if editor.property("path") == str(path):
                self.tabs.setCurrentWidget(editor)
                return editor
        from motiontool.aposs.preprocess import MAX_SOURCE_BYTES
        from motiontool.fileio import read_bytes

        data = read_bytes(path, MAX_SOURCE_BYTES, "program file")  # a device or pipe would never end (R4)
        text = data.decode("utf-8", errors="replace").replace("\r\n", "\n")
        editor = self._add_editor(path.name, text, path)
        editor.bookmarks.load_bookmarks(self.bookmark_store, path=path)
        self._remember_recent(path)
        return editor

    def open_or_report(self, path: Path):
        """A file the user chose again (a recent file, a Find in Files hit) opens in its window; one that cannot
        be read any more (deleted, a folder, a pipe) is said in a message, not a traceback (ui/documents.py)."""
        from motiontool.ui.documents import open_document

        return open_document(self, Path(path))

    def open_dialog(self) -> None:
        """File → Open: programs here, .zbc/.zbo/.zba and Testrun files in their windows (ui/documents.py)."""
        from motiontool.ui.documents import open_dialog

        open_dialog(self)

    def open_sample(self, name: str) -> CodeEditor:
        """File → Sample: a copy of the sample opens as a new, unsaved program (the original stays intact)."""
        text = resources_path("samples", name).read_text(encoding="utf-8")
        editor = self._add_editor(name, text, None)
        editor.setProperty("sample", name)
        from motiontool.ui.io_panel import offer_test_settings

        offer_test_settings(self, editor, name)  # a sample waiting for inputs says so and offers them
        return editor

    def editor_settings(self):
        from motiontool.ui.editor.settings import EditorColors, EditorSettings

        s = self.settings
        colors = s.value("editor/colors", None)
        try:
            return EditorSettings(tab_size=int(s.value("editor/tab_size", 4)),
                                  convert_tabs_while_typing=s.value("editor/convert_tabs", False, type=bool),
                                  colors=EditorColors.from_dict(dict(colors)) if colors else EditorColors())
        except (ValueError, TypeError):  # a damaged settings file falls back to the defaults
            return EditorSettings()

    def set_editor_settings(self, settings) -> None:
        self.settings.setValue("editor/tab_size", settings.tab_size)
        self.settings.setValue("editor/convert_tabs", settings.convert_tabs_while_typing)
        self.settings.setValue("editor/colors", settings.colors.to_dict())
        for editor in self.editors():
            editor.apply_settings(settings)

    def open_last_file(self) -> CodeEditor | None:
        """Settings → Options → Open last file: reopen the most recently used file at start-up."""
        last = self.settings.value("last_file", "")
        if self.settings.value("options/open_last_file", False, type=bool) and last and Path(last).is_file():
            try:
                return self.open_file(Path(last))
            except OSError as exc:  # unreadable since (permissions, grown too large): start with a new program
                self.messages.ide(f"Cannot open the last file {last}: {exc.strerror or exc}")
        return None

    def _add_editor(self, title: str, text: str, path: Path | None) -> CodeEditor:
        editor = CodeEditor(self, settings=self.editor_settings())
        editor.prompts = self.prompts.within(editor)   # its Go to Line, Repeat, Print, Find in Files' folder
        editor.macros = self.macros
        editor.setPlainText(text)
        editor.mark_saved()
        editor.setProperty("path", str(path) if path else "")
        editor.set_language("dpl" if is_dpl(path or title) else "aposs")
        editor.cursorLineColChanged.connect(lambda line, col: self.cursor_label.setText(f"{line}:{col}"))
        editor.textChanged.connect(self._live.start)
        editor.textChanged.connect(self.autosaver.changed)
        editor.document().modificationChanged.connect(lambda _m, *, e=editor: self._update_tab_title(e))
        editor.openLocationRequested.connect(self._open_location)
        self.tabs.setCurrentIndex(self.tabs.addTab(editor, title))
        editor.setFocus()
        self.live_check()
        return editor

    def _update_tab_title(self, editor: CodeEditor) -> None:
        index = self.tabs.indexOf(editor)
        path = editor.property("path")
        name = Path(path).name if path else (editor.property("sample") or editor.property("untitled") or "Untitled")
        self.tabs.setTabText(index, name + (" *" if editor.document().isModified() else ""))
        self._update_title()

    def _open_location(self, path: str, line: int, col: int) -> None:
        editor = self.open_or_report(Path(path))
        if isinstance(editor, CodeEditor):
            editor.goto_line(line, col=col)

    def save(self, *, editor: CodeEditor | None = None, path: Path | None = None) -> bool:
        from motiontool.fileio import atomic_write_text

        editor = editor or self.current_editor()
        if editor is None:
            return False
        target = path or (Path(editor.property("path")) if editor.property("path") else None)
        if target is None:
            target = self.prompts.save_name("Save as", "program.m", PROGRAM_FILTER)  # adds .m/.dpl to a bare name
            if target is None:
                return False
        try:
            atomic_write_text(target, editor.toPlainText())
        except OSError as exc:  # the buffer, its autosave and the window stay as they are (decisions R7)
            from motiontool.ui.file_errors import save_failed

            save_failed(self, "Save", target, exc, "Nothing was lost: the program is still open in the editor. "
                        "Save it somewhere else with File → Save as.")
            return False
        editor.setProperty("path", str(target.resolve()))
        editor.set_language("dpl" if is_dpl(target) else "aposs")
        editor.mark_saved()
        self._save_bookmarks(editor, target.resolve())
        self.recovery.discard(editor)
        self._remember_recent(target)
        self._update_tab_title(editor)
        return True

    def save_as(self) -> bool:
        editor = self.current_editor()
        if editor is None:
            return False
        chosen = self.prompts.save_name("Save as", editor.property("path") or "program.m", PROGRAM_FILTER)
        return chosen is not None and self.save(editor=editor, path=chosen)

    def close_tab(self, index: int) -> bool:
        """Close tab `index` (the tab bar's close button sends it), asking to save a changed program."""
        editor = self.tabs.widget(index)
        if editor is None:
            return True
        if editor.document().isModified() and self.ask_to_save:
            name = self.tabs.tabText(index).removesuffix(" *")  # the tab's "changed" mark is not part of the name
            answer = self.prompts.save_changes("Close", f"Save changes to {name}?")
            if answer is None:
                return False
            if answer == "save" and not self.save(editor=editor):
                return False
        if editor.property("path"):
            self._save_bookmarks(editor, editor.property("path"))
        self.recovery.discard(editor)
        self.tabs.removeTab(index)
        editor.deleteLater()
        return True

    def _save_bookmarks(self, editor: CodeEditor, path) -> None:
        try:
            editor.bookmarks.save_bookmarks(self.bookmark_store, path=path)
        except OSError as exc:  # the program itself is saved; its bookmarks are a convenience
            self.messages.ide(f"Bookmarks not saved: cannot write {self.bookmark_store.path}: {exc.strerror or exc}")

    # --- recent files / settings ------------------------------------------------------------------------------
    def recent_files(self) -> list[str]:
        value = self.settings.value("recent", [])
        return [value] if isinstance(value, str) else list(value or [])

    def _remember_recent(self, path: Path) -> None:
        files = [str(Path(path).resolve())] + [f for f in self.recent_files() if f != str(Path(path).resolve())]
        self.settings.setValue("recent", files[:MAX_RECENT])
        self.settings.setValue("last_file", str(Path(path).resolve()))
        if hasattr(self, "recent_menu"):
            from motiontool.ui.menus import fill_recent_menu

            fill_recent_menu(self)

    def closeEvent(self, event) -> None:  # noqa: N802 - Qt override
        scopes = sys.modules.get("motiontool.scope.ui")  # not loaded: no oscilloscope was opened
        if scopes is not None and not scopes.close_scopes(self):  # an unsaved recording, and the user cancelled
            event.ignore()
            return
        while self.tabs.count():
            if not self.close_tab(0):
                event.ignore()
                return
        self.settings.setValue("window/geometry", self.saveGeometry())
        self.settings.setValue("window/state", self.saveState())
        self.messages.stop_log()
        self.recovery.close()  # every buffer was saved or discarded
        self.connection.window_closed()
        event.accept()

    # --- live diagnostics, outline ---------------------------------------------------------------------------
    def live_check(self) -> None:
        """Check the current program in the background of typing (debounced): the outline at once, the
        diagnostics from a worker thread, an older check cancelled (ui/live_check.py)."""
        editor = self.current_editor()
        if editor is None:
            return
        self._fill_outline(editor)
        self.checker.request(editor, self.program_label(editor))

    def program_label(self, editor: CodeEditor) -> str:
        """The name the compiler gives the program: its path, else the sample's name, else Untitled.m."""
        return editor.property("path") or (editor.property("sample") or "Untitled.m")

    def show_diagnostics(self, editor: CodeEditor, result: CompileResult) -> None:
        editor.set_diagnostics(result.diagnostics, file=self.program_label(editor))

    def _show_location(self, file: str, line: int, col: int, controller_id) -> None:
        from motiontool.ui.documents import show_location

        show_location(self, file, line, col, controller_id)

    def _fill_outline(self, editor: CodeEditor) -> None:
        self.outline.clear()
        for item in editor.outline():
            entry = QListWidgetItem(f"{item.kind}: {item.name}  ({item.line})")
            entry.setData(Qt.ItemDataRole.UserRole, item.line)
            self.outline.addItem(entry)
        if not self.outline.count():  # say why the pane is empty rather than show a blank panel
            hint = QListWidgetItem("No labels, subprograms\nor functions")
            hint.setFlags(Qt.ItemFlag.NoItemFlags)
            self.outline.addItem(hint)

    def _outline_jump(self, item: QListWidgetItem) -> None:
        editor = self.current_editor()
        if editor is not None and item.data(Qt.ItemDataRole.UserRole) is not None:
            editor.goto_line(int(item.data(Qt.ItemDataRole.UserRole)))
            editor.setFocus()

    def _current_changed(self) -> None:
        self._update_title()
        editor = self.current_editor()
        if editor is not None:
            line, col = editor.caret_line_col()
            self.cursor_label.setText(f"{line}:{col}")
            self.live_check()

    # --- autosave and crash recovery -------------------------------------------------------------------------
    def autosave(self) -> None:
        self.autosaver.run()

    def recover(self) -> int:
        """Reopen the buffers IDEs that are gone left in the recovery folder; returns how many. Each is autosaved
        into this IDE's session before the old copies are deleted."""
        buffers = self.recovery.pending()
        blank = [e for e in self.editors() if not e.property("path") and not e.property("sample")
                 and not e.document().isModified() and not e.toPlainText()]  # the start-up's empty Untitled
        for buffer in buffers:
            original = buffer.original
            editor = self._add_editor(Path(original).name if original else "Recovered", buffer.text,
                                      Path(original) if original else None)
            editor.document().setModified(True)
        for editor in blank if buffers else []:  # the restored programs take its place
            self.tabs.removeTab(self.tabs.indexOf(editor))
            editor.deleteLater()
        self.autosaver.run()
        if self.autosaver.failed is None:
            self.recovery.forget_abandoned(delete=True)
        else:  # the copies could not be made: keep the old ones for the next start
            self.recovery.forget_abandoned(delete=False)
        return len(buffers)

    # --- controller ------------------------------------------------------------------------------------------
    def _controller_error(self, time_ms: int, number: int, text: str, line, cid: int) -> None:
        self.development.note_error(cid, time_ms, number)  # the Error History names this program (I19)
        line = self.pending_error.report(time_ms, number, text, line, cid)  # with its detail and a hint
        self._last_error[cid] = (number, text, line)

    def _program_event(self, time_ms: int, text: str, cid: int) -> None:
        """A program that ends with an error says which error and where (as `motiontool run` does)."""
        if text == "program error" and cid in self._last_error:
            _number, error, line = self._last_error[cid]
            text = f"program ended with {error}" + (f" (line {line})" if line else "")
        self.messages.controller(cid, text)

    def _status_changed(self, status) -> None:
        state = {"idle": "idle", "running": "running", "break": "stopped", "ended": "program ended",
                 "error": "program ended with an error"}.get(status.program_state, status.program_state)
        line = f", line {status.line}" if status.line and status.program_state in ("running", "break", "error") \
            else ""
        error = f" — error {status.error}" if status.error else ""
        self.controller_label.setText(f"{self.bridge.description}: {state}{line}{error}")
        self.pending_error.status(status)
        self._update_title()

    def _connection_changed(self, state: str) -> None:
        self.pending_error.status(self.bridge.last_status if state == "connected" else None)
        if state == "lost":
            cid = self.bridge.controller_id
            self.controller_label.setText(f"Controller {cid} ({self.connection.interface_description}): "
                                          "Lost connection")
            self.connection.lost()
        elif state == "closed":
            self.controller_label.setText("Controller: not connected")
        self._update_title()

    def _update_title(self) -> None:
        editor = self.current_editor()
        name = self.tabs.tabText(self.tabs.currentIndex()) if editor is not None else "APOSS"
        # a controller's error belongs to the program that ran there: its tab shows it, not every tab (I8)
        ran = self.development.ran.get(self.bridge.controller_id)
        suffix = self.connection.title_suffix(error=ran is None or ran is editor)
        self.setWindowTitle(f"motiontool — {name}{suffix}")

    def about(self) -> None:
        QMessageBox.about(self, "About motiontool",
                          f"motiontool {__version__}\nAPOSS IDE for the MCO 305\nCompiler and simulator built in")


__all__ = ["MainWindow", "QKeySequence"]
