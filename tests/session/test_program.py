"""Execute, Break, Continue, Execute now and the debugger on a session, without Qt (issue 27 item 5): the steps DG
2380-2391 lists ("connect, ask whether the controller runs, compile, download, start"), the questions asked through
a Prompts, what is said. Runs in the environment without Qt too."""

from __future__ import annotations

import time
from pathlib import Path

import pytest

from motiontool.aposs.driver import compile_source
from motiontool.program_header import TestSettings as Settings
from motiontool.session.controllers import ControllerRegistry
from motiontool.session.debug import DebugSession
from motiontool.session.program import Program, ProgramCommands
from motiontool.session.prompts import PromptRefused, ScriptedPrompts
from motiontool.session.session import Session

LOOP = "i = 0\nWHILE 1 DO\n  i = i + 1\n  DELAY 10\nENDWHILE\n"


@pytest.fixture
def session():
    registry = ControllerRegistry(realtime_factor=1.0)
    yield Session(registry)
    registry.close()


def program(source: str, name: str = "p.m") -> Program:
    result = compile_source(source, name, name=Path(name).stem)
    assert result.ok, [d.format() for d in result.errors]
    image = result.image
    return Program(image, None, [(v.name, v.dims) for v in image.dims], origin=name, listing=image)


def commands(session, *answers) -> tuple[ProgramCommands, list[str], ScriptedPrompts]:
    said: list[str] = []
    prompts = ScriptedPrompts.answering(answers)
    return ProgramCommands(session, prompts, said.append), said, prompts


def wait_state(session, *states: str, timeout: float = 10.0) -> str:
    end = time.monotonic() + timeout
    while (state := session.link.status().program_state) not in states:
        assert time.monotonic() < end, f"still {state}, waiting for {states}"
        time.sleep(0.01)
    return state


def test_execute_connects_compiles_downloads_and_starts_without_asking_an_idle_controller(session):
    cmds, said, prompts = commands(session)                     # no answers: any question raises
    built = []
    assert cmds.execute(lambda: built.append(1) or program(LOOP, "loop.m"), Settings)
    assert session.connected and built == [1]
    wait_state(session, "running")
    assert said == ["Executing loop on controller 1"]   # the image is named by the program's stem
    assert prompts.asked == []
    assert cmds.ran == {1: "loop.m"} and cmds.images[1] is not None


def test_a_running_program_is_stopped_only_after_yes(session):
    """DG 2380-2391: Execute on a controller that runs a program asks first; No leaves it running."""
    cmds, said, prompts = commands(session, False)
    assert cmds.execute(lambda: program(LOOP, "first.m"), Settings)
    wait_state(session, "running")
    built = []
    assert not cmds.execute(lambda: built.append(1) or program(LOOP, "second.m"), Settings)
    assert prompts.asked == [("confirm", "Execute", "The controller is executing a program. Stop it?")]
    assert built == [] and session.link.status().program == "first"
    assert session.link.status().program_state == "running"

    prompts.answers.append(True)
    assert cmds.execute(lambda: program(LOOP, "second.m"), Settings)
    wait_state(session, "running")
    assert session.link.status().program == "second"
    assert said[-1] == "Executing second on controller 1"


def test_without_asking_a_running_program_is_stopped(session):
    cmds, _said, prompts = commands(session)
    assert cmds.execute(lambda: program(LOOP, "first.m"), Settings)
    wait_state(session, "running")
    assert cmds.execute(lambda: program(LOOP, "second.m"), Settings, ask=False)
    assert prompts.asked == []


def test_a_build_that_fails_downloads_nothing(session):
    cmds, said, _prompts = commands(session)
    assert not cmds.execute(lambda: None, Settings)
    assert session.link.list_programs() == [] and session.link.status().program_state == "idle"
    assert said == [] and cmds.ran == {}


def test_a_dim_that_does_not_fit_the_controllers_arrays_is_offered_a_reset(session):
    """CR 1042-1049: the controller keeps its DIM arrays and a size never changes (decision I20)."""
    cmds, said, prompts = commands(session, None, "Execute Anyway", "Reset Arrays and Execute")
    assert cmds.execute(lambda: program("DIM a[10]\na[1] = 5\n", "ten.m"), Settings)
    wait_state(session, "ended")
    twenty = "DIM a[20]\na[1] = 5\n"
    assert not cmds.execute(lambda: program(twenty, "twenty.m"), Settings)      # Cancel
    [(kind, title, text)] = prompts.asked
    assert (kind, title) == ("choose", "Execute")
    assert text.startswith("This program's DIM a[20] (20 elements) is array 1, which the controller already has "
                           "with 10 elements")
    assert cmds.execute(lambda: program(twenty, "twenty.m"), Settings)          # Execute Anyway
    assert wait_state(session, "ended", "error") == "error"
    assert session.link.status().error == 176
    session.link.clear_error()
    assert cmds.execute(lambda: program(twenty, "twenty.m"), Settings)          # Reset Arrays and Execute
    assert wait_state(session, "ended", "error") == "ended"
    assert "Controller 1: arrays deleted (Reset ▸ Arrays)" in said
    assert [a.size for a in session.link.list_arrays()] == [20]


def test_test_settings_are_written_before_the_download(session):
    cmds, _said, _prompts = commands(session)
    settings = Settings(settings=[("32-60", 77)])
    assert cmds.execute(lambda: program("DELAY 1\n"), lambda: settings)
    assert session.link.read_parameter("32-60") == 77


def test_a_cancelled_test_set_up_downloads_nothing(session):
    cmds, _said, _prompts = commands(session)
    assert not cmds.execute(lambda: program(LOOP), lambda: None)
    assert session.link.list_programs() == [] and session.link.status().program_state == "idle"


def test_break_connects_first_then_stops_and_continue_goes_on(session):
    cmds, _said, _prompts = commands(session)
    cmds.break_program()                                     # DG 2054-2062: Esc without a controller connects
    assert session.connected and session.link.status().program_state == "idle"
    assert cmds.execute(lambda: program(LOOP), Settings)
    wait_state(session, "running")
    cmds.break_program()
    wait_state(session, "break", "idle", "ended")


def test_execute_now_runs_one_line(session):
    cmds, _said, _prompts = commands(session)
    cmds.execute_line(compile_source("DELAY 1\n", "command.m").image)
    wait_state(session, "ended")
    assert session.link.status().program == "command"


def test_a_lost_link_is_said_not_raised(session):
    cmds, said, _prompts = commands(session)
    assert session.select(1)
    session.link.close()
    assert not cmds.execute(lambda: program(LOOP), Settings)
    assert said and said[-1].startswith("Controller 1: ")


def test_an_unexpected_question_is_an_error_naming_it():
    prompts = ScriptedPrompts()
    with pytest.raises(PromptRefused, match="unexpected confirm 'Reset'"):
        prompts.confirm("Reset", "Continue?")
    with pytest.raises(PromptRefused, match="is not one of"):
        ScriptedPrompts.answering(["Maybe"]).choose("Execute", "?", ["Yes", "No"])


def test_a_debug_run_stops_before_its_first_statement_and_steps(session):
    """DG L2432-2450: Prepare Singlestep downloads the debug build and starts it stopped; Singlestep runs one
    statement; End Debug stops it and clears the breakpoints."""
    said: list[str] = []
    assert session.select(1)
    debug = DebugSession(session, said.append)
    result = compile_source("i = 1\ni = 2\ni = 3\n", "d.m", debug=True, name="d")
    asked = []
    assert debug.prepare(result.image, 1024, lambda lines: asked.append(sorted(lines)) or [3])
    assert asked == [[1, 2, 3]] and debug.active and debug.lines == {1, 2, 3}
    assert said == [f"Loading {len(result.image.to_bytes())} bytes ok"]
    wait_state(session, "break")
    assert session.link.status().line == 1
    debug.step()
    end = time.monotonic() + 10
    while (status := session.link.status()).line != 2:
        assert time.monotonic() < end, status
        time.sleep(0.01)
    assert debug.read_value("i") == 1
    assert debug.write_value("i", 40) and debug.read_value("i") == 40
    debug.go()                                                 # to the breakpoint on line 3
    while (status := session.link.status()).line != 3:
        assert time.monotonic() < end, status
        time.sleep(0.01)
    debug.end()
    assert not debug.active
    assert session.link.status().program_state != "running"      # stopped (Esc's "break"), not run on


@pytest.mark.parametrize("answer", [False, True])
def test_prepare_singlestep_asks_before_it_stops_a_running_program(session, answer: bool):
    """As Execute does (DG 2385: "the user is asked if the existing program can be stopped"), Prepare Singlestep
    asks before it stops the controller's program; No leaves it running, with its own program on the controller."""
    cmds, _, _ = commands(session)
    assert cmds.execute(lambda: program(LOOP, "loop.m"), Settings)
    wait_state(session, "running")
    said: list[str] = []
    prompts = ScriptedPrompts.answering([answer])
    debug = DebugSession(session, said.append, prompts=prompts)
    result = compile_source("i = 1\ni = 2\n", "d.m", debug=True, name="d")
    assert debug.prepare(result.image, 1024, lambda lines: []) is answer
    assert prompts.asked == [("confirm", "Prepare Singlestep", "The controller is executing a program. Stop it?")]
    if answer:
        assert wait_state(session, "break") == "break" and debug.active
    else:
        assert session.link.status().program_state == "running" and not debug.active and said == []
        assert session.link.status().program == "loop"


def test_prepare_singlestep_without_prompts_never_stops_a_running_program(session):
    cmds, _, _ = commands(session)
    assert cmds.execute(lambda: program(LOOP, "loop.m"), Settings)
    wait_state(session, "running")
    said: list[str] = []
    result = compile_source("i = 1\n", "d.m", debug=True, name="d")
    assert not DebugSession(session, said.append).prepare(result.image, 1024, lambda lines: [])
    assert said == ["Controller 1: it is executing a program: stop it first"]
    assert session.link.status().program_state == "running"
