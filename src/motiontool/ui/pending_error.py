"""The controller's pending error, as the drive's keypad shows it (issue 23 item 3): a red entry in the status bar
while an error is pending, Controller ▸ Clear Error (also on the toolbar and beside the red entry), the error's
text, detail and line in the Communication window with a hint for the errors a user cannot guess the way out
of, an error message box (a click on the red entry) and Controller ▸ Restart, which switches the simulated
controller off and on.

A pending error blocks every later motion command with error 105 "Error not reset" (DG 11446-11450) until it is
cleared (ERRCLR, or the keypad's Reset); nothing in the IDE cleared it, so after one failed sample every later one
failed. All requests go through the window's Link on a worker thread (ui/link_jobs.py)."""

from __future__ import annotations

import re

from PySide6.QtCore import QObject, Qt
from PySide6.QtWidgets import QToolButton

from motiontool.comms.client import ErrorRecord
from motiontool.ui.link_jobs import LinkJobs

ARRAY_ERRORS = (170, 175, 176)   # the controller's DIM arrays do not fit the program's DIM (DG 11700-11740)
HINTS = {
    105: "an earlier error is still pending (status bar): Controller ▸ Clear Error, then Execute again "
         "(DG 11446-11450)",
    170: "the controller keeps the DIM arrays of earlier programs (CR 1042-1049): Controller ▸ Reset ▸ Arrays "
         "deletes them; then Clear Error and Execute again (DG 11700-11708)",
    175: "the array memory is full of earlier programs' arrays: Controller ▸ Reset ▸ Arrays deletes them; then "
         "Clear Error and Execute again (DG 11724-11728)",
    176: "the controller keeps the DIM arrays of earlier programs and a size cannot change (CR 1042-1049): "
         "Controller ▸ Reset ▸ Arrays deletes them; then Clear Error and Execute again (DG 11732-11740)",
}
_DIM = re.compile(r"^\s*DIM\b", re.IGNORECASE)
RED = "QToolButton { color: white; background: #b00020; border-radius: 3px; padding: 1px 6px; font-weight: bold; }"


class PendingError(QObject):
    def __init__(self, w) -> None:
        super().__init__(w)
        self.w = w
        self.jobs = LinkJobs(self)
        # (controller ID, error number) → its last event: text, line, detail (a 105 that follows keeps the first's)
        self.known: dict[tuple[int, int], dict] = {}
        self.indicator = QToolButton()
        self.indicator.setStyleSheet(RED)
        self.indicator.setToolTip("The controller's pending error: click for its details and what clears it")
        self.indicator.clicked.connect(lambda *_: self.show_box())
        self.clear_button = QToolButton()
        self.clear_button.setToolButtonStyle(Qt.ToolButtonStyle.ToolButtonTextBesideIcon)  # the icon alone is vague
        self.indicator.hide()
        self.clear_button.hide()

    def attach(self) -> None:
        """Into the status bar, once the menus have built the Clear Error action."""
        self.clear_button.setDefaultAction(self.w.actions_by_text["Clear Error"])
        bar = self.w.statusBar()
        bar.insertPermanentWidget(0, self.indicator)
        bar.insertPermanentWidget(1, self.clear_button)

    # --- the error as it arrives ---------------------------------------------------------------------------
    def report(self, time_ms: int, number: int, text: str, line, cid: int) -> int | None:
        """Say the error in the Communication window; its detail and a hint follow when the controller's error
        history has answered. Returns the line (a DIM error names the program's DIM line, which the controller
        does not: the arrays are made before the first statement runs)."""
        if not line and number in ARRAY_ERRORS:
            line = self._dim_line(cid)
        self.known[(cid, number)] = {"text": _plain(text, number), "line": line, "detail": ""}
        self.w.messages.controller(cid, text + (f" (line {line})" if line else ""))
        link = self.w.bridge.link if cid == self.w.bridge.controller_id else None
        if link is None:
            self._explain(cid, number, None)
            return line
        self.jobs.run(lambda: link.error_history(),
                      lambda history, *, c=cid, n=number, t=time_ms: self._explain(c, n, _detail(history, t, n)))
        return line

    def _explain(self, cid: int, number: int, detail: str | None) -> None:
        if detail:
            if (cid, number) in self.known:
                self.known[(cid, number)]["detail"] = detail
            self.w.messages.controller(cid, f"error {number} detail: {detail}")
        if number in HINTS:
            self.w.messages.controller(cid, f"error {number} hint: {HINTS[number]}")
        self._show(self.w.bridge.last_status)

    def _dim_line(self, cid: int) -> int | None:
        editor = self.w.development.ran.get(cid)
        if editor is None or editor not in self.w.editors():
            return None
        for n, text in enumerate(editor.toPlainText().splitlines(), 1):
            if _DIM.match(text):
                return n
        return None

    # --- the status bar ---------------------------------------------------------------------------------------
    def status(self, status) -> None:
        self._show(status)

    def _show(self, status) -> None:
        number = status.error if status is not None and self.w.bridge.connected else 0
        self.indicator.setVisible(bool(number))
        self.clear_button.setVisible(bool(number))
        if number:
            text = self.known.get((self.w.bridge.controller_id, number), {}).get("text", "")
            self.indicator.setText(f"⚠ Error {number}" + (f": {text}" if text else ""))

    # --- Clear Error, Reset Arrays, Restart ---------------------------------------------------------------
    def _link(self):
        return self.w.bridge.link if self.w.development.connect_default() else None

    def clear(self) -> None:
        """Controller ▸ Clear Error: ERRCLR, as the keypad's Reset (DG 11446-11450)."""
        link, cid = self._link(), self.w.bridge.controller_id
        status = self.w.bridge.last_status
        said = f"error {status.error} cleared" if status is not None and status.error else "error cleared"
        if link is not None:
            self.jobs.run(lambda: link.clear_error(),
                          lambda result, *, c=cid, s=said: self._done(c, result, s))

    def reset_arrays_and_clear(self) -> None:
        link, cid = self._link(), self.w.bridge.controller_id
        if link is not None:
            self.jobs.run(lambda: (link.reset("arrays"), link.clear_error()),
                          lambda result, *, c=cid: self._done(c, result, "arrays deleted, error cleared"))

    def restart(self, *, ask: bool = True) -> None:
        """Controller ▸ Restart: the simulated controller is switched off and on. Its RAM starts afresh (program
        stopped, pending error gone, variables and SET values back); what a drive stores stays: saved programs,
        parameters and arrays, and an Autostart program starts (DG 2699-2788)."""
        link, cid = self._link(), self.w.bridge.controller_id
        if link is None:
            return
        if ask and not self.w.prompts.confirm(
                "Restart", f"Switch controller {cid} off and on? The program stops and the pending error "
                "is cleared; stored programs, parameters and arrays are kept."):
            return
        self.jobs.run(lambda: link.power_on(),
                      lambda result, *, c=cid: self._done(c, result, "restarted (switched off and on)"))

    def _done(self, cid: int, result, said: str) -> None:
        if isinstance(result, Exception):
            self.w.messages.ide(f"Controller {cid}: {result}")
            return
        self.w.messages.ide(f"Controller {cid}: {said}")
        self.w.bridge.poll()   # the status bar follows when the controller says the error is gone

    # --- the message box ---------------------------------------------------------------------------------------
    def show_box(self) -> None:
        """The pending error with its detail, line and hint; its buttons clear it."""
        cid = self.w.bridge.controller_id
        status = self.w.bridge.last_status
        number = status.error if status is not None else 0
        known = self.known.get((cid, number), {})
        info = [f"Line {known['line']} of the program." if known.get("line") else "",
                known.get("detail", ""), HINTS.get(number, "")]
        choices = ["Clear Error"] + (["Reset Arrays and Clear Error"] if number in ARRAY_ERRORS else []) \
            + ["Restart Controller"]
        chosen = self.w.prompts.choose(
            "Controller error", f"Controller {cid}: error {number}" + (f": {known['text']}" if known else ""),
            choices, detail="\n\n".join(i[:1].upper() + i[1:] for i in info if i), warning=True, cancel="Close")
        if chosen == "Clear Error":
            self.clear()
        elif chosen == "Reset Arrays and Clear Error":
            self.reset_arrays_and_clear()
        elif chosen == "Restart Controller":
            self.restart(ask=False)


def _plain(text: str, number: int) -> str:
    """'error 176: Array size wrong' → 'Array size wrong'."""
    prefix = f"error {number}: "
    return text[len(prefix):] if text.startswith(prefix) else text


def _detail(history: list[ErrorRecord] | Exception, time_ms: int, number: int) -> str | None:
    if isinstance(history, Exception):
        return None
    for record in reversed(history):
        if record.time_ms == time_ms and record.number == number:
            return record.detail or None
    return None
