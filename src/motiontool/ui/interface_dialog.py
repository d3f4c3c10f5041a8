"""Settings → Interface (DG 3087-3111) and Development → Select Controller (DG 2536-2546).

Settings → Interface: the interface type, its port or URL, baud rate and controller ID scan range; one type is the
default (Esc and commands without a controller connect through it). Changes affect only new connections.
Select Controller: a tree of the open interfaces and their controllers; an Interface drop-down with Open Interface
opens another one (without changing the default), the simulated APC among them.
"""

from __future__ import annotations

from dataclasses import replace

from PySide6.QtCore import QSettings, Qt
from PySide6.QtWidgets import (
    QCheckBox,
    QComboBox,
    QDialog,
    QDialogButtonBox,
    QFormLayout,
    QHBoxLayout,
    QLabel,
    QPushButton,
    QSpinBox,
    QTreeWidget,
    QTreeWidgetItem,
    QVBoxLayout,
)

from motiontool.comms.protocol import LinkError
from motiontool.session.controllers import APC_SIM, BAUDS, SIMULATED_IDS, ControllerRegistry, InterfaceConfig
from motiontool.ui.link_jobs import waiting

KINDS = {"sim": "Simulator (embedded MCO 305)", "fc": "FC protocol (RS-485 / USB)",
         "canopen": "CANopen (slcan, SocketCAN, PCAN, Kvaser, IXXAT … adapter)"}
DEFAULTS = {"sim": InterfaceConfig("sim", "", 9600, 1, len(SIMULATED_IDS)),
            "canopen": InterfaceConfig("canopen", "slcan:socket://127.0.0.1:4002", 9600, 1, 8),
            "fc": InterfaceConfig("fc", "/dev/ttyUSB0", 9600, 1, 8)}
ROLE = Qt.ItemDataRole.UserRole
# Select Controller also opens the simulated APC, the controller DPL programs run on (A68); it has no settings
# (one controller, no port), so it is not a type of Settings → Interface
APC_KIND = (APC_SIM, "APC simulator (Unidrive SP + SM-Applications, DPL)", InterfaceConfig(APC_SIM, "", 9600, 1, 1))


# --- settings --------------------------------------------------------------------------------------------------
def load_interfaces(settings: QSettings) -> tuple[dict[str, InterfaceConfig], str]:
    """({kind: configuration}, the default kind) from the settings file (defaults where missing or damaged)."""
    configs = {}
    for kind, default in DEFAULTS.items():
        try:
            configs[kind] = InterfaceConfig(
                kind, str(settings.value(f"interface/{kind}/port", default.port)),
                int(settings.value(f"interface/{kind}/baud", default.baud)),
                int(settings.value(f"interface/{kind}/first", default.first)),
                int(settings.value(f"interface/{kind}/last", default.last)),
                int(settings.value(f"interface/{kind}/sdo", default.sdo)) if kind == "canopen" else 1)
        except (TypeError, ValueError):
            configs[kind] = default
        if configs[kind].sdo not in (1, 2):     # a damaged settings file: the channel the node always has
            configs[kind] = replace(configs[kind], sdo=1)
    kind = str(settings.value("interface/default", "sim"))
    return configs, kind if kind in configs else "sim"


def save_interface(settings: QSettings, config: InterfaceConfig, *, default: bool) -> None:
    for name in ("port", "baud", "first", "last", "sdo"):
        settings.setValue(f"interface/{config.kind}/{name}", getattr(config, name))
    if default:
        settings.setValue("interface/default", config.kind)


def serial_ports() -> list[str]:
    """The serial ports of this computer (USB adapters, COM ports), for the port drop-down."""
    try:
        from serial.tools import list_ports
    except ImportError:
        return []
    return sorted(p.device for p in list_ports.comports())


class InterfaceSettingsDialog(QDialog):
    """Settings → Interface."""

    def __init__(self, parent, settings: QSettings):
        super().__init__(parent)
        self.setWindowTitle("Interface")
        self.settings = settings
        self.configs, self.default_kind = load_interfaces(settings)
        self.kind = QComboBox()
        for kind, text in KINDS.items():
            self.kind.addItem(text, kind)
        self.port = QComboBox()
        self.port.setEditable(True)
        self.port.addItems(serial_ports())
        self.port.setToolTip("FC: a serial port (/dev/ttyUSB0, COM3) or any pyserial URL (socket://HOST:PORT); "
                             "CANopen: INTERFACE:CHANNEL of python-can (slcan:socket://HOST:PORT, socketcan:can0, "
                             "pcan:PCAN_USBBUS1)")
        self.baud = QComboBox()
        for baud in BAUDS:
            self.baud.addItem(str(baud), baud)
        self.sdo = QComboBox()
        self.sdo.addItem("1 (0x600 / 0x580 + node)", 1)
        self.sdo.addItem("2 (0x100 / 0x680 + node: beside another master)", 2)
        self.sdo.setToolTip("CANopen: the node's SDO server the IDE talks to; choose 2 when another master (a PLC, "
                            "the command line) uses 1 (DG 7317-7349)")
        self.first, self.last = QSpinBox(), QSpinBox()
        for box in (self.first, self.last):
            box.setRange(1, 126)
        self.default = QCheckBox("Default interface (used by Esc and by commands without a controller)")
        form = QFormLayout()
        form.addRow("Interface type:", self.kind)
        form.addRow("Port or URL:", self.port)
        form.addRow("Baud rate:", self.baud)
        form.addRow("SDO channel:", self.sdo)
        scan = QHBoxLayout()
        scan.addWidget(self.first)
        scan.addWidget(QLabel("to"))
        scan.addWidget(self.last)
        form.addRow("Controller ID scan range:", scan)
        form.addRow(self.default)
        note = QLabel("Changes affect only new connections; connected controllers stay connected.")
        note.setWordWrap(True)
        self.buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Ok | QDialogButtonBox.StandardButton.Cancel)
        self.buttons.accepted.connect(self.accept)
        self.buttons.rejected.connect(self.reject)
        layout = QVBoxLayout(self)
        layout.addLayout(form)
        layout.addWidget(note)
        layout.addWidget(self.buttons)
        self._shown = None
        self.kind.currentIndexChanged.connect(self._kind_changed)
        self.kind.setCurrentIndex(self.kind.findData(self.default_kind))
        self._kind_changed(self.kind.currentIndex())

    def _kind_changed(self, _index: int) -> None:
        if self._shown is not None:                # keep what was typed for the type we leave
            self.configs[self._shown] = self._read(self._shown)
        kind = self.kind.currentData()
        config = self.configs[kind]
        self.port.setEditText(config.port)
        self.baud.setCurrentIndex(max(0, self.baud.findData(config.baud)))
        self.first.setValue(config.first)
        self.last.setValue(config.last)
        self.default.setChecked(kind == self.default_kind)
        wire = kind != "sim"
        self.port.setEnabled(wire)
        self.baud.setEnabled(kind == "fc")      # a CAN adapter's bit rate is the bus's, not ours
        self.sdo.setCurrentIndex(max(0, self.sdo.findData(config.sdo)))
        self.sdo.setEnabled(kind == "canopen")
        self._shown = kind

    def _read(self, kind: str) -> InterfaceConfig:
        first, last = sorted((self.first.value(), self.last.value()))
        return replace(self.configs[kind], port=self.port.currentText().strip(), baud=int(self.baud.currentData()),
                       first=first, last=last, sdo=int(self.sdo.currentData()) if kind == "canopen" else 1)

    def config(self) -> InterfaceConfig:
        return self._read(self.kind.currentData())

    def accept(self) -> None:
        config = self.config()
        if config.kind != "sim" and not config.port:
            self.port.setFocus()
            return
        save_interface(self.settings, config, default=self.default.isChecked())
        super().accept()


# --- Select Controller -------------------------------------------------------------------------------------------
class SelectControllerDialog(QDialog):
    """Development → Select Controller: interface → controllers; Open Interface adds another interface."""

    def __init__(self, parent, registry: ControllerRegistry, settings: QSettings):
        super().__init__(parent)
        self.setWindowTitle("Select Controller")
        self.registry = registry
        self.configs, default_kind = load_interfaces(settings)
        self.tree = QTreeWidget()
        self.tree.setHeaderLabels(["Interface / controller", "Name"])
        self.interface = QComboBox()
        self.configs[APC_SIM] = APC_KIND[2]
        for kind, text in (*KINDS.items(), APC_KIND[:2]):
            self.interface.addItem(f"{text}: {self.configs[kind].description}", kind)
        self.interface.setCurrentIndex(max(0, self.interface.findData(default_kind)))  # Open Interface: the default
        self.open_button = QPushButton("Open Interface")
        self.open_button.clicked.connect(self.open_selected_interface)
        self.message = QLabel("")
        self.message.setWordWrap(True)
        row = QHBoxLayout()
        row.addWidget(QLabel("Interface:"))
        row.addWidget(self.interface, 1)
        row.addWidget(self.open_button)
        self.buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Ok | QDialogButtonBox.StandardButton.Cancel)
        self.buttons.accepted.connect(self.accept)
        self.buttons.rejected.connect(self.reject)
        self.tree.itemDoubleClicked.connect(lambda item, _column: self.accept() if item.data(0, ROLE) else None)
        layout = QVBoxLayout(self)
        layout.addWidget(self.tree)
        layout.addLayout(row)
        layout.addWidget(self.message)
        layout.addWidget(self.buttons)
        self.resize(520, 360)
        if not registry.interfaces:   # a bus is scanned: the window paints and says so meanwhile
            waiting(parent, f"Scanning {registry.default.description} …", registry.open_interface)
        self.fill()

    def fill(self) -> None:
        self.tree.clear()
        first = None
        for key, iface in self.registry.interfaces.items():
            top = QTreeWidgetItem([iface.config.description])
            self.tree.addTopLevelItem(top)
            for cid in iface.found:
                item = QTreeWidgetItem([f"Controller {cid}", self.controller_name(iface, cid)])
                item.setData(0, ROLE, (key, cid))
                top.addChild(item)
                first = first or item
            if not iface.found:
                top.addChild(QTreeWidgetItem([f"no controller answered in {iface.config.first}..{iface.config.last}"]))
            top.setExpanded(True)
        self.tree.resizeColumnToContents(0)
        if first is not None:
            self.tree.setCurrentItem(first)

    def controller_name(self, iface, cid: int) -> str:
        """The name given with Parameters ▸ Name (DG 2872: "displayed in various dialogs … to more easily
        differentiate between multiple controllers"), from a controller already connected; one not connected
        is not opened just for its name (a bus would be asked once per controller)."""
        link = iface.links.get(cid)
        if link is None or not getattr(link, "alive", True):
            return ""
        try:
            return waiting(self.parent(), f"Controller {cid}: asking its name …", lambda: link.identify().name)
        except (LinkError, ValueError):
            return ""

    def open_selected_interface(self) -> None:
        """Open Interface (DG 2540): scan the chosen interface; the default interface stays as it is."""
        config = self.configs[self.interface.currentData()]
        try:
            self.message.setText(f"{config.description}: scanning {config.first}..{config.last} …")
            iface = waiting(self.parent(), f"Scanning {config.description} …",
                            lambda: self.registry.open_interface(config=config))
        except Exception as exc:  # noqa: BLE001 - a port that cannot be opened is reported in the dialog
            self.message.setText(f"{config.description}: {exc}")
            return
        self.message.setText(f"{config.description}: {len(iface.found)} controller(s) in "
                             f"{config.first}..{config.last}")
        self.fill()

    def selected(self) -> tuple[str, int] | None:
        item = self.tree.currentItem()
        return item.data(0, ROLE) if item is not None else None

    def accept(self) -> None:
        if self.selected() is None:
            self.message.setText("Choose a controller")
            return
        super().accept()
