"""The APOSS window's toolbar (DG 2013, ide-spec 1.4): one click for the common commands — the file commands,
Execute / Break / Continue / Syntax Check / Clear Error, the debugger with Watch Start and Stop, the tools
(CAM-Editor, Array Editor, Oscilloscope) and Select Controller ("Connect"). The buttons fire the menu's own
actions; those with a standard icon show it, the others their text."""

from __future__ import annotations

from PySide6.QtWidgets import QStyle

SP = QStyle.StandardPixmap
GROUPS = (
    (("New", SP.SP_FileIcon), ("Open...", SP.SP_DialogOpenButton), ("Save", SP.SP_DialogSaveButton)),
    (("Execute", SP.SP_MediaPlay), ("Break", SP.SP_MediaStop), ("Continue", SP.SP_MediaSeekForward),
     ("Syntax Check", SP.SP_DialogApplyButton), ("Clear Error", SP.SP_MessageBoxWarning)),
    (("Prepare Singlestep", None), ("Go", None), ("Singlestep", None), ("End Debug", None), ("Watch Start", None),
     ("Watch Stop", None)),
    (("CAM-Editor", None), ("Array Editor", None), ("Oscilloscope", None)),
    (("Select Controller...", SP.SP_DriveNetIcon),),
)


def build_toolbar(w):
    bar = w.addToolBar("APOSS")
    bar.setObjectName("aposs-toolbar")
    for k, group in enumerate(GROUPS):
        if k:
            bar.addSeparator()
        for text, icon in group:
            action = w.actions_by_text[text]
            if icon is not None:
                action.setIcon(w.style().standardIcon(icon))
            bar.addAction(action)
    return bar
