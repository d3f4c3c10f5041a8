"""Controller → Parameters ▸ Global / Axis / Name (DG 2796-2882, ide-spec 2.24-2.26).

The fields come from the parameter database, grouped as the manual groups them. A typed value is checked at
once against the parameter's range and options: a bad one is refused with the reason (the field turns red and
the message line says why) and never sent; a good one is marked as changed (bold on yellow) until written. OK
writes the changed values to the controller; choosing another controller first writes the pending values to the
one being left, then reads the new one ("the changed values are written to the previous controller and the new
controller's values are read", DG 2816-2818). F1 on a field shows the parameter's help. "Drive (FC 300)..." opens
the drive's own parameters (ui/drive_parameters.py, I24).

Reads and writes run on the dialog's link-jobs thread (ui/link_jobs.py, issue 27 item 2): Axis is ~115 reads, 6.6 s
at 9600 baud, and the window stood still that long before the dialog appeared. Now the dialog appears at once, each
field says "reading …" (and takes no input) until its answer arrives, and OK writes only the changed values (I22).
Decision I30."""

from __future__ import annotations

from collections.abc import Callable
from functools import cache

from PySide6.QtCore import QTimer
from PySide6.QtGui import QKeySequence, QShortcut
from PySide6.QtWidgets import (
    QComboBox,
    QDialog,
    QDialogButtonBox,
    QFormLayout,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QListWidget,
    QScrollArea,
    QStackedWidget,
    QVBoxLayout,
    QWidget,
)

from motiontool.comms.protocol import LinkError
from motiontool.paramdb import Parameter, ParameterError, database
from motiontool.ui.controller_links import controller_link, interface_controllers
from motiontool.ui.drive_parameters import DriveParametersDialog
from motiontool.ui.link_jobs import LinkJobs

CHANGED = "font-weight: bold; background: #fff3b0;"
REFUSED = "background: #ffc8c8;"
_MARKER = {"SYNCFAULT", "SYNCREADY"}   # marker counts: with the marker parameters (SYNCM…)


def _marker(p: Parameter) -> bool:
    return bool(p.name) and (p.name.startswith("SYNCM") or p.name in _MARKER)


# the manual's groups (DG 2838-2864); 33-1* holds both the synchronization and the marker parameters (I13)
AXIS_GROUPS: tuple[tuple[str, Callable[[Parameter], bool]], ...] = (
    ("Basic Settings", lambda p: p.number.startswith("32-8")),
    ("Encoder Data", lambda p: p.number[:4] in ("32-0", "32-1", "32-3", "32-4", "32-5")),
    ("Predefined I/Os", lambda p: p.number[:4] in ("33-4", "33-5", "33-6", "33-7")),
    ("Homing", lambda p: p.number.startswith("33-0")),
    ("Synchronization", lambda p: p.number[:4] in ("33-1", "33-2", "33-3") and not _marker(p)),
    ("Sync Marker", lambda p: p.number[:4] in ("33-1", "33-2", "33-3") and _marker(p)),
    ("Position Regulation", lambda p: p.number[:4] in ("32-6", "32-7")),
)
# "the functions of the inputs and outputs and the standard parameters … 33-5* and 33-8*" (DG 2808), and the
# CAN and RS-485 settings the manual's dialog shows (CAN ID [100])
GLOBAL_GROUPS: tuple[tuple[str, Callable[[Parameter], bool]], ...] = (
    ("Inputs and outputs", lambda p: p.number[:4] in ("33-5", "33-6", "33-7")),
    ("Global", lambda p: p.number.startswith("33-8")),
    ("CAN bus and RS-485", lambda p: p.number.startswith("33-9")),
)


@cache   # sorting the database into groups took ~25 ms of the GUI thread at each opening
def grouped(groups) -> tuple[tuple[str, tuple[Parameter, ...]], ...]:
    return tuple((title, tuple(p for p in database() if not p.read_only and keep(p))) for title, keep in groups)


def _text(p: Parameter, value) -> str:
    if isinstance(value, float):
        return f"{value:.6f}".rstrip("0").rstrip(".") if value != int(value) else f"{value:.1f}"
    return str(value)


LABEL_WIDTH = 480   # px: most descriptions on one line, the longest on two


class ParameterField:
    """One parameter's input: a combo box for an enumeration, else a line edit; knows its state."""

    def __init__(self, parameter: Parameter, on_change: Callable[[ParameterField], None]) -> None:
        self.p = parameter
        self.current = None           # the controller's value
        self.pending = None           # a checked new value, not yet written
        self.refused: str | None = None
        self._on_change = on_change
        self._loading = False
        tip = (f"{parameter.label}: {parameter.description}\nRange {_text(parameter, parameter.minimum)} .. "
               f"{_text(parameter, parameter.maximum)} {parameter.unit}, default "
               f"{_text(parameter, parameter.default)}\nF1: help")
        if parameter.options:
            self.widget = QComboBox()
            for number, text in parameter.options.items():
                self.widget.addItem(f"{number}: {text}", number)
            self.widget.currentIndexChanged.connect(lambda _i: self._typed())
            self.widget.setMaximumWidth(280)  # an option's long text must not push the field out of view
            # the open list shows every option whole, however narrow the field
            self.widget.view().setMinimumWidth(self.widget.view().sizeHintForColumn(0) + 24)
        else:
            self.widget = QLineEdit()
            self.widget.setMaximumWidth(160)
            self.widget.editingFinished.connect(self._typed)
        self.widget.setToolTip(tip)
        self.widget.setProperty("parameter", parameter.number)

    def text(self) -> str:
        if isinstance(self.widget, QComboBox):
            return str(self.widget.currentData())
        return self.widget.text().strip()

    def wait(self, *, text: str = "reading …") -> None:
        """No value yet: the field is empty, says why and takes no input (a value typed now would be overwritten)."""
        self._loading = True
        self.current, self.pending, self.refused = None, None, None
        self.widget.setPlaceholderText(text)
        if isinstance(self.widget, QComboBox):
            self.widget.setCurrentIndex(-1)
        else:
            self.widget.clear()
        self.widget.setStyleSheet("")
        self.widget.setEnabled(False)
        self._loading = False

    def written(self, value) -> None:
        """`value` is now the controller's; a value typed meanwhile stays pending."""
        if self.pending == value:
            self.load(value)
        else:
            self.current = value

    def load(self, value) -> None:
        """Show the controller's value (forgets what was pending)."""
        self._loading = True
        self.current, self.pending, self.refused = value, None, None
        self.widget.setPlaceholderText("")
        self.widget.setEnabled(True)
        if isinstance(self.widget, QComboBox):
            index = self.widget.findData(value)
            if index < 0:  # a value outside the options: shown, not offered
                self.widget.addItem(f"{value}: (not an option)", value)
                index = self.widget.count() - 1
            self.widget.setCurrentIndex(index)
        else:
            self.widget.setText(_text(self.p, value))
        self.widget.setStyleSheet("")
        self._loading = False

    def _typed(self) -> None:
        if self._loading:
            return
        try:
            value = self.p.validate(self.text())
        except ParameterError as exc:
            self.pending, self.refused = None, str(exc)
            self.widget.setStyleSheet(REFUSED)
        else:
            self.refused = None
            self.pending = None if value == self.current else value
            self.widget.setStyleSheet(CHANGED if self.pending is not None else "")
        self._on_change(self)


class _Ticket:
    """One pass of reads; cancelled when its answers would be stale (another controller, a fault, closed)."""

    cancelled = False


class ParametersDialog(QDialog):
    """The fields of `groups` for one controller at a time; with several groups a list chooses the page."""

    def __init__(self, w, title: str, groups, *, paged: bool) -> None:
        super().__init__(w)
        self.w = w
        self.setWindowTitle(title)
        self.jobs = LinkJobs(self)
        self._ticket = _Ticket()
        self.waiting = 0                  # fields whose value has not arrived yet
        self.fields: dict[str, ParameterField] = {}
        self.controller = QComboBox()
        for cid in interface_controllers(w):
            self.controller.addItem(f"Controller {cid}", cid)
        self.controller.setCurrentIndex(max(0, self.controller.findData(w.bridge.controller_id)))
        self._shown_controller = self.controller.currentData()
        self.controller.currentIndexChanged.connect(lambda _i: self._controller_changed())
        self.message = QLabel("")
        self.message.setWordWrap(True)
        self.pages = QStackedWidget()
        self.groups = QListWidget()
        single = QWidget()
        single_form = QFormLayout(single)
        self._unbuilt: list[tuple[str | None, QFormLayout, tuple[Parameter, ...]]] = []
        for title_, parameters in grouped(groups):
            if paged:
                page = QWidget()
                form = QFormLayout(page)
                self.groups.addItem(title_)
                self.pages.addWidget(_scroll(page))
            else:  # one page with a heading per group (the manual's Global dialog)
                form = single_form
            self._unbuilt.append((None if paged else title_, form, parameters))
        if not paged:
            self.pages.addWidget(_scroll(single))
        self.groups.currentRowChanged.connect(self.pages.setCurrentIndex)
        buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Ok | QDialogButtonBox.StandardButton.Cancel)
        buttons.accepted.connect(self.accept)
        buttons.rejected.connect(self.reject)
        self.ok = buttons.button(QDialogButtonBox.StandardButton.Ok)
        # the drive's own parameters beside the option's, as MCT 10 shows them (I24)
        drive = buttons.addButton("Drive (FC 300)...", QDialogButtonBox.ButtonRole.ActionRole)
        drive.clicked.connect(lambda: show_drive(self.w, self))
        top = QHBoxLayout()
        top.addWidget(QLabel("Controller:"))
        top.addWidget(self.controller, 1)
        middle = QHBoxLayout()
        if paged:
            self.groups.setMaximumWidth(170)
            middle.addWidget(self.groups)
        middle.addWidget(self.pages, 1)
        layout = QVBoxLayout(self)
        layout.addLayout(top)
        layout.addLayout(middle, 1)
        layout.addWidget(self.message)
        layout.addWidget(buttons)
        QShortcut(QKeySequence("F1"), self, self._help)
        self.resize(1000, 600)  # the long names of the manual and the value fields side by side
        if paged:
            self.groups.setCurrentRow(0)
        # all 115 Axis fields at once stood the window still ~150 ms: one group now, one per event-loop pass after
        self._builder = QTimer(self, interval=0, timeout=self._build_group)
        self._link = None
        self._start_reading(self._still_to_build())
        self._build_group()
        if self._unbuilt:
            self._builder.start()

    def _build_group(self) -> None:
        """The next group's fields; their reads are asked at once."""
        heading, form, parameters = self._unbuilt.pop(0)
        if heading:
            label = QLabel(heading)
            label.setStyleSheet("font-weight: bold; margin-top: 6px;")
            form.addRow(label)
        new = {}
        for p in parameters:
            field = new[p.number] = ParameterField(p, self._field_changed)
            # the whole description, wrapped: cut at 60 characters it lost its end mid-word (issue 23 item 11)
            label = QLabel(f"{p.description} [{p.label}]" + (f" ({p.unit})" if p.unit else ""))
            label.setWordWrap(True)
            label.setMinimumWidth(LABEL_WIDTH)   # a wrapped label would otherwise take the narrowest column
            label.setToolTip(p.description)
            form.addRow(label, field.widget)
        self.fields.update(new)
        self._request(new)
        if not self._unbuilt:
            self._builder.stop()

    # --- reading and writing ---------------------------------------------------------------------------------
    def link(self):
        return controller_link(self.w, self._shown_controller)

    def read(self) -> None:
        """Every field's value, one request each on the link-jobs thread: the fields fill in as answers arrive."""
        self._start_reading(len(self.fields) + self._still_to_build())   # pages built later ask with this read
        self._request(self.fields)

    def _still_to_build(self) -> int:
        return sum(len(parameters) for *_, parameters in self._unbuilt)

    def _start_reading(self, count: int) -> None:
        self._ticket.cancelled = True
        self._ticket = _Ticket()
        self.waiting = count
        cid = self._shown_controller
        try:
            self._link = self.link()
        except (LinkError, ValueError) as exc:
            self._ticket.cancelled = True
            self.say(f"Controller {cid}: {exc}", error=True)
            return
        self._busy(f"Controller {cid}: reading {count} parameters …")

    def _request(self, fields: dict[str, ParameterField]) -> None:
        ticket, link, cid = self._ticket, self._link, self._shown_controller
        for number, field in fields.items():
            if ticket.cancelled:              # no link, or a fault already said
                field.wait(text="not read")
                continue
            field.wait()
            # a request still queued when its answer would be stale is not sent: the line is free at once
            self.jobs.run(lambda *, n=number: None if ticket.cancelled else link.read_parameter(n),
                          lambda result, *, f=field: self._answer(ticket, cid, f, result))

    def _answer(self, ticket: _Ticket, cid: int, field: ParameterField, result) -> None:
        if ticket.cancelled:
            return
        try:
            if isinstance(result, Exception):
                raise result
            field.load(field.p.from_raw(result))
        except (LinkError, ValueError) as exc:
            ticket.cancelled = True           # one answer missing: the rest would wait for the same fault
            for f in self.fields.values():
                if f.current is None:
                    f.wait(text="not read")
            self._busy(None)
            self.say(f"Controller {cid}: {exc}", error=True)
            return
        self.waiting -= 1
        if self.waiting:
            self.message.setText(f"Controller {cid}: reading {self.waiting} parameters …")
        else:
            self._busy(None)
            self._field_changed(field)

    def pending(self) -> dict[str, object]:
        return {n: f.pending for n, f in self.fields.items() if f.pending is not None}

    def refused(self) -> list[str]:
        return [f.refused for f in self.fields.values() if f.refused]

    def _write(self, then: Callable[[], None]) -> None:
        """The pending values to the shown controller on the link-jobs thread, then `then()` if all were written."""
        cid, values = self._shown_controller, self.pending()
        raws = {n: self.fields[n].p.to_raw(v) for n, v in values.items()}
        try:
            link = self.link()
        except (LinkError, ValueError) as exc:
            self.say(f"Controller {cid}: {exc}", error=True)
            self._select(cid)
            return

        def work() -> tuple[list[str], Exception | None]:
            written: list[str] = []
            try:
                for number, raw in raws.items():
                    link.write_parameter(number, raw)
                    written.append(number)
            except (LinkError, ValueError) as exc:
                return written, exc           # those before the fault are written and said so
            return written, None

        labels = [self.fields[n].p.label for n in values]
        self._busy(f"Controller {cid}: writing {', '.join(labels)} …")
        self.jobs.run(work, lambda result: self._written(cid, values, result, then))

    def _written(self, cid: int, values: dict[str, object], result, then: Callable[[], None]) -> None:
        self._busy(None)
        written, error = ([], result) if isinstance(result, Exception) else result
        for number in written:
            self.fields[number].written(values[number])
        if written:
            self.w.messages.ide(f"Controller {cid}: wrote {', '.join(self.fields[n].p.label for n in written)}")
        if error is not None:
            self.say(f"Controller {cid}: {error}", error=True)
            self._select(self._shown_controller)
            return
        self.say("")
        then()

    def accept(self) -> None:
        if self.refused():
            self.say("Not written: " + "; ".join(self.refused()), error=True)
        elif self.pending():
            self._write(lambda: super(ParametersDialog, self).accept())
        else:
            super().accept()

    def done(self, result: int) -> None:
        self._ticket.cancelled = True         # closed: the reads still queued are not sent
        super().done(result)

    def _controller_changed(self) -> None:
        """Another controller: the pending values go to the one left, then the new one's are read."""
        new = self.controller.currentData()
        if self.refused():
            self._select(self._shown_controller)
            self.say("Not written: " + "; ".join(self.refused()), error=True)
            return

        def switch() -> None:
            self._shown_controller = new
            self.read()

        if self.pending():
            self._write(switch)
        else:
            switch()

    def _select(self, cid: int) -> None:
        self.controller.blockSignals(True)
        self.controller.setCurrentIndex(self.controller.findData(cid))
        self.controller.blockSignals(False)

    def _busy(self, text: str | None) -> None:
        for widget in (self.ok, self.controller):
            widget.setEnabled(text is None)
        if text is not None:
            self.say(text)

    # --- feedback ----------------------------------------------------------------------------------------------
    def say(self, text: str, *, error: bool = False) -> None:
        self.message.setText(text)
        self.message.setStyleSheet("color: #a00000;" if error else "")

    def _field_changed(self, field: ParameterField) -> None:
        if field.refused:
            self.say(f"Refused: {field.refused}", error=True)
        else:
            changed = len(self.pending())
            self.say(f"{changed} changed value(s): OK writes them" if changed else "")

    def _help(self) -> None:
        number = self.focusWidget().property("parameter") if self.focusWidget() is not None else None
        from motiontool.ui.help import show_help

        show_help(self.w, parameter=number)


def _scroll(widget: QWidget) -> QScrollArea:
    area = QScrollArea()
    area.setWidgetResizable(True)
    area.setWidget(widget)
    return area


class NameDialog(QDialog):
    """Parameters → Name (DG 2870-2882): at most 8 characters, upper case. Read and written on the link-jobs
    thread like Global and Axis (I30)."""

    def __init__(self, w) -> None:
        super().__init__(w)
        self.w = w
        self.setWindowTitle("Controller name")
        self.jobs = LinkJobs(self)
        self.controller = QComboBox()
        for cid in interface_controllers(w):
            self.controller.addItem(f"Controller {cid}", cid)
        self.controller.setCurrentIndex(max(0, self.controller.findData(w.bridge.controller_id)))
        self._shown = self.controller.currentData()
        self.controller.currentIndexChanged.connect(lambda _i: self._controller_changed())
        self.name = QLineEdit()
        self.name.setMaxLength(32)  # longer input is refused with the reason rather than cut silently
        self.name.textEdited.connect(self._typed)
        self.message = QLabel("")
        form = QFormLayout(self)
        form.addRow("Controller:", self.controller)
        form.addRow("Name (8 characters, upper case):", self.name)
        form.addRow(self.message)
        buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Ok | QDialogButtonBox.StandardButton.Cancel)
        buttons.accepted.connect(self.accept)
        buttons.rejected.connect(self.reject)
        self.ok = buttons.button(QDialogButtonBox.StandardButton.Ok)
        form.addRow(buttons)
        self._loaded = ""
        self.read()

    def _busy(self, text: str | None) -> None:
        for widget in (self.ok, self.controller, self.name):
            widget.setEnabled(text is None)
        self.name.setPlaceholderText(text or "")

    def read(self) -> None:
        cid = self._shown
        try:
            link = controller_link(self.w, cid)
        except (LinkError, ValueError) as exc:
            self._read(exc)
            return
        self.name.clear()
        self._busy("reading …")
        self.jobs.run(lambda: link.identify().name, self._read)

    def _read(self, result) -> None:
        self._busy(None)
        if isinstance(result, Exception):
            self.message.setText(str(result))
            result = ""
        self._loaded = result
        self.name.setText(self._loaded)

    def _typed(self, text: str) -> None:
        """As it is typed: upper case (DG 2872 "must be uppercase"), and a name too long says so at once with OK
        off, rather than at OK (issue 23 item 11)."""
        if text != text.upper():
            position = self.name.cursorPosition()
            self.name.setText(text.upper())
            self.name.setCursorPosition(position)
        refused = self.problem(self.name.text().strip())
        self.message.setText(f"Refused: {refused}" if refused else "")
        self.message.setStyleSheet("color: #a00000;" if refused else "")
        self.name.setStyleSheet(REFUSED if refused else "")
        self.ok.setEnabled(refused is None)

    @staticmethod
    def problem(name: str) -> str | None:
        reasons = []
        if len(name) > 8:
            reasons.append(f"{len(name)} characters, at most 8")
        if name != name.upper():
            reasons.append("not upper case")
        return f"{name!r}: " + " and ".join(reasons) if reasons else None

    def _write(self, then: Callable[[], None]) -> None:
        """A changed name to the shown controller on the link-jobs thread, then `then()`; a refusal says why."""
        name = self.name.text().strip()
        if name == self._loaded:
            then()
            return
        refused = self.problem(name)
        if refused is None:
            try:
                link = controller_link(self.w, self._shown)
            except (LinkError, ValueError) as exc:
                refused = str(exc)
        if refused:
            self._refused(refused)
            return
        cid = self._shown
        self._busy("writing …")
        self.jobs.run(lambda: link.set_name(name), lambda result: self._written(cid, name, result, then))

    def _written(self, cid: int, name: str, result, then: Callable[[], None]) -> None:
        self._busy(None)
        if isinstance(result, Exception):
            self._refused(str(result))
            return
        self.w.messages.ide(f"Controller {cid}: named {name}")
        self._loaded = name
        then()

    def _refused(self, why: str) -> None:
        self.message.setText(f"Refused: {why}")
        self.message.setStyleSheet("color: #a00000;")
        self.name.setStyleSheet(REFUSED)
        self.controller.blockSignals(True)   # a change of controller waits for a name the controller takes
        self.controller.setCurrentIndex(self.controller.findData(self._shown))
        self.controller.blockSignals(False)

    def accept(self) -> None:
        self._write(lambda: super(NameDialog, self).accept())

    def _controller_changed(self) -> None:
        new = self.controller.currentData()

        def switch() -> None:
            self._shown = new
            self.read()

        self._write(switch)


def show_global(w) -> None:
    if w.development.connect_default():
        dialog = ParametersDialog(w, "Global Parameters", GLOBAL_GROUPS, paged=False)
        dialog.exec()
        dialog.deleteLater()   # its link-jobs thread ends with it


def show_axis(w) -> None:
    if w.development.connect_default():
        dialog = ParametersDialog(w, "Axis Parameters", AXIS_GROUPS, paged=True)
        dialog.exec()
        dialog.deleteLater()


def show_name(w) -> None:
    if w.development.connect_default():
        dialog = NameDialog(w)
        dialog.exec()
        dialog.deleteLater()


def show_drive(w, parent=None) -> None:
    """Parameters ▸ Drive (FC 300): from the Global and Axis dialogs' "Drive (FC 300)..." button."""
    if w.development.connect_default():
        dialog = DriveParametersDialog(w, parent)
        dialog.exec()
        dialog.deleteLater()   # its link-jobs thread ends with it
