"""Keyboard macros (ide-spec 1.24-1.25): record key presses, replay them, keep up to 10 under shortcuts.

Ctrl-Shift-R starts recording [DG L2206]; in the editor the same key stops it (the manual's "Record Macro"
dialog with its stop button is left to the main window, which can call ``editor.recorder.stop_recording``).
Stopping from the keyboard opens the "Save Macro" dialog [DG L2208-2216]: press the new shortcut (up to two keystrokes),
see what it is currently assigned to, choose one of the 10 "Save As" slots. The macros belong to the IDE, not
to one program: a window's editors share one MacroSlots, kept in the settings file (``MacroSlots.kept_in``), so
they "are saved and restored the next time that the APOS-IDE is started" [DG L2204].
"""

from __future__ import annotations

import json
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, NamedTuple

from PySide6.QtCore import QEvent, Qt
from PySide6.QtGui import QKeyEvent, QKeySequence
from PySide6.QtWidgets import (
    QApplication,
    QDialog,
    QDialogButtonBox,
    QKeySequenceEdit,
    QLabel,
    QListWidget,
    QVBoxLayout,
    QWidget,
)

if TYPE_CHECKING:
    from motiontool.ui.editor.code_editor import CodeEditor

MAX_MACROS = 10
MACROS_KEY = "editor/macros"
RECORD_SHORTCUT = "Ctrl+Shift+R"
_MODIFIER_MASK = (Qt.KeyboardModifier.ShiftModifier | Qt.KeyboardModifier.ControlModifier
                  | Qt.KeyboardModifier.AltModifier | Qt.KeyboardModifier.MetaModifier)


class KeyStroke(NamedTuple):
    key: int
    modifiers: int
    text: str

    @classmethod
    def from_event(cls, event: QKeyEvent) -> KeyStroke:
        return cls(int(event.key()), int(event.modifiers().value & _MODIFIER_MASK.value), event.text())

    def send(self, widget: QWidget) -> None:
        """Deliver this key press (and its release) to `widget` as if typed."""
        mods = Qt.KeyboardModifier(self.modifiers)
        for kind in (QEvent.Type.KeyPress, QEvent.Type.KeyRelease):
            QApplication.sendEvent(widget, QKeyEvent(kind, self.key, mods, self.text))


def combination(event: QKeyEvent) -> str:
    """The event's key combination in portable text ("Ctrl+Shift+M")."""
    mods = event.modifiers().value & _MODIFIER_MASK.value
    return QKeySequence(int(mods) | int(event.key())).toString(QKeySequence.SequenceFormat.PortableText)


def normalize_shortcut(shortcut: str) -> str:
    """A shortcut of one or two keystrokes in portable text; ValueError if empty or longer."""
    seq = QKeySequence(shortcut)
    if seq.isEmpty() or seq.count() > 2:
        raise ValueError(f"a macro shortcut is one or two keystrokes, got {shortcut!r}")
    return seq.toString(QKeySequence.SequenceFormat.PortableText)


class MacroSlots:
    """MAX_MACROS numbered slots, each empty or a (shortcut, keystrokes) pair."""

    def __init__(self) -> None:
        self._slots: list[tuple[str, list[KeyStroke]] | None] = [None] * MAX_MACROS
        self.listeners: list[Callable[[], None]] = []   # told after every change (the settings file keeps them)

    def _changed(self) -> None:
        for listener in list(self.listeners):
            listener()

    def slot_of(self, shortcut: str) -> int | None:
        name = normalize_shortcut(shortcut)
        return next((i for i, s in enumerate(self._slots) if s is not None and s[0] == name), None)

    def assign(self, shortcut: str, keys: list[KeyStroke], *, slot: int | None = None) -> int:
        """Store `keys` under `shortcut` in `slot` (0-based; default: the slot that already has this shortcut,
        else the first free one). Returns the slot; ValueError when no slot is free."""
        name = normalize_shortcut(shortcut)
        old = self.slot_of(name)
        if slot is None:
            slot = old if old is not None else next((i for i, s in enumerate(self._slots) if s is None), None)
            if slot is None:
                raise ValueError(f"all {MAX_MACROS} macro slots are used; choose one to overwrite")
        if not 0 <= slot < MAX_MACROS:
            raise ValueError(f"slot must be 0..{MAX_MACROS - 1}, got {slot}")
        if old is not None:
            self._slots[old] = None  # one shortcut, one macro
        self._slots[slot] = (name, list(keys))
        self._changed()
        return slot

    def get(self, shortcut: str) -> list[KeyStroke] | None:
        slot = self.slot_of(shortcut)
        return None if slot is None else list(self._slots[slot][1])

    def slots(self) -> list[str | None]:
        """The shortcut in each slot (None = unassigned)."""
        return [None if s is None else s[0] for s in self._slots]

    def shortcuts(self) -> list[str]:
        return [s for s in self.slots() if s is not None]

    def first_keys(self) -> set[str]:
        """The first keystroke of every shortcut (to recognise a pending two-key shortcut)."""
        return {s.split(", ")[0] for s in self.shortcuts()}

    def clear(self) -> None:
        """Edit → Clear Macros [DG L2225]."""
        self._slots = [None] * MAX_MACROS
        self._changed()

    def __len__(self) -> int:
        return len(self.shortcuts())

    def to_json(self) -> str:
        return json.dumps([None if s is None else [s[0], [list(k) for k in s[1]]] for s in self._slots])

    @classmethod
    def from_json(cls, text: str) -> MacroSlots:
        slots = cls()
        for i, entry in enumerate(json.loads(text)[:MAX_MACROS]):
            if entry:
                slots.assign(entry[0], [KeyStroke(int(k), int(m), str(t)) for k, m, t in entry[1]], slot=i)
        return slots


    @classmethod
    def kept_in(cls, settings: Any, say: Callable[[str], None]) -> MacroSlots:
        """The macros of the settings file (`settings`: a QSettings), written back after every change. A damaged
        entry is said; the IDE then starts without macros, and the next macro saved replaces the entry."""
        text = settings.value(MACROS_KEY, "", type=str)
        try:
            slots = cls.from_json(text) if text else cls()
        except (ValueError, TypeError, IndexError) as exc:
            say(f"Macros not restored: {MACROS_KEY} in the settings file is damaged ({exc})")
            slots = cls()
        slots.listeners.append(lambda: settings.setValue(MACROS_KEY, slots.to_json()))
        return slots


class SaveMacroDialog(QDialog):
    """ "Save Macro" [DG L2208-2216]: the new shortcut, what it is assigned to now, the 10 Save As slots."""

    def __init__(self, keys: list[KeyStroke], slots: MacroSlots, bindings: dict[str, str],
                 parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setWindowTitle("Save Macro")
        self.keys, self.macro_slots, self.bindings = keys, slots, bindings
        self.shortcut_edit = QKeySequenceEdit()
        self.shortcut_edit.setMaximumSequenceLength(2)
        self.assigned = QLabel()
        self.slot_list = QListWidget()
        self.hint = QLabel("Alt+letter shortcuts rarely clash with existing keys.")
        self.hint.setWordWrap(True)
        buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Ok | QDialogButtonBox.StandardButton.Cancel)
        buttons.accepted.connect(self.accept)
        buttons.rejected.connect(self.reject)
        self.ok_button = buttons.button(QDialogButtonBox.StandardButton.Ok)
        layout = QVBoxLayout(self)
        for w in (QLabel("Press new shortcut key:"), self.shortcut_edit, self.assigned, QLabel("Save As:"),
                  self.slot_list, self.hint, buttons):
            layout.addWidget(w)
        self.shortcut_edit.keySequenceChanged.connect(self._changed)
        self._fill_slots()
        self._changed()

    def _fill_slots(self) -> None:
        self.slot_list.clear()
        for i, name in enumerate(self.macro_slots.slots()):
            self.slot_list.addItem(f"{i + 1} : {name or '<unassigned>'}")
        free = next((i for i, n in enumerate(self.macro_slots.slots()) if n is None), 0)
        self.slot_list.setCurrentRow(free)

    def shortcut(self) -> str:
        return self.shortcut_edit.keySequence().toString(QKeySequence.SequenceFormat.PortableText)

    def _changed(self, *_args) -> None:
        name = self.shortcut()
        self.ok_button.setEnabled(bool(name))
        if not name:
            self.assigned.setText("Currently assigned to: <unassigned>")
            return
        slot = self.macro_slots.slot_of(name)
        what = self.bindings.get(name) or (f"macro {slot + 1}" if slot is not None else None)
        self.assigned.setText(f"Currently assigned to: {what or '<unassigned>'}")
        self.assigned.setStyleSheet("color: #b35c00" if what else "")  # the warning of DG L2218-2222
        if slot is not None:
            self.slot_list.setCurrentRow(slot)

    def accept(self) -> None:
        if self.shortcut():
            self.macro_slots.assign(self.shortcut(), self.keys, slot=max(0, self.slot_list.currentRow()))
        super().accept()


class MacroRecorder:
    """Recording and playing macros in one CodeEditor, ``editor.recorder``; keys arrive through the editor's
    keyPressEvent (``note`` and ``take_shortcut``), the slots are the editor's ``macros``."""

    def __init__(self, editor: CodeEditor) -> None:
        self.editor = editor
        self._recording: list[KeyStroke] | None = None
        self._last_macro: list[KeyStroke] = []
        self.playing = False
        self.pending_chord: str | None = None  # the first key of a two-key macro shortcut, waiting for the second
        self.macro_dialog: SaveMacroDialog | None = None

    @property
    def is_recording(self) -> bool:
        return self._recording is not None

    @property
    def last_macro(self) -> list[KeyStroke]:
        """The most recently recorded macro (played by ``play_macro()`` without a shortcut)."""
        return list(self._last_macro)

    def note(self, event: QKeyEvent, combo: str) -> None:
        """A key press of the editor: recorded while recording, unless it is replayed or stops the recording."""
        if self._recording is not None and not self.playing and combo != RECORD_SHORTCUT:
            self._recording.append(KeyStroke.from_event(event))

    def start_recording(self) -> None:
        """Ctrl-Shift-R: start recording key presses."""
        self._recording = []
        self.editor.macroRecordingChanged.emit(True)

    def stop_recording(self, *, shortcut: str | None = None) -> list[KeyStroke]:
        """End recording; the macro becomes the last macro and, with `shortcut`, is saved under it."""
        if self._recording is None:
            return []
        keys, self._recording = self._recording, None
        self._last_macro = keys
        if shortcut:
            self.editor.macros.assign(shortcut, keys)
        self.editor.macroRecordingChanged.emit(False)
        return keys

    def toggle_recording(self) -> None:
        """Ctrl-Shift-R: start recording, or stop it and open the Save Macro dialog."""
        if not self.is_recording:
            self.start_recording()
            return
        keys = self.stop_recording()
        if keys:
            editor = self.editor
            self.macro_dialog = SaveMacroDialog(keys, editor.macros, editor.key_bindings(), editor)
            self.macro_dialog.show()

    def play_macro(self, *, shortcut: str | None = None) -> bool:
        """Replay the macro saved under `shortcut` (default: the last recorded one); False if there is none."""
        keys = self._last_macro if shortcut is None else self.editor.macros.get(shortcut)
        if not keys or self.playing:
            return False
        self.playing = True
        self.editor.completer.popup().hide()
        try:
            for key in keys:
                key.send(self.editor)
        finally:
            self.playing = False
        return True

    def clear_macros(self) -> None:
        """Edit → Clear Macros (ide-spec 1.25)."""
        self.editor.macros.clear()
        self._last_macro = []

    def take_shortcut(self, combo: str) -> bool:
        """True if the key press `combo` played a macro or began a two-key macro shortcut (the editor then
        does nothing else with it)."""
        macros = self.editor.macros
        if not len(macros) or self.playing:
            return False
        chord = f"{self.pending_chord}, {combo}" if self.pending_chord else combo
        self.pending_chord = None
        if chord in macros.shortcuts():
            self.play_macro(shortcut=chord)
            return True
        if any(s.startswith(chord + ", ") for s in macros.shortcuts()):
            self.pending_chord = chord
            return True
        return False
