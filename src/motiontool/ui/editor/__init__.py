"""The APOSS program editor (ide-spec group 1): CodeEditor, its syntax highlighter and Find/Replace dialog.

Qt-free modules (importing them does not load Qt): ``search`` (Find/Replace patterns, Find in Files),
``outline`` (labels, subprograms, functions, symbols), ``bookmarks`` (BookmarkStore), ``lang`` (keywords, hover
help, completion items), ``textops`` (text operations behind the keys) and ``settings`` (EditorColors,
EditorSettings). The Qt classes below are imported on first use.
"""

from __future__ import annotations

import importlib

_EXPORTS = {
    "AposHighlighter": "highlighter", "BookmarkStore": "bookmarks", "CodeEditor": "code_editor",
    "EditorColors": "settings", "EditorSettings": "settings", "EditorSettingsDialog": "settings_dialog",
    "FindInFilesDialog": "find_dialog", "FindReplaceDialog": "find_dialog", "OutlineItem": "outline",
}
__all__ = sorted(_EXPORTS)


def __getattr__(name: str) -> object:
    if name in _EXPORTS:
        return getattr(importlib.import_module(f"{__name__}.{_EXPORTS[name]}"), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
