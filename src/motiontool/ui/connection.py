"""The controller of one APOSS window and the commands for every controller of its interface (ide-spec 2.2-2.13).

- A window is connected to one controller of one interface; the title shows the controller ID and the interface
  (DG 2011), the status bar the connection state. One controller belongs to one window at a time: selecting it in
  another window moves it there (DG 2546).
- Break all, Start all and Delete Programs all act on the controllers of this window's interface within its ID scan
  range — also those no window is connected to (DG 2504-2534).
- Close Interface closes every controller of this window's interface after saying which; Close All Interfaces all
  of them, in every window (DG 2548-2552).
- A lost connection is reported in the Communication pane and the status bar, which offers Reconnect; Esc or any
  command that needs the controller reconnects to the same controller on the same interface (DG 2064-2066).
"""

from __future__ import annotations

from PySide6.QtWidgets import QToolButton

from motiontool.session.interface import InterfaceCommands
from motiontool.session.session import Session, SessionEvent
from motiontool.ui.link_jobs import waiting


class Connection:
    """The Qt adapter of the window's Session (decision I35): the session decides, this shows it."""

    def __init__(self, window) -> None:
        self.w = window
        self.registry = window.controllers
        self.session = Session(self.registry)
        self.session.listeners.append(self._session_event)
        self.interface = InterfaceCommands(self.session, window.messages.ide, self._run)
        window.bridge.serve(self.connect_default, window.prompts)   # what tool windows are given
        self.reconnect_button = QToolButton(window)
        self.reconnect_button.setText("Reconnect")
        self.reconnect_button.setToolTip("Connect again to the same controller on the same interface")
        self.reconnect_button.clicked.connect(lambda *_: self.reconnect())
        self.reconnect_button.hide()
        window.statusBar().addPermanentWidget(self.reconnect_button)

    def _run(self, doing: str, work):
        return waiting(self.w, doing, work)

    def _session_event(self, event: SessionEvent) -> None:
        if event.kind == "connected":
            self.reconnect_button.hide()
            self.w.bridge.attach(self.session.link, f"Controller {event.controller_id} ({self.interface_description})",
                                 controller_id=event.controller_id)
        elif event.kind == "disconnected":
            self.w.bridge.detach(close=False)
        elif event.kind == "lost":
            self.reconnect_button.show()
        if event.message:
            self.w.messages.ide(event.message)

    # --- what the window shows ---------------------------------------------------------------------------
    @property
    def interface_key(self) -> str | None:
        return self.session.interface_key

    @property
    def lost_reason(self) -> str:
        return self.session.lost_reason

    @property
    def interface_description(self) -> str:
        return self.session.interface_description

    def title_suffix(self, *, error: bool = True) -> str:
        """" [Controller: 1 FC: /dev/ttyUSB0 9600 baud]" while connected, " [Controller: 1 … — Lost connection]"
        after a loss (the window stays bound to its controller), "" before the first connection; with `error`
        the controller's pending error follows (" — error 171")."""
        bridge = self.w.bridge
        if bridge.connected:
            text = f" [Controller: {bridge.controller_id} {self.interface_description}]"
            status = bridge.last_status
            if error and status is not None and status.error:
                text += f" — error {status.error}"
            return text
        if self.lost_reason:
            return f" [Controller: {bridge.controller_id} {self.interface_description} — Lost connection]"
        return ""

    # --- connecting ----------------------------------------------------------------------------------------
    def select(self, controller_id: int, *, interface: str | None = None) -> bool:
        """Connect this window to a controller (the default interface when none is named); the controller it
        leaves keeps running its program; a controller another window holds moves here."""
        return self.session.select(controller_id, interface=interface, run=self._run)

    def connect_default(self) -> bool:
        return self.session.connect_default(run=self._run)

    def reconnect(self) -> bool:
        return self.session.reconnect(run=self._run)

    def release(self, why: str) -> None:
        self.session.release(why)

    def lost(self) -> None:
        """The bridge found the link dead: say so, offer Reconnect (the window stays bound to the controller)."""
        self.session.lost()

    def window_closed(self) -> None:
        self.session.close()

    # --- every controller of the interface (session/interface.py) --------------------------------------------
    def break_all(self) -> list[int]:
        return self.interface.break_all()

    def start_all(self) -> list[int]:
        return self.interface.start_all()

    def delete_programs_all(self) -> list[int]:
        return self.interface.delete_programs_all()

    def close_interface(self) -> None:
        self.interface.close_interface()

    def close_all(self) -> None:
        self.interface.close_all()


def new_registry(settings, realtime_factor: float):
    """The interfaces of a first APOSS window; its default interface comes from Settings → Interface (windows
    opened from it share its registry)."""
    from motiontool.session.controllers import ControllerRegistry
    from motiontool.ui.interface_dialog import load_interfaces

    configs, default = load_interfaces(settings)
    return ControllerRegistry(realtime_factor=realtime_factor, default=configs[default])


def new_window(w):
    """Window → New APOSS Window (DG 1999): another program and another controller, the same interfaces."""
    other = type(w)(settings=w.settings, realtime_factor=w.realtime_factor, controllers=w.controllers,
                    macros=w.macros)
    other.ask_to_save = w.ask_to_save
    other.new_file()
    other.show()
    return other
