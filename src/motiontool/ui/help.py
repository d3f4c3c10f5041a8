"""Help (DG 2043-2049, 3244-3268, ide-spec 1.50): Contents (F1) is context help — the command under the caret
from the command table, the parameter of a dialog field —, Index lists every command, parameter and object to
search, SDO Dictionary (F11) the controller's object dictionary (system process data, axis process data,
parameters, arrays …). One help window per APOSS window, not modal: it stays open beside the program."""

from __future__ import annotations

import html
import re

from PySide6.QtCore import Qt
from PySide6.QtWidgets import (
    QDialog,
    QHBoxLayout,
    QLineEdit,
    QListWidget,
    QListWidgetItem,
    QSplitter,
    QTextBrowser,
    QVBoxLayout,
    QWidget,
)

from motiontool.aposs.commands import command_table
from motiontool.paramdb import database

_WORD = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
ROLE = Qt.ItemDataRole.UserRole


def command_page(name: str) -> str | None:
    command = command_table().get(name)
    if command is None:
        return None
    errors = ", ".join(map(str, command.errors)) or "—"
    return (f"<h2>{html.escape(command.name)}</h2><p><b>{html.escape(command.syntax)}</b></p>"
            f"<p>{html.escape(command.help)}</p><p>Group: {html.escape(command.group)}<br>"
            f"Returns: {command.returns}<br>Controller errors: {errors}<br>"
            f"Since: {html.escape(command.since or '—')}</p><p><small>{html.escape(command.src)}</small></p>")


def parameter_page(key: str) -> str | None:
    try:
        p = database().get(key)
    except (KeyError, ValueError):
        return None
    options = "".join(f"<li>{n}: {html.escape(text)}</li>" for n, text in p.options.items())
    return (f"<h2>{html.escape(p.label)}</h2><p>{html.escape(p.description)}</p>"
            f"<p>Group: {html.escape(p.group)}<br>Default: {p.default}<br>Range: {p.minimum} .. {p.maximum} "
            f"{html.escape(p.unit)}<br>Type: {html.escape(p.data_type)}<br>Changes during operation: "
            f"{'yes' if p.changes_during_operation else 'no'}<br>"
            f"{'Read only' if p.read_only else 'GET / SET ' + str(p.index)}</p>"
            + (f"<ul>{options}</ul>" if options else "")
            + f"<p><small>{html.escape(p.seed_lines)}</small></p>")


def dictionary_entries() -> list[tuple[str, str]]:
    """(label, html) of every object of the controller's object dictionary (the SDO dictionary)."""
    from motiontool.controller.canopen.eds import dictionary

    entries = []
    for index, obj in sorted(dictionary().items()):
        rows = "".join(f"<tr><td>{sub}</td><td>{html.escape(e.name)}</td><td>{e.datatype}</td><td>{e.access}</td>"
                       f"<td>0x{0x01000000 + (index << 8) + sub:08X}</td></tr>"
                       for sub, e in sorted(obj.entries.items()))
        if obj.count and obj.element is not None:  # a compact ARRAY: its elements are all alike
            first = obj.element(1)
            rows += (f"<tr><td>1 … {obj.count}</td><td>{html.escape(first.name)} …</td><td>{first.datatype}</td>"
                     f"<td>{first.access}</td><td>0x{0x01000000 + (index << 8) + 1:08X} …</td></tr>")
        page = (f"<h2>0x{index:04X} {html.escape(obj.name)}</h2><table border=1 cellpadding=3 cellspacing=0>"
                "<tr><th>Sub</th><th>Name</th><th>Type</th><th>Access</th><th>SYSVAR</th></tr>" + rows + "</table>"
                "<p>A program reads an object with SYSVAR[0x01000000 + (index &lt;&lt; 8) + sub] (CR 2039), the "
                "oscilloscope records it by the same number.</p>")
        entries.append((f"0x{index:04X} {obj.name}", page))
    return entries


class HelpWindow(QDialog):
    def __init__(self, parent=None) -> None:
        super().__init__(parent)
        self.setWindowTitle("motiontool Help")
        self.setWindowFlag(Qt.WindowType.Window, True)
        self.search = QLineEdit()
        self.search.setPlaceholderText("Search commands, parameters and objects")
        self.search.textChanged.connect(self._filter)
        self.search.returnPressed.connect(self.open_hit)
        self.index = QListWidget()
        self.index.currentItemChanged.connect(lambda item, _previous: self._show_item(item))
        self.page = QTextBrowser()
        self.page.setOpenExternalLinks(False)
        left = QWidget()
        column = QVBoxLayout(left)
        column.setContentsMargins(0, 0, 0, 0)
        column.addWidget(self.search)
        column.addWidget(self.index)
        split = QSplitter()
        split.addWidget(left)
        split.addWidget(self.page)
        split.setSizes([300, 620])
        layout = QHBoxLayout(self)
        layout.addWidget(split)
        for command in sorted(command_table(), key=lambda c: c.name):
            self._add(f"{command.name} (command)", "command", command.name)
        for p in database():
            self._add(f"{p.label} (parameter)", "parameter", p.number)
        self._dictionary: list[tuple[str, str]] | None = None
        self.resize(960, 620)

    def _add(self, text: str, kind: str, key: str) -> QListWidgetItem:
        item = QListWidgetItem(text)
        item.setData(ROLE, (kind, key))
        self.index.addItem(item)
        return item

    def _filter(self, text: str) -> None:
        needle = text.strip().lower()
        for row in range(self.index.count()):
            item = self.index.item(row)
            item.setHidden(bool(needle) and needle not in item.text().lower())

    def open_hit(self) -> bool:
        """Enter in the search field opens the selected hit if it is shown, else the first one, as the Index tab
        of the Windows help does (DG 3262); nothing when there is none."""
        current = self.index.currentItem()
        if current is None or current.isHidden():
            current = next((self.index.item(row) for row in range(self.index.count())
                            if not self.index.item(row).isHidden()), None)
        if current is None:
            return False
        self.index.setCurrentItem(current)
        self.index.scrollToItem(current)
        self._show_item(current)   # also when it was already the current item
        return True

    def _show_item(self, item: QListWidgetItem | None) -> None:
        if item is None:
            return
        kind, key = item.data(ROLE)
        if kind == "command":
            self.page.setHtml(command_page(key) or "")
        elif kind == "parameter":
            self.page.setHtml(parameter_page(key) or "")
        else:
            self.page.setHtml(self.dictionary()[int(key)][1])

    def dictionary(self) -> list[tuple[str, str]]:
        if self._dictionary is None:
            self._dictionary = dictionary_entries()
            for n, (label, _page) in enumerate(self._dictionary):
                self._add(f"{label} (object)", "object", str(n))
        return self._dictionary

    def show_entry(self, kind: str, key: str) -> bool:
        """Select the entry (and show its page); False when there is none."""
        if kind == "object":
            self.dictionary()
        for row in range(self.index.count()):
            item = self.index.item(row)
            if item.data(ROLE) == (kind, key):
                self.search.clear()
                self.index.setCurrentItem(item)
                self.index.scrollToItem(item)
                return True
        return False

    def show_index(self) -> None:
        self.search.clear()
        self.search.setFocus()
        self.page.setHtml("<h2>Index</h2><p>Type to find a command, a parameter (number or name) or, after Help → "
                          "SDO Dictionary, an object of the controller's dictionary.</p>")

    def show_dictionary(self) -> None:
        entries = self.dictionary()
        self.search.setText("(object)")
        rows = "".join(f"<li>{html.escape(label)}</li>" for label, _page in entries)
        self.page.setHtml("<h2>SDO Dictionary</h2><p>The objects of the controller's CANopen dictionary: system "
                          "process data (0x2202), axis process data (0x2500), user parameters (0x2201), every "
                          f"parameter at 0x2000 + its number, arrays (0x2100 …).</p><ul>{rows}</ul>")


def window_for(w) -> HelpWindow:
    window = getattr(w, "help_window", None)
    if window is None:
        window = w.help_window = HelpWindow(w)
    window.show()
    window.raise_()
    return window


def word_at_caret(editor) -> str:
    """The command under the caret, two words for MOTOR ON and the like."""
    cursor = editor.textCursor()
    text, col = cursor.block().text(), cursor.positionInBlock()
    words = [(m.start(), m.end(), m.group(0)) for m in _WORD.finditer(text)]
    for k, (start, end, word) in enumerate(words):
        if start <= col <= end:
            if k + 1 < len(words) and command_table().get(f"{word} {words[k + 1][2]}"):
                return f"{word} {words[k + 1][2]}"
            if k > 0 and command_table().get(f"{words[k - 1][2]} {word}"):
                return f"{words[k - 1][2]} {word}"
            return word
    return ""


def show_help(w, *, command: str | None = None, parameter: str | None = None) -> HelpWindow:
    """F1: the given command or parameter; without either the command or parameter under the caret of the
    current program, else the index."""
    window = window_for(w)
    if command is None and parameter is None and w.current_editor() is not None:
        word = word_at_caret(w.current_editor())
        if command_table().get(word) is not None:
            command = word
        elif word:
            try:
                parameter = database().get(word).number
            except (KeyError, ValueError):
                parameter = None
    if command is not None and window.show_entry("command", command_table().get(command).name):
        return window
    if parameter is not None and window.show_entry("parameter", parameter):
        return window
    window.show_index()
    return window


def show_index(w) -> HelpWindow:
    window = window_for(w)
    window.show_index()
    return window


def show_dictionary(w) -> HelpWindow:
    window = window_for(w)
    window.show_dictionary()
    return window
