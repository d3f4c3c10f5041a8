"""Every documented CAN command runs on the simulated controller (issue 15: never error 110 for a documented
command), and the ones whose device the simulation lacks warn in `check` and give the manual's failure result."""

from __future__ import annotations

from pathlib import Path

from motiontool.aposs.commands import command_table
from motiontool.aposs.driver import compile_source
from motiontool.aposs.simulated import UNSERVED
from motiontool.kernel.commands import COMMANDS
from tests.kernel.can_helpers import bus, prints

MANUAL = Path(__file__).parents[1] / "aposs" / "manual"


def test_every_command_of_the_can_group_and_the_pdo_links_is_simulated():
    """DG 7274-7428 (CAN basic library, CANopen master and slave libraries) and CR 1910-2108 (LINKPDO, LINKSDO,
    LINKSYSVAR)."""
    table = command_table()
    names = [c.name for c in table if c.group == "CAN" and c.kind in ("command", "function", "sysvar")]
    names += ["LINKPDO", "LINKSDO", "LINKSYSVAR", *UNSERVED]
    assert len(names) > 20
    assert [n for n in names if n not in COMMANDS] == []


def test_check_warns_about_commands_without_a_simulated_device_and_they_give_the_manuals_failure_result():
    """CR 1232-1243: ENCTGREAD returns TIMEOUT -1 "No answer has been received within 300ms" — the manual's C07
    program then prints its transmission error."""
    source = (MANUAL / "C07_enctg_absolute_position_corrected.m").read_text()  # as printed: ENCODEABSRES (issue 17)
    result = compile_source(source, "c07.m")
    assert result.ok
    warnings = [d.message for d in result.diagnostics if d.severity == "warning"]
    assert any(w.startswith("ENCTGWRITE on the simulated controller") for w in warnings)
    assert any(w.startswith("ENCTGREAD on the simulated controller") for w in warnings)
    sim = bus({1: source})
    sim.run_for(3000)
    assert prints(sim, 1)[0] == "-------- Transmission error ------------: -1"
    assert sim[1].program_state == "ended"
    sim = bus({1: """DIM b[4]
PRINT ENCTGWRITE 1 b, " ", ENCTGWRITE 1 b, " ", ENCTGREAD b
DELAY 300
PRINT ENCTGREAD b, " ", MENCTGWRITE 1 b
"""})
    sim.run_for(400)
    assert prints(sim, 1) == ["0 -3 0", "-1 0"]


def test_linksysvar_shows_a_system_value_as_a_user_parameter():
    """CR 2093-2102: LINKSYSVAR links SYSVAR[indx] with parameter 19-xx; "The parameter is updated every 40 ms"."""
    sim = bus({1: """LINKSYSVAR 4119 1990 "sys_clock"
LINKSYSVAR 4097 1991 "position"
WAITI 12 ON
"""})
    sim.run_for(200)
    assert 120 <= sim[1].params.get(1990) <= 200 and sim[1].params.get(1991) == 0


def test_a_program_start_forgets_the_previous_programs_can_objects_but_not_the_pdo_set_up():
    """CR 418-419: the CANINI 999 capture is disabled "whenever you use a new CANINI command or you start a new
    program"; decision K111: so are the previous program's mailboxes; the PDO set-up stays."""
    sim = bus({1: 'a = DEFCANIN 5 8\nb = DEFCANOUT 6 8\nCANINI 999\nLINKSDO 0x01250001 32 1 "" 2\nPRINT b\n'})
    sim.run_for(5)
    assert sim[1].can.capture is not None
    sim[1].start()
    assert sim[1].can.capture is None and not sim[1].can.mailboxes and sim[1].can.pdo.tx[2].valid
    sim.run_for(5)
    assert prints(sim, 1) == ["2", "2"]              # the same object numbers again
