"""Parameters ▸ Drive (FC 300): the drive's own parameters by menu group, beside the option's Global and Axis
parameters as MCT 10 shows them (issue 25 item 2, decision I24; the table and its sources: docs/fc300.md).

One row per parameter: number, name, value in the LCP's unit (the link's integer scaled by the conversion index),
unit, conversion index, range. 16-** are readouts (DG 7594: "Parameter groups 16-** … are read only"), shown
greyed and read again with Refresh. Values are read and written on the window's link-jobs thread (ui/link_jobs.py),
never on the GUI thread; OK writes only the values the user changed (I22). A typed value is checked at once
against its range (an end may be another parameter: 4-13 from 4-11) and refused with the reason, never sent."""

from __future__ import annotations

from decimal import Decimal, InvalidOperation

from PySide6.QtWidgets import QComboBox, QHBoxLayout, QLabel

from motiontool.formats.zbc_drive import write_settings
from motiontool.kernel.fc300_table import CELSIUS, FC_PARAMETERS, RPM, FCParam
from motiontool.ui.controller_links import controller_link, interface_controllers
from motiontool.ui.parameter_pages import ParameterPages

# the FC 300 menus a motion program reads (issue 25 item 2); the LCP's group names
GROUPS = (("1-** Load and Motor", 1), ("3-** Reference / Ramps", 3), ("4-** Limits / Warnings", 4),
          ("5-** Digital In/Out", 5), ("16-** Data Readouts", 16))
COLUMNS = ("Par.", "Name", "Value", "Unit", "Conv. index", "Range")
# units as the LCP shows them; a selection has none. kW parameters cross in W/10 (conversion index 1), the LCP
# shows kW with two decimals, so they are shown at 10^-2 (the power-of-ten the table's index and the unit imply)
UNITS = {120: "kW", 122: "V", 123: "Hz", 124: "A", 125: "RPM", 302: "Unit", 303: "Unit",
         **dict.fromkeys((341, 342, 351, 352, 361, 362, 371, 372), "s"), 411: "RPM", 412: "Hz", 413: "RPM",
         414: "Hz", 416: "%", 417: "%", 418: "%", 419: "Hz", 1601: "Unit", 1602: "%", 1610: "kW", 1612: "V",
         1613: "Hz", 1614: "A", 1616: "Nm", 1617: "RPM", 1622: "%", 1630: "V"}
_SHOWN_EXPONENT = {120: -2, 1610: -2}
_HEX = {1600, 1603}   # control and status word: bits, shown as the FC 300 Design Guide writes them


def exponent(p: FCParam) -> int:
    if p.number in _SHOWN_EXPONENT:
        return _SHOWN_EXPONENT[p.number]
    return 0 if p.conversion in (RPM, CELSIUS) else p.conversion


def shown(p: FCParam, raw: int) -> str:
    """The link's integer as the LCP shows it: 16-13's 500 at index -1 is 50.0 (CR 1394-1396)."""
    if p.number in _HEX:
        return f"0x{raw:04X}"
    e = exponent(p)
    return f"{Decimal(raw).scaleb(e):.{max(0, -e)}f}"


def parsed(p: FCParam, text: str, low: int, high: int) -> int:
    """The link's integer for a typed LCP value; ValueError with the reason."""
    try:
        value = Decimal(int(text, 16)) if text.lower().startswith("0x") else Decimal(text.strip())
    except (InvalidOperation, ValueError):
        raise ValueError(f"{p.label} {p.name}: {text.strip()!r} is not a number") from None
    raw = value.scaleb(-exponent(p))
    if not value.is_finite() or raw != raw.to_integral_value():
        raise ValueError(f"{p.label} {p.name}: {text.strip()} has more decimals than the parameter holds "
                         f"(steps of {shown(p, 1)})")
    if not low <= raw <= high:
        raise ValueError(f"{p.label} {p.name}: {text.strip()} is outside {shown(p, low)} .. {shown(p, high)}")
    return int(raw)


class DriveParametersDialog(ParameterPages):
    def __init__(self, w, parent=None) -> None:
        super().__init__(parent or w)
        self.w = w
        self.setWindowTitle("Drive Parameters (FC 300)")
        self.controller = QComboBox()
        for cid in interface_controllers(w):
            self.controller.addItem(f"Controller {cid}", cid)
        self.controller.setCurrentIndex(max(0, self.controller.findData(w.bridge.controller_id)))
        self._shown_controller = self.controller.currentData()
        self.controller.currentIndexChanged.connect(lambda _i: self._controller_changed())
        for title, menu in GROUPS:
            self.add_group(title, menu, COLUMNS, [(p.number, p) for p in FC_PARAMETERS.values()
                                                  if p.number // 100 == menu], self._cells, self._tooltip)
        self.groups.setMaximumWidth(180)
        top = QHBoxLayout()
        top.addWidget(QLabel("Controller:"))
        top.addWidget(self.controller, 1)
        top.addWidget(self.refresh)
        self.lay_out(top, 1000, 520)

    def _cells(self, p: FCParam) -> tuple[str, ...]:
        return p.label, p.name, "", UNITS.get(p.number, ""), str(p.conversion), self._range(p)

    @staticmethod
    def _tooltip(p: FCParam) -> str:
        return (f"{p.label} {p.name}\nsource: {p.source}"
                + ("\nindexed: index 0 is shown (the link reaches index 0)" if p.size else ""))

    def shown(self, p: FCParam, raw: int) -> str:
        return shown(p, raw)

    def _range(self, p: FCParam) -> str:
        if p.number in _HEX:
            return f"{shown(p, p.low)} .. {shown(p, p.high)}"
        low = FC_PARAMETERS[p.low_par].label if p.low_par else shown(p, p.low)
        high = FC_PARAMETERS[p.high_par].label if p.high_par else shown(p, p.high)
        return f"{low} .. {high}"

    def _bound(self, number: int, fallback: int) -> int:
        row = self.rows.get(number)
        if row is None:
            return fallback
        value = row.pending if row.pending is not None else row.current
        return fallback if value is None else value

    # --- reading and writing (link-jobs thread) ----------------------------------------------------------------
    def read(self) -> None:
        link, cid = controller_link(self.w, self._shown_controller), self._shown_controller
        self._busy(f"Controller {cid}: reading the drive's parameters …")
        self.jobs.run(lambda: {n: link.read_parameter(row.p.label) for n, row in self.rows.items()},
                      lambda result: self._loaded(cid, result))

    def _write_then_read(self, cid: int, then_cid: int, done) -> None:
        """The changed values to controller `cid`, then every value of `then_cid` (the same or the next one)."""
        link, then = controller_link(self.w, cid), controller_link(self.w, then_cid)
        values = self.pending()

        def work():
            if values:
                write_settings(link, values)
            return {n: then.read_parameter(row.p.label) for n, row in self.rows.items()}

        self._busy(f"Controller {cid}: writing {', '.join(values)} …" if values else "reading …")
        self.jobs.run(work, done)

    def accept(self) -> None:
        if self.refused():
            self.say("Not written: " + "; ".join(self.refused()), error=True)
            return
        if not self.pending():
            super().accept()
            return
        cid, written = self._shown_controller, list(self.pending())

        def done(result) -> None:
            self._loaded(cid, result)
            if not isinstance(result, Exception):
                self.w.messages.ide(f"Controller {cid}: wrote FC 300 {', '.join(written)}")
                super(DriveParametersDialog, self).accept()

        self._write_then_read(cid, cid, done)

    def _controller_changed(self) -> None:
        """Another controller: the changed values go to the one left, then the new one's are read (DG 2816-2818)."""
        old, new = self._shown_controller, self.controller.currentData()
        if self.refused():
            self._select(old)
            self.say("Not written: " + "; ".join(self.refused()), error=True)
            return

        def done(result) -> None:
            if isinstance(result, Exception):
                self._select(old)
                self._busy(None)
                self.say(f"Controller {old}: {result}", error=True)
                return
            self._shown_controller = new
            for row in self.rows.values():
                row.pending = None
            self._loaded(new, result)

        self._write_then_read(old, new, done)

    def _select(self, cid: int) -> None:
        self.controller.blockSignals(True)
        self.controller.setCurrentIndex(self.controller.findData(cid))
        self.controller.blockSignals(False)

    # --- editing ----------------------------------------------------------------------------------------------
    def parse(self, row) -> int:
        p = row.p
        return parsed(p, row.item.text(), self._bound(p.low_par, p.low) if p.low_par else p.low,
                      self._bound(p.high_par, p.high) if p.high_par else p.high)

    def recheck_others(self, row) -> None:
        for other in self.rows.values():   # a value typed against this one's bound is checked again (4-11, 4-13)
            if row.p.number in (other.p.low_par, other.p.high_par) and (other.refused or other.pending is not None):
                self._check(other)

    def busy_widgets(self) -> list:
        return [self.ok, self.refresh, self.controller]
