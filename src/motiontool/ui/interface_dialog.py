"""Settings → Interface / Development → Select Controller: the link kinds that exist (ide-spec 2.12)."""

from __future__ import annotations

from PySide6.QtWidgets import QDialog, QDialogButtonBox, QLabel, QListWidget, QListWidgetItem, QVBoxLayout

from motiontool.ui.controllers import SIMULATED_IDS

LINK_KINDS = [(f"embedded:{n}", f"Simulated MCO 305 — controller {n} (embedded)", True) for n in SIMULATED_IDS] + [
    ("fc-serial", "RS-485 FC protocol (serial)", False),
    ("canopen", "CANopen", False),
]


class InterfaceDialog(QDialog):
    def __init__(self, parent=None):
        super().__init__(parent)
        self.setWindowTitle("Select Controller")
        self.list = QListWidget()
        for key, text, available in LINK_KINDS:
            item = QListWidgetItem(text if available else f"{text} — not available yet")
            item.setData(256, key)
            if not available:
                item.setFlags(item.flags() & ~item.flags().ItemIsEnabled)
            self.list.addItem(item)
        self.list.setCurrentRow(0)
        buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Ok | QDialogButtonBox.StandardButton.Cancel)
        buttons.accepted.connect(self.accept)
        buttons.rejected.connect(self.reject)
        layout = QVBoxLayout(self)
        layout.addWidget(QLabel("Interface and controller:"))
        layout.addWidget(self.list)
        layout.addWidget(buttons)

    def selected_kind(self) -> str:
        return self.list.currentItem().data(256)

    def selected_controller(self) -> int:
        return int(self.selected_kind().split(":")[1])
