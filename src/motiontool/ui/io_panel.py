"""Tools ▸ I/O Panel (issue 23 item 4): the simulated controller's terminals, as a test box on a real drive's
terminals would give them. Every digital input is a toggle (stays) and a push button (on while held); the marker
inputs 5 and 6 are buttons of their own; the analog inputs 53/54 are sliders over INAD's range; the outputs are
lamps, polled five times a second while the panel is shown.

A program whose header asks for test inputs or settings (`// Test-inputs: 1=1@500`, `// Test-settings:
JERKMIN=200`, motiontool/program_header.py) gets an offer here: "Apply at Execute" writes the settings before the
download and has the controller set the inputs at their times after the start, as `motiontool run --input/--set`
does (decision I23).

The panel talks to the controller only through the window's Link, on a worker thread (ui/link_jobs.py): a slow line
never holds the window. Only a simulated MCO 305 can have its inputs set (the `set_input` request); on another
controller the inputs are disabled and say why.
"""

from __future__ import annotations

from PySide6.QtCore import Qt, QTimer
from PySide6.QtWidgets import (
    QDockWidget,
    QFrame,
    QGridLayout,
    QGroupBox,
    QHBoxLayout,
    QLabel,
    QPushButton,
    QSlider,
    QVBoxLayout,
    QWidget,
)

from motiontool.program_header import HeaderError, TestSettings, read_test_settings
from motiontool.ui.link_jobs import LinkJobs

MCO_INPUTS = tuple(range(1, 13))        # inputs 1-10 on X57, 11/12 on X59 (DG 10420-10530)
FC_INPUTS = (18, 19, 27, 29, 32, 33)    # the FC 300's digital inputs within "18 … 33" (CR 2724; decision I23)
MARKERS = {5: "Master marker", 6: "Slave marker"}  # "inputs 5 and 6 are also used as marker inputs" (CR 1575-1576)
ANALOG = (53, 54)
ANALOG_RANGE = (-1000, 1000)            # INAD 53/54: -1000 … 1000 = -10 V … 10 V (CR 1608)
OUTPUTS = (*range(1, 9), 21, 22, 27, 29)  # outputs 1-8 on X59, relays 21/22, FC 300 27/29 (CR 3097-3156, 3181-3210)
POLL_MS = 200                           # the lamps: five times a second is quick to the eye and light on a line
TOGGLE = ("QPushButton { min-width: 34px; padding: 2px 4px; }"
          "QPushButton:checked { background: #2e7d32; color: white; font-weight: bold; }")
LAMP_OFF = "background: #d6d6d6; color: #555; border: 1px solid #999; border-radius: 12px;"
LAMP_ON = "background: #ffc107; color: black; border: 1px solid #b28704; border-radius: 12px; font-weight: bold;"


class IoPanel(QWidget):
    def __init__(self, w) -> None:
        super().__init__(w)
        self.w = w
        self.jobs = LinkJobs(self)
        self.toggles: dict[int, QPushButton] = {}
        self.pushes: dict[int, QPushButton] = {}
        self.markers: dict[int, QPushButton] = {}
        self.sliders: dict[int, QSlider] = {}
        self.analog_labels: dict[int, QLabel] = {}
        self.lamps: dict[int, QLabel] = {}
        self.offered = None            # the editor whose header's test settings are offered
        self._polling = False          # a poll is on its way: the next tick does not ask again
        self._setting = 0              # input requests on their way: a poll answer then may predate them
        self._analog_sent: dict[int, int] = {}
        self.can_set: bool | None = None   # None until the controller has said what it is

        layout = QVBoxLayout(self)
        layout.addWidget(self._offer_box())
        self.note = QLabel()
        self.note.setWordWrap(True)
        self.note.setStyleSheet("color: #8a4b00;")
        self.note.hide()
        layout.addWidget(self.note)
        self.inputs_box = QGroupBox("Digital inputs (toggle · push)")
        grid = QGridLayout(self.inputs_box)
        grid.setHorizontalSpacing(4)
        grid.setVerticalSpacing(2)
        for block, (title, numbers) in enumerate((("MCO 305", MCO_INPUTS[:6]), ("", MCO_INPUTS[6:]),
                                                  ("FC 300", FC_INPUTS))):
            grid.addWidget(QLabel(f"<b>{title}</b>"), 0, block * 4, 1, 3)
            for row, number in enumerate(numbers, start=1):
                self._input_row(grid, row, block * 4, number)
            if block < 2:
                grid.setColumnMinimumWidth(block * 4 + 3, 12)
        layout.addWidget(self.inputs_box)
        self.markers_box = QGroupBox("Marker inputs")
        row = QGridLayout(self.markers_box)
        for number, title in MARKERS.items():
            button = QPushButton(f"{title} (input {number})")
            button.setToolTip(f"On while held: a rising edge on input {number} latches the "
                              f"{'master (MIPOS)' if number == 5 else 'slave (IPOS)'} marker position")
            button.pressed.connect(lambda *_, n=number: self._set(n, 1))
            button.released.connect(lambda *_, n=number: self._set(n, int(self.toggles[n].isChecked())))
            self.markers[number] = button
            row.addWidget(button, 0, number - 5)
        index = QLabel("Encoder index: from the simulated\nencoder, once per revolution")
        index.setStyleSheet("color: #555;")
        index.setToolTip("The index (zero) pulse comes with the axis's position, as on a real encoder; a button "
                         "would give a pulse where the encoder has none (decision I23)")
        row.addWidget(index, 1, 0, 1, 2)
        layout.addWidget(self.markers_box)
        layout.addWidget(self._analog_box())
        layout.addWidget(self._outputs_box())
        layout.addStretch()

        self.timer = QTimer(self)
        self.timer.setInterval(POLL_MS)
        self.timer.timeout.connect(self.poll)
        w.bridge.connection_changed.connect(self._connection_changed)
        if w.bridge.connected:
            self._connection_changed("connected")

    # --- building ------------------------------------------------------------------------------------------
    def _offer_box(self) -> QFrame:
        self.offer = QFrame()
        self.offer.setFrameShape(QFrame.Shape.StyledPanel)
        self.offer.setStyleSheet("QFrame { background: #fff8e1; }")
        row = QHBoxLayout(self.offer)
        self.offer_label = QLabel()
        self.offer_label.setWordWrap(True)
        self.apply_button = QPushButton("Apply at Execute")
        self.apply_button.setCheckable(True)
        self.apply_button.setToolTip("Execute writes the settings before the download and sets the inputs at their "
                                     "times after the start, as motiontool run --set/--input does")
        row.addWidget(self.offer_label, 1)
        row.addWidget(self.apply_button)
        self.offer.hide()
        return self.offer

    def _input_row(self, grid: QGridLayout, row: int, column: int, number: int) -> None:
        toggle = QPushButton(str(number))
        toggle.setCheckable(True)
        toggle.setStyleSheet(TOGGLE)
        toggle.setToolTip(f"Input {number}: click to switch it on or off")
        toggle.toggled.connect(lambda on, *_, n=number: self._set(n, int(on)))
        push = QPushButton("push")
        push.setMaximumWidth(52)   # three blocks side by side keep the dock narrow beside the editor
        push.setToolTip(f"Input {number} is on while this is held")
        push.pressed.connect(lambda *_, n=number: self._set(n, 1))
        push.released.connect(lambda *_, n=number: self._set(n, int(self.toggles[n].isChecked())))
        self.toggles[number], self.pushes[number] = toggle, push
        grid.addWidget(toggle, row, column)
        grid.addWidget(push, row, column + 1)

    def _analog_box(self) -> QGroupBox:
        box = QGroupBox("Analog inputs (INAD: -1000 … 1000 = -10 V … 10 V)")
        grid = QGridLayout(box)
        for row, number in enumerate(ANALOG):
            slider = QSlider(Qt.Orientation.Horizontal)
            slider.setRange(*ANALOG_RANGE)
            slider.setSingleStep(10)     # 0.1 V per arrow key, 1 V per Page Up/Down
            slider.setPageStep(100)
            slider.setTickInterval(250)
            slider.setTickPosition(QSlider.TickPosition.TicksBelow)
            slider.setToolTip(f"Analog input {number}: arrow keys ±10 (0.1 V), Page Up/Down ±100 (1 V)")
            label = QLabel()
            label.setMinimumWidth(110)
            slider.valueChanged.connect(lambda value, *_, n=number: self._analog_moved(n, value))
            self.sliders[number], self.analog_labels[number] = slider, label
            grid.addWidget(QLabel(f"<b>{number}</b>"), row, 0)
            grid.addWidget(QLabel("-10 V"), row, 1)
            grid.addWidget(slider, row, 2)
            grid.addWidget(QLabel("+10 V"), row, 3)
            grid.addWidget(label, row, 4)
            self._show_analog(number, 0)
        grid.setColumnStretch(2, 1)
        self.analog_box = box
        return box

    def _outputs_box(self) -> QGroupBox:
        box = QGroupBox("Digital outputs")
        row = QHBoxLayout(box)
        row.setSpacing(6)
        for number in OUTPUTS:
            lamp = QLabel(str(number))
            lamp.setAlignment(Qt.AlignmentFlag.AlignCenter)
            lamp.setFixedSize(26, 26)
            lamp.setStyleSheet(LAMP_OFF)
            lamp.setToolTip(f"Output {number}" + (" (relay)" if number in (21, 22) else ""))
            lamp.setProperty("on", False)
            self.lamps[number] = lamp
            row.addWidget(lamp)
        row.addStretch()
        self.outputs_box = box
        return box

    # --- the inputs ------------------------------------------------------------------------------------------
    def _link(self):
        """The window's controller; as every command, the panel connects to the default one first (DG 2054)."""
        return self.w.bridge.link if self.w.development.connect_default() else None

    def _set(self, number: int, value: int) -> None:
        link = self._link()
        if link is None:
            return
        self._setting += 1
        self.jobs.run(lambda: link.set_input(number, value),
                      lambda result, *, n=number: self._answered(n, result))

    def _answered(self, number: int, result) -> None:
        self._setting -= 1
        if isinstance(result, Exception):
            self.w.messages.ide(f"I/O panel: input {number}: {result}")

    def _analog_moved(self, number: int, value: int) -> None:
        self._show_analog(number, value)
        if number not in self._analog_sent:  # one request on its way per input; the last value follows it
            self._send_analog(number)

    def _send_analog(self, number: int) -> None:
        link = self._link()
        if link is None:
            return
        value = self.sliders[number].value()
        self._analog_sent[number] = value
        self.jobs.run(lambda: link.set_input(number, value),
                      lambda result, *, n=number: self._analog_answered(n, result))

    def _analog_answered(self, number: int, result) -> None:
        sent = self._analog_sent.pop(number, None)
        if isinstance(result, Exception):
            self.w.messages.ide(f"I/O panel: analog input {number}: {result}")
        elif sent != self.sliders[number].value():
            self._send_analog(number)

    def _show_analog(self, number: int, value: int) -> None:
        self.analog_labels[number].setText(f"{value:+d}  ({value / 100:+.2f} V)")

    # --- the lamps (and the inputs the program's schedule set) -----------------------------------------------
    def showEvent(self, event) -> None:  # noqa: N802 - Qt override
        super().showEvent(event)
        self.timer.start()
        self.poll()

    def hideEvent(self, event) -> None:  # noqa: N802 - Qt override
        self.timer.stop()  # nothing asks the line while nobody looks
        super().hideEvent(event)

    def poll(self) -> None:
        link = self.w.bridge.link
        if link is None or self._polling:
            return
        self._polling = True
        setting = self._setting
        self.jobs.run(lambda: link.read_signals(["INPUTS", "OUTPUTS"]),
                      lambda result, *, s=setting: self._polled(result, s))

    def _polled(self, result, setting_before: int) -> None:
        self._polling = False
        if isinstance(result, Exception):  # not asked again until the window connects anew
            self.timer.stop()
            self.outputs_box.setEnabled(False)
            self.outputs_box.setToolTip(f"The outputs cannot be read from this controller: {result}")
            return
        inputs, outputs = (int(v) for v in result)
        for number, lamp in self.lamps.items():
            on = bool(outputs >> (number - 1) & 1)
            if lamp.property("on") != on:
                lamp.setProperty("on", on)
                lamp.setStyleSheet(LAMP_ON if on else LAMP_OFF)
        if setting_before or self._setting or self._held():
            return  # a click is on its way: this answer may predate it
        for number, toggle in self.toggles.items():
            if number <= 32 and toggle.isChecked() != bool(inputs >> (number - 1) & 1):
                toggle.blockSignals(True)   # the controller's state (a scheduled Test-input), not a click
                toggle.setChecked(not toggle.isChecked())
                toggle.blockSignals(False)

    def _held(self) -> bool:
        return any(b.isDown() for b in (*self.pushes.values(), *self.markers.values()))

    # --- what the controller can do ----------------------------------------------------------------------------
    def _connection_changed(self, state: str) -> None:
        link = self.w.bridge.link
        if state != "connected" or link is None:
            return
        self.outputs_box.setEnabled(True)
        self.outputs_box.setToolTip("")
        # a slow line (FC at 9600 baud) is asked no more often than the status bar asks it
        self.timer.setInterval(max(POLL_MS, round(link.status_interval_s * 1000)))
        if self.isVisible():
            self.timer.start()
        self.jobs.run(lambda: link.identify(), self._identified)

    def _identified(self, ident) -> None:
        product = "" if isinstance(ident, Exception) else ident.product
        self.can_set = product.startswith("MCO 305") and "simulated" in product
        why = "" if self.can_set else (
            f"The inputs of {product or 'this controller'} cannot be set from here: the link's set_input request "
            "is for simulated MCO 305 controllers only (docs/link-protocol.md); use the drive's terminals.")
        for box in (self.inputs_box, self.markers_box, self.analog_box):
            box.setEnabled(bool(self.can_set))
            for widget in (box, *box.findChildren(QWidget)):  # a disabled button says why, not what it would do
                if not widget.property("tip_saved"):
                    widget.setProperty("tip_saved", True)
                    widget.setProperty("tip", widget.toolTip())
                widget.setToolTip(why or widget.property("tip"))
        self.note.setText(why)
        self.note.setVisible(bool(why))

    # --- a program's test settings -----------------------------------------------------------------------------
    def show_offer(self, editor, name: str, wanted: TestSettings) -> None:
        if self.offered is not editor:
            self.apply_button.setChecked(False)  # another program: the user chooses again
        self.offered = editor
        self.offer_label.setText(f"<b>{name}</b> asks for test {wanted.describe()}")
        self.offer.show()

    def armed(self, editor, name: str) -> TestSettings:
        """What Execute applies for `editor`: its header's test settings when the user chose Apply at Execute.
        A header that cannot be read raises HeaderError (Execute says it and does not start)."""
        if self.offered is not editor or not self.apply_button.isChecked():
            return TestSettings()
        return read_test_settings(editor.toPlainText(), name)


def io_panel(w, *, show: bool = True) -> IoPanel:
    """The window's I/O panel in a dock on the right, made when first asked for."""
    panel = getattr(w, "io_panel", None)
    if panel is None:
        panel = IoPanel(w)
        dock = QDockWidget("I/O", w)
        dock.setObjectName("io")
        dock.setWidget(panel)
        w.addDockWidget(Qt.DockWidgetArea.RightDockWidgetArea, dock)
        w.io_panel, panel.dock = panel, dock
    if show:
        panel.dock.show()
        panel.dock.raise_()
    return panel


def offer_test_settings(w, editor, name: str) -> None:
    """A program was opened or is executed: when its header asks for test inputs or settings, the panel shows
    and offers to apply them, and the Communication window says so (once per program)."""
    panel = getattr(w, "io_panel", None)
    if panel is not None and panel.offered is editor:
        return
    try:
        wanted = read_test_settings(editor.toPlainText(), name)
    except HeaderError as exc:
        w.messages.ide(str(exc))
        return
    if wanted:
        io_panel(w).show_offer(editor, name, wanted)
        w.messages.ide(f"{name} asks for test {wanted.describe()}: Apply at Execute in the I/O panel (Tools ▸ "
                       "I/O Panel) applies them; its buttons set inputs by hand")


def armed_test_settings(w, editor, name: str) -> TestSettings:
    panel = getattr(w, "io_panel", None)
    return panel.armed(editor, name) if panel is not None else TestSettings()
