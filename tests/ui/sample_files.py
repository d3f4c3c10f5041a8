"""One file of every kind the IDE opens, written by the project's own writers, for tests that answer Open and
Save dialogs (tests/modal.py)."""

from __future__ import annotations

from pathlib import Path

from PySide6.QtWidgets import QFileDialog, QLineEdit

EXAMPLE_ZBA = ("Date,2009:07:27 10:52\n"  # from the manual's example (DG L4574-4590)
               'User,,130,Height,50,100,10,1000,"Maximum height of any unit",1\n'
               'Group, 0, 0, "Quantity by Country", , , , 0\n'
               'Array,0,1,Switzerland,5,10,0,5000,"This is the first value in array 0",1\n')
TESTRUN = "Testrun\nInterval: 1\nAPOS\n1\n2\n3\n"


class Files:
    """Real files for Open dialogs and fresh paths for Save dialogs, by the dialog's name filters."""

    def __init__(self, folder: Path) -> None:
        from motiontool.cameditor import editing
        from motiontool.formats.dat import write_dat
        from motiontool.formats.zbc import ConfigFile, write_config
        from motiontool.resources import resources_path
        from motiontool.scope import zbo
        from motiontool.scope.acquisition import default_group, new_curve
        from motiontool.scope.curves import Scope

        self.folder = folder
        self.count = 0
        curve = editing.add_points(editing.new_curve("walk", 1000, 10, True), [(300, 200), (700, 900)])
        config = ConfigFile()
        config.add_curve(curve)
        write_config(folder / "walk.zbc", config)
        write_dat(folder / "walk.dat", curve)
        scope = Scope("free_run")
        default_group(scope, "free_run")
        recorded = new_curve(scope, "APOS", "Test Group (Free Run)", "free_run")
        recorded.buffer.extend([0.0, 1.0, 2.0], [0.0, 5.0, 9.0])
        zbo.save(scope, folder / "walk.zbo", True)
        (folder / "walk.zba").write_text(EXAMPLE_ZBA, encoding="utf-8")
        (folder / "walk.m").write_text(resources_path("samples", "01_positioning.m").read_text(encoding="utf-8"),
                                       encoding="utf-8")
        (folder / "walk.csv").write_text("t,APOS,CPOS\n0,0,0\n1,5,6\n2,9,10\n", encoding="utf-8")
        (folder / "walk.txt").write_text(TESTRUN, encoding="utf-8")
        (folder / "notes.txt").write_text("just some notes\n", encoding="utf-8")

    def extensions(self, dialog: QFileDialog) -> list[str]:
        patterns = " ".join(dialog.nameFilters()).replace("(", " ").replace(")", " ").split()
        return [p[2:] for p in patterns if p.startswith("*.")]

    def answer(self, dialog: QFileDialog) -> None:
        if dialog.fileMode() == QFileDialog.FileMode.Directory:
            dialog.setDirectory(str(self.folder))
            dialog.selectFile(str(self.folder))
            dialog.accept()
            return
        extensions = self.extensions(dialog) or ["txt"]
        if dialog.acceptMode() == QFileDialog.AcceptMode.AcceptOpen:
            existing = [self.folder / f"walk.{ext}" for ext in extensions if (self.folder / f"walk.{ext}").exists()]
            if not existing:
                dialog.reject()
                return
            path = existing[0]
        else:
            self.count += 1
            path = self.folder / f"saved{self.count}.{extensions[0]}"
        # the file name field too: QFileDialog.selectFile leaves a field that has the keyboard focus alone, and
        # accept() with an empty field only opens the folder; whether the field had the focus when the reply came
        # depended on window activation timing, so the dialog stayed open now and then
        dialog.findChild(QLineEdit).setText(str(path))
        dialog.selectFile(str(path))
        dialog.accept()
