"""Break all, Start all, Delete Programs all and closing interfaces from a session, without Qt (issue 27 item 5;
DG 2504-2552: "Break all ... stops the programs of all controllers", one controller after another)."""

from __future__ import annotations

import time

import pytest

from motiontool.aposs.driver import compile_source
from motiontool.comms.protocol import LinkError
from motiontool.dpl.image import DplImage
from motiontool.resources import resources_path
from motiontool.session.controllers import APC_SIM, ControllerRegistry, InterfaceConfig
from motiontool.session.interface import InterfaceCommands
from motiontool.session.session import Session

LOOP = compile_source("WHILE 1 DO\n  DELAY 10\nENDWHILE\n", "loop.m", name="loop").image


@pytest.fixture
def registry():
    reg = ControllerRegistry(realtime_factor=1.0)
    yield reg
    reg.close()


def state(link, want: str) -> None:
    end = time.monotonic() + 10
    while link.status().program_state != want:
        assert time.monotonic() < end, link.status()
        time.sleep(0.01)


def run_loops(*sessions: Session) -> None:
    for session in sessions:
        session.link.download(LOOP.to_bytes(), name="loop")
        session.link.start()
        state(session.link, "running")


def test_break_all_stops_every_running_program_of_the_interface_and_start_all_starts_them(registry):
    said: list[str] = []
    session, other = Session(registry), Session(registry)
    assert session.select(1) and other.select(3)
    run_loops(session, other)
    commands = InterfaceCommands(session, said.append)
    assert commands.break_all() == [1, 3]           # also the controller another window holds
    assert said == ["Break all: stopped the programs of controllers 1, 3"]
    assert commands.break_all() == []
    assert said[-1] == "Break all: no program was running"
    assert commands.start_all() == [1, 3]
    state(other.link, "running")
    assert said[-1] == "Start all: started controllers 1, 3"


def test_delete_programs_all_deletes_the_stored_programs(registry):
    said: list[str] = []
    session = Session(registry)
    assert session.select(2)
    session.link.download(LOOP.to_bytes(), number=5, name="loop")
    commands = InterfaceCommands(session, said.append)
    assert commands.delete_programs_all() == [2]
    assert session.link.list_programs() == []
    assert commands.delete_programs_all() == []
    assert said == ["Delete Programs all: deleted the programs of controllers 2",
                    "Delete Programs all: no saved programs"]


def test_delete_programs_all_on_the_apc_claims_nothing_it_did_not_delete(registry):
    """DG 2530: Delete Programs all "will delete all programs saved on all controllers" of the interface. The
    simulated APC lists its one DPL program without a program number, and it cannot be deleted: the command must
    not say it deleted the programs of a controller that still has its program."""
    said: list[str] = []
    apc = InterfaceConfig(kind=APC_SIM, first=1, last=1)
    registry.open_interface(config=apc)
    session = Session(registry)
    assert session.select(1, interface=apc.key)
    source = resources_path("samples", "apc_7_1_position.dpl").read_text(encoding="utf-8")
    session.link.download(DplImage("apc_7_1_position.dpl", source).to_bytes(), name="apc_7_1_position.dpl")
    listed = session.link.list_programs()
    assert [p.number for p in listed] == [None]
    assert InterfaceCommands(session, said.append).delete_programs_all() == []
    assert session.link.list_programs() == listed
    assert said == ["Delete Programs all: no saved programs"]


def test_a_controller_that_refuses_is_said_and_the_others_go_on(registry):
    said: list[str] = []
    session, other = Session(registry), Session(registry)
    assert session.select(1) and other.select(2)
    run_loops(session, other)

    def run(doing, work):
        if doing == "Controller 1: Break all …":
            raise LinkError("timeout")
        return work()
    assert InterfaceCommands(session, said.append, run).break_all() == [2]
    assert said == ["Controller 1: timeout", "Break all: stopped the programs of controllers 2"]
    assert session.link.status().program_state == "running"


def test_close_interface_says_which_controllers_then_closes_them(registry):
    said: list[str] = []
    session = Session(registry)
    assert session.select(1)
    link = session.link
    InterfaceCommands(session, said.append).close_interface()
    assert said == ["Close Interface: closing the connections to controllers 1 on Simulator"]
    assert not link.alive and not session.connected
