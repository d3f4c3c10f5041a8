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

from functools import partial

from PySide6.QtWidgets import QToolButton

from motiontool.comms.protocol import LinkError
from motiontool.session.session import Session, SessionEvent
from motiontool.ui.link_jobs import waiting


class Connection:
    """The Qt adapter of the window's Session (decision I35): the session decides, this shows it."""

    def __init__(self, window) -> None:
        self.w = window
        self.registry = window.controllers
        self.session = Session(self.registry)
        self.session.listeners.append(self._session_event)
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

    # --- every controller of the interface -------------------------------------------------------------------
    def _interface_links(self, *, all_in_range: bool):
        """(id, link) of this window's interface: every controller found in its scan range, or the open ones."""
        if not self.connect_default():
            return []
        iface = self.registry.interfaces.get(self.interface_key)
        # a simulated controller exists only once something opened it: the open ones are all there are
        ids = iface.found if all_in_range and iface.config.kind != "sim" else sorted(iface.links)
        found = []
        for cid in ids:
            try:
                found.append((cid, waiting(self.w, f"Controller {cid}: connecting …",
                                           partial(self.registry.link, cid, interface=self.interface_key))))
            except (LinkError, ValueError) as exc:
                self.w.messages.ide(f"Controller {cid}: {exc}")
        return found

    def _each(self, action, doing: str, *, all_in_range: bool) -> list[int]:
        done = []
        for cid, link in self._interface_links(all_in_range=all_in_range):
            try:
                if waiting(self.w, f"Controller {cid}: {doing} …", partial(action, link)):
                    done.append(cid)
            except LinkError as exc:
                self.w.messages.ide(f"Controller {cid}: {exc}")
        return done

    def break_all(self) -> list[int]:
        """Break all (DG 2504-2514)."""
        def stop(link) -> bool:
            if link.status().program_state != "running":
                return False
            link.break_program()
            return True
        done = self._each(stop, "Break all", all_in_range=True)
        self.w.messages.ide(f"Break all: stopped the programs of controllers {_ids(done)}" if done
                            else "Break all: no program was running")
        return done

    def start_all(self) -> list[int]:
        """Start all (DG 2516-2518): Execute on every connected controller of the interface."""
        def start(link) -> bool:
            if link.status().program_state == "running":
                return False
            link.start()
            return True
        done = self._each(start, "Start all", all_in_range=False)
        self.w.messages.ide(f"Start all: started controllers {_ids(done)}" if done else "Start all: nothing started")
        return done

    def delete_programs_all(self) -> list[int]:
        """Delete Programs all (DG 2528-2534): the saved programs of every controller of the interface."""
        def delete(link) -> bool:
            programs = link.list_programs()
            for program in programs:
                link.delete_program(program.number)
            return bool(programs)
        done = self._each(delete, "Delete Programs all", all_in_range=True)
        self.w.messages.ide(f"Delete Programs all: deleted the programs of controllers {_ids(done)}" if done
                            else "Delete Programs all: no saved programs")
        return done

    def close_interface(self) -> None:
        """Close Interface (DG 2548-2550): every controller of this window's interface, after saying which."""
        key = self.interface_key
        iface = self.registry.interfaces.get(key or "")
        if iface is None:
            self.w.messages.ide("Close Interface: no interface is open in this window")
            return
        self.w.messages.ide(f"Close Interface: closing the connections to controllers {_ids(sorted(iface.links))} "
                            f"on {iface.config.description}")
        self.registry.close(interface=key)

    def close_all(self) -> None:
        """Close All Interfaces (DG 2552): every controller on every interface, in every window."""
        closed = self.registry.close()
        names = ", ".join(f"{cid} ({key})" for key, cid in closed) or "none"
        self.w.messages.ide(f"Close All Interfaces: closed the connections to controllers {names}")


def _ids(ids: list[int]) -> str:
    return ", ".join(str(i) for i in ids) or "none"



def new_registry(settings, realtime_factor: float):
    """The interfaces of a first APOSS window; its default interface comes from Settings → Interface (windows
    opened from it share its registry)."""
    from motiontool.session.controllers import ControllerRegistry
    from motiontool.ui.interface_dialog import load_interfaces

    configs, default = load_interfaces(settings)
    return ControllerRegistry(realtime_factor=realtime_factor, default=configs[default])


def new_window(w):
    """Window → New APOSS Window (DG 1999): another program and another controller, the same interfaces."""
    other = type(w)(settings=w.settings, realtime_factor=w.realtime_factor, controllers=w.controllers)
    other.ask_to_save = w.ask_to_save
    other.new_file()
    other.show()
    return other
