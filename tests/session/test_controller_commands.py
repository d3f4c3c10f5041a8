"""The Controller menu's commands and Download all on a session, without Qt (issue 27 item 5): Save to file /
Restore from file, Reset, Memory, Diagnostic Report, the Programs dialog's commands and Download all's steps, with
the questions asked through a ScriptedPrompts. Runs in the environment without Qt too."""

from __future__ import annotations

from pathlib import Path

import pytest

from motiontool.aposs.driver import compile_source
from motiontool.formats.zbc import read_config
from motiontool.session.controller_commands import ControllerCommands, StoredPrograms
from motiontool.session.controllers import ControllerRegistry
from motiontool.session.download_all import DownloadAll, parse_ids
from motiontool.session.prompts import ScriptedPrompts
from motiontool.session.session import Session

PRINT = 'PRINT "stored"\n'
ALL_ON = {"download": True, "verify": True, "autostart": True, "eprom": True, "restart": False}


@pytest.fixture
def session():
    registry = ControllerRegistry(realtime_factor=1.0)
    yield Session(registry)
    registry.close()


def parts(cls, session, *answers):
    said: list[str] = []
    prompts = ScriptedPrompts.answering(answers)
    return cls(session, prompts, said.append), said, prompts


def compiled(source: str = PRINT, name: str = "prog.m"):
    return compile_source(source, name, name=Path(name).stem)


def test_save_to_file_connects_and_writes_the_configuration_and_restore_loads_the_chosen_sets(session, tmp_path):
    """DG 2886: "the entire controller configuration (i.e. global parameters, axis parameters, user parameters,
    and arrays) can be uploaded and saved as a file on the PC"; DG 2898: "select the FC 300 into which the data
    should be loaded. Use the checkboxes to specify which sets of parameters are to be loaded"."""
    path = tmp_path / "backup.zbc"
    cmds, said, prompts = parts(ControllerCommands, session, path)
    assert cmds.save_parameters()                          # connects first, then asks where
    assert session.connected and prompts.asked[0][:2] == ("save_path", "Save to file")
    assert said[-1] == f"Controller 1: configuration saved to {path}"

    session.link.write_parameter("KPROP", 77)
    assert cmds.save_parameters(path)
    assert read_config(path).parameters["32-60"] == 77
    chosen: list[Path] = []
    assert cmds.restore_parameters(path, choose=lambda p: chosen.append(p) or (2, ("axis",)))
    assert chosen == [path]
    assert session.registry.link(2).read_parameter("KPROP") == 77
    assert said[-1] == f"Controller 2: restored axis from {path}"


def test_restore_refuses_a_broken_file_before_asking_which_controller(session, tmp_path):
    cmds, said, _prompts = parts(ControllerCommands, session)
    path = tmp_path / "b.zbc"
    assert cmds.save_parameters(path)
    path.write_text(path.read_text().replace("32-60 KPROP = 30", "32-60 KPROP = 30x"))
    session.link.write_parameter("KPROP", 44)
    assert not cmds.restore_parameters(path, choose=lambda p: pytest.fail("asked for a refused file"))
    assert session.link.read_parameter("KPROP") == 44
    assert said[-1].startswith(f"Restore from file: {path}:") and "30x" in said[-1]


def test_a_file_that_cannot_be_written_is_said_and_warned_and_changes_nothing(session, tmp_path):
    cmds, said, prompts = parts(ControllerCommands, session)
    path = tmp_path / "missing" / "c.zbc"
    assert not cmds.save_parameters(path)
    assert said[-1].startswith(f"Save to file: cannot write {path}")
    assert prompts.asked[-1][:2] == ("warn", "Save to file") and not path.exists()


def test_reset_asks_once_and_no_leaves_the_controller_alone(session):
    """DG 2958: "Parameter function will reset all global and axis parameters in the controller to their
    initialization values"; DG 2962: "Arrays function will delete all arrays in RAM"."""
    cmds, said, prompts = parts(ControllerCommands, session, False)
    assert session.select(1)
    session.link.write_parameter("KPROP", 77)
    assert not cmds.reset("parameters")
    assert prompts.asked == [("confirm", "Reset Parameter", "Reset Parameter: global and axis parameters go back to "
                              "their defaults. Continue?")]
    assert session.link.read_parameter("KPROP") == 77 and said == []
    prompts.answers.append(True)
    assert cmds.reset("parameters")
    assert session.link.read_parameter("KPROP") == 30
    assert said == ["Controller 1: reset parameter done"]
    session.link.call("restore_arrays", arrays=[{"name": "table", "values": [1]}])
    assert cmds.reset("arrays", ask=False) and session.link.list_arrays() == []


def test_memory_delete_eprom_says_it_takes_effect_at_the_next_power_on(session):
    """DG 2976: "Memory → Delete EPROM which happens only after the controller has been turned off and on again"."""
    cmds, said, prompts = parts(ControllerCommands, session, True, True)
    assert cmds.memory("ram")
    assert cmds.memory("delete")
    assert [a[1] for a in prompts.asked] == ["Save RAM", "Delete EPROM"]
    assert said[-2:] == ["Controller 1: Save RAM done",
                         "Controller 1: Delete EPROM done (takes effect at the next power on)"]


def test_diagnostic_report_holds_the_whole_state(session, tmp_path):
    """DG 3031: "a text file containing the entire current state of the controller"."""
    cmds, said, _prompts = parts(ControllerCommands, session)
    path = tmp_path / "report.txt"
    assert cmds.diagnostic_report(path)
    text = path.read_text()
    for part in ("# motiontool diagnostic report, controller 1", "[status]", "[error history]", "[programs]",
                 "[readouts]", "[configuration]"):
        assert part in text, part
    assert said == [f"Controller 1: diagnostic report written to {path}"]


def test_programs_save_numbers_automatically_save_as_asks_the_number_and_delete_all_empties(session):
    """DG 2653: "Save and enter a name ... The program number will be assigned automatically"; DG 2655: "Save as
    and you can also assign the program number (0 to 90) yourself"; DG 2794: "Delete all ... deletes all the
    programs in the controller"."""
    assert session.select(1)
    progs, said, prompts = parts(StoredPrograms, session, "FIRSTPROGRAM", "SEVEN", 7)
    assert progs.save(compiled, "PROG")
    assert progs.save_as(compiled, "PROG")
    assert [(p.number, p.name) for p in progs.programs()] == [(0, "FIRSTPRO"), (7, "SEVEN")]
    assert [a[:2] for a in prompts.asked] == [("text", "Save"), ("text", "Save as"), ("integer", "Save as")]
    assert progs.start(7)
    progs.autostart(0, True)
    assert [p.number for p in progs.programs() if p.autostart] == [0]
    progs.autostart(7, False)                           # not the marked one: nothing sent, the mark stays
    assert [p.number for p in progs.programs() if p.autostart] == [0]
    progs.autostart(0, False)
    assert not any(p.autostart for p in progs.programs())
    progs.delete(0)
    assert [p.number for p in progs.programs()] == [7]
    progs.delete_all()
    assert progs.programs() == [] and said == []


def test_a_program_with_errors_is_not_stored(session):
    assert session.select(1)
    progs, said, _prompts = parts(StoredPrograms, session)
    assert not progs.store(lambda: compiled("x = \n"), name="BAD")
    assert said == ["Programs: the program has errors and was not saved"] and progs.programs() == []


def test_upload_writes_the_stored_source_under_a_name_with_its_time(session, tmp_path):
    """DG 2675: "The default program name will contain the date and time when the original source code was saved
    on the controller"."""
    assert session.select(1)
    progs, said, _prompts = parts(StoredPrograms, session)
    assert progs.store(compiled, name="UP", source=lambda result: {"up.m": PRINT})
    target = progs.upload(0, folder=tmp_path)
    assert target is not None and target.parent == tmp_path and target.name.startswith("up_")
    assert target.read_text() == PRINT and said == [f"Program 0 uploaded to {target}"]


def test_download_all_asks_before_deleting_then_downloads_verifies_and_sets_autostart(session, tmp_path):
    """DG 3316-3321: "All existing programs on the controller are deleted. The program is downloaded. The program
    is saved as program number 0 with the specified program name ... If the Verify flag is set, then the
    downloaded program is uploaded again and ... compared ... The Autostart flag is set for the program if
    requested."""
    source = tmp_path / "print3.m"
    source.write_text(PRINT)
    assert session.select(1)
    progs, _said, _p = parts(StoredPrograms, session)
    assert progs.store(compiled, number=5, name="OLD")
    steps, said, prompts = parts(DownloadAll, session, None)
    assert not steps.start(str(source), "1-2", "TEST", lambda: ALL_ON)       # Cancel: nothing is deleted
    assert prompts.asked[0][:2] == ("choose", "Download all")
    assert said[-1] == "Cancelled: no program was deleted" and [p.number for p in progs.programs()] == [5]

    prompts.answers.append("Delete and Download")
    assert steps.start(str(source), "1-2", "TEST", lambda: ALL_ON)
    assert said[said.index("Controller 1: deleting programs"):said.index("Controller 2: deleting programs")] == [
        "Controller 1: deleting programs", 'Controller 1: saved as "TEST" (program 0)', "Controller 1: verify ok",
        "Controller 1: Autostart set", "Controller 1: saving RAM"]
    assert said[-1] == "Done for controllers: 1, 2" and steps.succeeded == [1, 2] and steps.failed == []
    for cid in (1, 2):
        assert [(p.number, p.name, p.autostart) for p in session.registry.link(cid).list_programs()] == [
            (0, "TEST", True)]


def test_download_all_a_failing_controller_stops_only_itself(session, tmp_path):
    """DG 3330: "If any error occurs during the processing of a controller, then processing is halted for that
    controller. However, processing will continue for subsequent controllers in the ID range"."""
    source = tmp_path / "p.m"
    source.write_text(PRINT)
    steps, said, _prompts = parts(DownloadAll, session)
    options = dict(ALL_ON, autostart=False, eprom=False)
    assert not steps.start(str(source), "1,99,2", "", lambda: options)        # 99 is not a simulated controller
    assert steps.succeeded == [1, 2] and steps.failed == [99]
    assert said[-2:] == ["Done for controllers: 1, 2", "Failed for controllers: 99"]
    assert session.registry.link(2).list_programs()[0].name == "p"            # no name: the file's stem


def test_download_all_verify_alone_compares_without_writing(session, tmp_path):
    source = tmp_path / "p.m"
    source.write_text(PRINT)
    steps, said, _prompts = parts(DownloadAll, session)
    verify = {key: key == "verify" for key in ALL_ON}
    assert not steps.start(str(source), "1", "P", lambda: verify)
    assert said[-2].startswith("Controller 1: ") and said[-1] == "Failed for controllers: 1"
    assert session.registry.link(1).list_programs() == []


def test_download_all_refuses_a_bad_id_list_and_a_program_with_errors(session, tmp_path):
    steps, said, _prompts = parts(DownloadAll, session)
    assert not steps.start("x.m", "1,x", "", lambda: ALL_ON)
    assert said[-1] == "controllers: 'x' is not an ID or a range like 1-5"
    bad = tmp_path / "bad.m"
    bad.write_text("x = \n")
    assert not steps.start(str(bad), "1", "", lambda: ALL_ON)
    assert said[-1] == "Compilation failed: nothing downloaded"
    assert parse_ids("1-3,7, 9,2") == [1, 2, 3, 7, 9]
