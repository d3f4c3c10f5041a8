"""Asking for the name to save under: a file dialog that adds the selected filter's extension to a name typed
without one (issue 23 item 9: a program saved as `ctl2_test` was then hidden by File ▸ Open's filter). The dialog
adds it itself (defaultSuffix), so its overwrite question is asked about the file that will be written. Used by
the oscilloscope and the program editor; it lives here because the scope's UI may not import the IDE's."""

from __future__ import annotations

import re
from pathlib import Path

from PySide6.QtWidgets import QFileDialog, QWidget

from motiontool.fileio import filter_extension


def ask_save_name(parent: QWidget | None, title: str, suggested: str | Path, filters: str) -> tuple[str, str]:
    """(path, selected filter) like QFileDialog.getSaveFileName; ("", "") when cancelled. A suggested name whose
    extension one filter names selects that filter."""
    dialog = QFileDialog(parent, title, "", filters)
    dialog.setAcceptMode(QFileDialog.AcceptMode.AcceptSave)
    dialog.setFileMode(QFileDialog.FileMode.AnyFile)
    suggested = Path(suggested) if str(suggested) else None
    if suggested is not None:
        if str(suggested.parent) not in ("", "."):
            dialog.setDirectory(str(suggested.parent))
        for name_filter in dialog.nameFilters():
            if suggested.suffix.lower() in re.findall(r"\*(\.\w+)", name_filter.lower()):
                dialog.selectNameFilter(name_filter)
                break
        dialog.selectFile(suggested.name)
    dialog.filterSelected.connect(lambda name_filter: dialog.setDefaultSuffix(filter_extension(name_filter)))
    dialog.setDefaultSuffix(filter_extension(dialog.selectedNameFilter()))
    if not dialog.exec() or not dialog.selectedFiles():
        return "", ""
    return dialog.selectedFiles()[0], dialog.selectedNameFilter()
