"""The program editor's own keys (ide-spec 1.14-1.19) and which of them change the text.

Each key names a method of the CodeEditor or of one of its parts ("edit.cut_line"); the editor looks it up on
itself when the key is pressed.
"""

from __future__ import annotations

from motiontool.ui.editor.macros import RECORD_SHORTCUT

# the keys a read-only editor (while debugging) ignores: they would change the text
EDITING = frozenset({"cut", "paste", "edit.cut_line", "edit.cut_paragraph", "edit.delete_word_end", "undo", "redo",
                     "edit.lowercase_selection", "edit.uppercase_selection", "edit.insert_line_above",
                     "edit.toggle_overwrite", "search.show_replace_dialog", "edit.repeat_dialog",
                     "recorder.toggle_recording", "complete"})

# key → "method" or "part.method", or (that, arguments..., {options}); Tab, Shift-Tab, Return: in code_editor.
KEYMAP: dict[str, str | tuple] = {
    "F2": "bookmarks.next_bookmark", "Shift+F2": "bookmarks.previous_bookmark",
    "Ctrl+F2": "bookmarks.toggle_bookmark", "Ctrl+G": "edit.goto_line_dialog", "Ctrl+B": "edit.goto_matching_bracket",
    "Ctrl+Alt+Down": "edit.goto_next_blank_line", "Ctrl+Alt+Up": "edit.goto_previous_blank_line",
    "Ctrl+Right": "edit.move_word_end", "Ctrl+Shift+Right": ("edit.move_word_end", {"select": True}),
    "Ctrl+Alt+F8": "edit.select_line",
    "Ctrl+Ins": "copy", "Shift+Del": "cut", "Shift+Ins": "paste", "Ctrl+Y": "edit.cut_line",
    "Ctrl+Alt+K": "edit.cut_paragraph", "Ctrl+Del": "edit.delete_word_end",
    "Ctrl+F": "search.show_find_dialog", "Alt+F3": "search.show_find_dialog", "Ctrl+R": "search.show_replace_dialog",
    "F3": "search.find_next", "Shift+F3": "search.find_previous", "Ctrl+F3": "search.find_word",
    "Ctrl+Shift+F3": ("search.find_word", {"backward": True}),
    "Ins": "edit.toggle_overwrite", "Alt+Backspace": "undo", "Ctrl+Z": "undo", "Ctrl+Shift+Z": "redo",
    "Ctrl+U": "edit.lowercase_selection", "Ctrl+Shift+U": "edit.uppercase_selection",
    "Ctrl+Shift+N": "edit.insert_line_above", "Ctrl+Alt+R": "edit.repeat_dialog",
    RECORD_SHORTCUT: "recorder.toggle_recording",
    "Ctrl+Up": ("edit.scroll_lines", -1), "Ctrl+Down": ("edit.scroll_lines", 1),
    "Ctrl+PgUp": ("edit.scroll_columns", -1), "Ctrl+PgDown": ("edit.scroll_columns", 1),
    "Ctrl+Space": "complete",
}
