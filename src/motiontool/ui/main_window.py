"""The APOSS main window: menu bar as in the manual, edit tabs, Communication pane, status bar.

Entries that are not built yet are present but disabled, so the menu structure users know is visible
from the start (ide-spec 1.26, 1.39-1.50, 2.14-2.15).
"""

from __future__ import annotations

from pathlib import Path

from PySide6.QtCore import Qt
from PySide6.QtGui import QAction, QFont, QFontDatabase, QKeySequence
from PySide6.QtWidgets import (
    QDockWidget,
    QLabel,
    QMainWindow,
    QMessageBox,
    QPlainTextEdit,
    QTabWidget,
)

from motiontool import __version__

# (menu, [(text, shortcut or None, slot name or None)]); None entry = separator.
_MENUS: list[tuple[str, list[tuple[str, str | None, str | None] | None]]] = [
    ("&File", [
        ("&New", "Ctrl+N", "new_file"), ("&Open...", "Ctrl+O", None), ("&Close", None, "close_tab"),
        ("&Save", "Ctrl+S", None), ("Save &as...", None, None), None,
        ("&Print...", "Ctrl+P", None), ("Print set&up...", None, None), None,
        ("Sa&mple", None, None), None, ("E&xit Program", None, "close"),
    ]),
    ("&Edit", [
        ("&Undo", "Ctrl+Z", None), ("Cu&t", "Ctrl+X", None), ("&Copy", "Ctrl+C", None),
        ("&Paste", "Ctrl+V", None), None, ("&Find...", "Ctrl+F", None), ("&Replace...", "Ctrl+R", None),
        ("Find in F&iles...", None, None), None, ("Next Bookmark", "F2", None),
        ("Previous Bookmark", "Shift+F2", None), ("Toggle Bookmark", "Ctrl+F2", None),
        ("Clear All Bookmarks", None, None), None, ("Convert Tabs", None, None),
    ]),
    ("&Development", [
        ("&Execute", "F5", None), ("&Break", "Esc", None), ("C&ontinue", None, None), None,
        ("Prepare Singlestep", None, None), ("Go", None, None), ("Singlestep", "F9", None),
        ("End Debug", None, None), None, ("Watch Add", None, None), ("Watch Start", None, None),
        ("Watch Stop", None, None), None, ("&Syntax Check", "F4", None), ("Compile to file...", None, None),
        None, ("Break all", None, None), ("Start all", None, None), ("Download all", None, None),
        ("Delete Programs all", None, None), None, ("Select Controller...", None, None),
        ("Close Interface", None, None), ("Close All Interfaces", None, None), None,
        ("Command List...", "F12", None),
    ]),
    ("&Controller", [
        ("&Programs...", None, None), ("P&arameters", None, None), ("&Memory", None, None),
        ("&Reset", None, None), None, ("Error &History...", None, None),
        ("&Diagnostic Report...", None, None),
    ]),
    ("&Tools", [
        ("&CAM-Editor", None, None), ("&Array Editor", None, None), ("&Oscilloscope", None, None),
    ]),
    ("&Settings", [
        ("&Editor...", None, None), ("&Compiler...", None, None), ("&Options...", None, None),
        ("&Interface...", None, None), ("&Language...", None, None),
    ]),
    ("&Window", [
        ("&Cascade", None, None), ("Tile &vertically", None, None), ("Tile &horizontally", None, None),
    ]),
    ("&Help", [
        ("&Contents", "F1", None), ("&Index", None, None), ("&SDO Dictionary", "F11", None), None,
        ("&About Program", None, "about"),
    ]),
]


class MainWindow(QMainWindow):
    """The APOSS window: edit tabs, Communication pane, status bar with line:column and controller."""

    def __init__(self) -> None:
        super().__init__()
        self.setWindowTitle("motiontool — APOSS")
        self.resize(1100, 720)
        self.actions_by_text: dict[str, QAction] = {}
        self._build_menus()

        self.tabs = QTabWidget(self)
        self.tabs.setTabsClosable(True)
        self.tabs.setDocumentMode(True)
        self.tabs.tabCloseRequested.connect(self.close_tab)
        self.tabs.currentChanged.connect(self._update_cursor_label)
        self.setCentralWidget(self.tabs)

        self.messages = QPlainTextEdit(self)
        self.messages.setReadOnly(True)
        self.messages.setFont(QFontDatabase.systemFont(QFontDatabase.SystemFont.FixedFont))
        dock = QDockWidget("Communication", self)
        dock.setObjectName("communication")
        dock.setWidget(self.messages)
        self.addDockWidget(Qt.DockWidgetArea.BottomDockWidgetArea, dock)

        self.cursor_label = QLabel("1:1")
        self.controller_label = QLabel("Controller: embedded simulator (not connected)")
        self.statusBar().addPermanentWidget(self.controller_label)
        self.statusBar().addPermanentWidget(self.cursor_label)
        self.log(f"motiontool {__version__} — APOSS programming for the MCO 305")

    def _build_menus(self) -> None:
        for title, entries in _MENUS:
            menu = self.menuBar().addMenu(title)
            for entry in entries:
                if entry is None:
                    menu.addSeparator()
                    continue
                text, shortcut, slot = entry
                action = menu.addAction(text)
                if shortcut:
                    action.setShortcut(QKeySequence(shortcut))
                if slot is None:
                    action.setEnabled(False)  # not built yet; the entry shows where it will be
                else:
                    action.triggered.connect(getattr(self, slot))
                self.actions_by_text[text.replace("&", "")] = action

    # --- editing ---------------------------------------------------------------------------------
    def open_file(self, path: Path) -> QPlainTextEdit:
        """Open a program in a new edit tab (read as UTF-8, undecodable bytes replaced)."""
        text = path.read_bytes().decode("utf-8", errors="replace")
        return self._add_editor(path.name, text, path)

    def new_file(self) -> QPlainTextEdit:
        return self._add_editor("Untitled", "", None)

    def _add_editor(self, title: str, text: str, path: Path | None) -> QPlainTextEdit:
        editor = QPlainTextEdit(self)
        font = QFontDatabase.systemFont(QFontDatabase.SystemFont.FixedFont)
        font.setStyleHint(QFont.StyleHint.Monospace)
        editor.setFont(font)
        editor.setLineWrapMode(QPlainTextEdit.LineWrapMode.NoWrap)
        editor.setPlainText(text)
        editor.setProperty("path", str(path) if path else "")
        editor.cursorPositionChanged.connect(self._update_cursor_label)
        self.tabs.setCurrentIndex(self.tabs.addTab(editor, title))
        return editor

    def close_tab(self, index: int | bool = False) -> None:
        index = self.tabs.currentIndex() if isinstance(index, bool) else index
        if index >= 0:
            self.tabs.removeTab(index)

    def _update_cursor_label(self) -> None:
        editor = self.tabs.currentWidget()
        if isinstance(editor, QPlainTextEdit):
            cursor = editor.textCursor()
            self.cursor_label.setText(f"{cursor.blockNumber() + 1}:{cursor.positionInBlock() + 1}")

    # --- messages --------------------------------------------------------------------------------
    def log(self, line: str) -> None:
        """Append a line to the Communication pane."""
        self.messages.appendPlainText(line)

    def about(self) -> None:
        QMessageBox.about(self, "About motiontool", f"motiontool {__version__}\nAPOSS IDE for the MCO 305")
