"""The commands for every controller of a session's interface, without Qt (issue 27 item 5; DG 2504-2552).

Break all, Start all and Delete Programs all act on the controllers of the session's interface within its ID scan
range - also those no window is connected to (DG 2504-2534), one controller after another; a controller that
refuses is said and the others go on. Close Interface closes every controller of the interface after saying
which, Close All Interfaces all of them, in every window (DG 2548-2552). Requests run through `run` (the IDE: off
the GUI thread, I34), what happened is said through `say`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import partial

from motiontool.comms.link import Link
from motiontool.comms.protocol import LinkError
from motiontool.session.session import Runner, Session, run_here


@dataclass
class InterfaceCommands:
    session: Session
    say: Callable[[str], None]
    run: Runner = run_here

    def _links(self, *, all_in_range: bool) -> list[tuple[int, Link]]:
        """(id, link) of the session's interface: every controller found in its scan range, or the open ones."""
        if not self.session.connect_default(run=self.run):
            return []
        registry, key = self.session.registry, self.session.interface_key
        iface = registry.interfaces.get(key or "")
        if iface is None:
            return []
        # a simulated controller exists only once something opened it: the open ones are all there are
        ids = iface.found if all_in_range and iface.config.kind != "sim" else sorted(iface.links)
        found = []
        for cid in ids:
            try:
                found.append((cid, self.run(f"Controller {cid}: connecting …",
                                            partial(registry.link, cid, interface=key))))
            except (LinkError, ValueError) as exc:
                self.say(f"Controller {cid}: {exc}")
        return found

    def _each(self, action: Callable[[Link], bool], doing: str, *, all_in_range: bool) -> list[int]:
        done = []
        for cid, link in self._links(all_in_range=all_in_range):
            try:
                if self.run(f"Controller {cid}: {doing} …", partial(action, link)):
                    done.append(cid)
            except LinkError as exc:
                self.say(f"Controller {cid}: {exc}")
        return done

    def break_all(self) -> list[int]:
        """Break all (DG 2504-2514): the running programs."""
        def stop(link: Link) -> bool:
            if link.status().program_state != "running":
                return False
            link.break_program()
            return True
        done = self._each(stop, "Break all", all_in_range=True)
        self.say(f"Break all: stopped the programs of controllers {_ids(done)}" if done
                 else "Break all: no program was running")
        return done

    def start_all(self) -> list[int]:
        """Start all (DG 2516-2518): Execute on every connected controller of the interface."""
        def start(link: Link) -> bool:
            if link.status().program_state == "running":
                return False
            link.start()
            return True
        done = self._each(start, "Start all", all_in_range=False)
        self.say(f"Start all: started controllers {_ids(done)}" if done else "Start all: nothing started")
        return done

    def delete_programs_all(self) -> list[int]:
        """Delete Programs all (DG 2528-2534): the saved programs of every controller of the interface."""
        def delete(link: Link) -> bool:
            # the APC lists its one DPL program without a number: not a saved program, so not claimed deleted
            saved = [p.number for p in link.list_programs() if p.number is not None]
            for number in saved:
                link.delete_program(number)
            return bool(saved)
        done = self._each(delete, "Delete Programs all", all_in_range=True)
        self.say(f"Delete Programs all: deleted the programs of controllers {_ids(done)}" if done
                 else "Delete Programs all: no saved programs")
        return done

    def close_interface(self) -> None:
        """Close Interface (DG 2548-2550): every controller of the session's interface, after saying which."""
        key = self.session.interface_key
        iface = self.session.registry.interfaces.get(key or "")
        if iface is None:
            self.say("Close Interface: no interface is open in this window")
            return
        self.say(f"Close Interface: closing the connections to controllers {_ids(sorted(iface.links))} "
                 f"on {iface.config.description}")
        self.session.registry.close(interface=key)

    def close_all(self) -> None:
        """Close All Interfaces (DG 2552): every controller on every interface, in every window."""
        closed = self.session.registry.close()
        names = ", ".join(f"{cid} ({key})" for key, cid in closed) or "none"
        self.say(f"Close All Interfaces: closed the connections to controllers {names}")


def _ids(ids: list[int]) -> str:
    return ", ".join(str(i) for i in ids) or "none"
