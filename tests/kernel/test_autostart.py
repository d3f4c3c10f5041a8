"""Saved programs, Autostart and Restart (DG 2699-2788, ide-spec 2.21-2.22) on the real kernel."""

from motiontool.aposs.driver import compile_source
from motiontool.kernel.controller import Controller
from motiontool.kernel.programs import ProgramStore


def _image(source: str, name: str):
    result = compile_source(source, f"{name}.m", name=name)
    assert result.ok, [d.format() for d in result.diagnostics]
    return result.image


def _setup():
    ctl = Controller()
    printed = []
    ctl.listeners.append(lambda e: printed.append(e.text) if e.kind == "print" else None)
    store = ProgramStore()
    return ctl, store, printed


def _run(ctl, store, ms):
    for _ in range(ms):
        ctl.tick()
        store.tick(ctl)


def test_autostart_program_starts_at_power_on_and_repeats_when_it_is_the_only_one():
    """DG 2707-2711: "The Autostart program … is normally always started automatically when the controller is
    powered on"; DG 2766: "if the Autostart program is the only program to have been executed, then the
    Autostart program will be the Restart program (i.e. the Autostart program will be executed repeatedly)"."""
    ctl, store, printed = _setup()
    store.save(0, _image('PRINT "auto"\nDELAY 100\n', "auto"))
    store.set_autostart(0)
    store.power_on(ctl)
    _run(ctl, store, 350)
    assert printed.count("auto") == 4  # t = 0, ~100, ~200, ~300 ms
    assert store.listing() == [{"number": 0, "name": "auto", "autostart": True}]


def test_prgpar_chains_programs():
    """DG 2759-2761, 2768-2770: 33-80 Activated Program Number is the Restart program; a program sets it to
    link programs together."""
    ctl, store, printed = _setup()
    store.save(0, _image('PRINT "home"\nSET PRGPAR 5\n', "home"))
    store.save(5, _image('PRINT "work"\nDELAY 50\n', "work"))
    store.set_autostart(0)
    store.power_on(ctl)
    _run(ctl, store, 180)
    assert printed[:3] == ["home", "work", "work"]


def test_a_programs_set_values_revert_at_its_end_but_prgpar_stays():
    """CR 3898: "The parameter alterations are only valid while the program is running. After program end or abort,
    the original parameter values are valid again." DG 2772: "The currently executing program simply needs to set
    Activated Program Number to specify which program is to be executed next. Note that if Activated Program Number
    is not reset, then the current program will be executed repeatedly" - which holds only if the program's SET of
    33-80 outlives its end (decision K22): KPROP reverts, PRGPAR does not."""
    ctl, store, printed = _setup()
    kprop = ctl.params["KPROP"]
    store.save(0, _image('SET KPROP 77\nSET PRGPAR 5\nPRINT GET KPROP\n', "home"))
    store.save(5, _image('PRINT "work ", GET KPROP, " ", GET PRGPAR\nDELAY 50\n', "work"))
    store.set_autostart(0)
    store.power_on(ctl)
    _run(ctl, store, 120)
    assert printed[:3] == ["77", f"work {kprop} 5", f"work {kprop} 5"]


def test_break_deactivates_but_a_position_error_does_not():
    """DG 2744-2757: a user break deactivates the mechanism; errors 108, 125 and 111 do not."""
    ctl, store, printed = _setup()
    store.save(1, _image('PRINT "run"\nDELAY 100\n', "run"))
    store.set_autostart(1)
    store.power_on(ctl)
    _run(ctl, store, 20)
    ctl.break_program()
    _run(ctl, store, 300)
    assert printed == ["run"] and not store.active

    ctl, store, printed = _setup()
    store.save(1, _image('PRINT "limit"\nSET SWPOSLIMACT 1\nPOSA 600000\n', "lim"))
    store.set_autostart(1)
    store.power_on(ctl)
    _run(ctl, store, 20)
    assert ctl.error == 111
    ctl.clear_error()
    _run(ctl, store, 20)
    assert printed.count("limit") >= 2 and store.active  # 111 keeps the mechanism alive


def test_a_program_started_by_hand_is_not_restarted():
    """DG 2719-2727 NB: a manually started Autostart program "will execute as a normal program … and no
    Restart program will be started when the program terminates"."""
    ctl, store, printed = _setup()
    store.save(0, _image('PRINT "once"\n', "once"))
    store.set_autostart(0)
    store.start(ctl, 0)
    _run(ctl, store, 100)
    assert printed == ["once"]


def test_start_input_and_program_select_inputs():
    """DG 10390-10402: I_FUNCTION_3 = 15 and I_FUNCTION_7 = 13: on activation of input 7 the inputs 3, 4, 5, 6
    are evaluated binary (3 low, 4 high, 5 high, 6 low → program 6)."""
    ctl, store, printed = _setup()
    ctl.params.set("33-52", 15, source="link")
    ctl.params.set("33-56", 13, source="link")
    store.save(6, _image('PRINT "program 6"\n', "six"))
    store.power_on(ctl)
    for number, value in ((3, 0), (4, 1), (5, 1), (6, 0)):
        ctl.io.inputs[number] = value
    _run(ctl, store, 10)
    assert printed == []
    ctl.io.inputs[7] = 1
    _run(ctl, store, 10)
    assert printed == ["program 6"]
