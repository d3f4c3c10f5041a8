"""SDO between simulated controllers: SDOREAD/SDOWRITE/SDOREADSEG(P)/SDOSTATE, CAN I/O and CANINI (DG 7355-7391,
CR 3689-3887)."""

from __future__ import annotations

from pathlib import Path

from motiontool.kernel import cansdo
from tests.kernel.can_helpers import bus, errors, prints

MANUAL = Path(__file__).parents[1] / "aposs" / "manual"


def test_sdowrite_sets_another_controllers_maximum_velocity_as_the_manual_says():
    """CR 3887: `SDOWRITE 127 0x2300 2 3000 // sets max. velocity to 3000 rpm`; DG 7405-7407: "one controller could
    easily write into the others object dictionary"; CR 3689-3698: SDOREAD returns the object's value."""
    sim = bus({1: """SDOWRITE 2 0x2300 2 3000 // sets max. velocity to 3000 rpm
PRINT "VELMAX of 2: ", SDOREAD 2 0x2300 2, " KPROP of 2: ", SDOREAD 2 (0x2000 + 3260) 0
PRINT "done at ", TIME
""", 2: ""})
    sim.run_for(50)
    assert sim[2].params.get("VELMAX") == 3000
    assert prints(sim, 1) == ["VELMAX of 2: 3000 KPROP of 2: 30", "done at 7"]   # 2 ms per expedited transfer


def test_a_non_waiting_sdoread_is_polled_with_sdostate():
    """CR 3857-3866 (SDOSTATE syntax example): `res = SDOREAD -id idx subidx / WHILE(res == 0) DO / res = SDOSTATE id
    value` — 1 = answer arrived, value = data; reading the result frees the channel (-33 "id not in use")."""
    sim = bus({1: """id = 2
value = 0
res = SDOREAD -id 0x1018 2
WHILE(res == 0) DO
res = SDOSTATE id value
ENDWHILE
PRINT res, " ", value
PRINT SDOSTATE id value
""", 2: ""})
    sim.run_for(50)
    assert prints(sim, 1) == ["1 305", "-33"]


def test_sdo_failures_waiting_and_not_waiting():
    """CR 3823-3837: -2 timeout (value = index << 8 + subindex), -50 aborted (value = abort code); DG 11800-11806:
    a waiting transfer that fails is error 189, which ON ERROR can handle."""
    sim = bus({1: """ON ERROR GOSUB failed
value = 0
res = SDOREAD -9 0x1000 0 // node 9 is not on the bus
WHILE(res == 0) DO
res = SDOSTATE 9 value
ENDWHILE
PRINT "timeout ", res, " ", value, " at ", TIME
res = SDOREAD -2 0x1234 0 // no such object
x = SDOREAD 2 0x1000 0 // another transfer to the same id: error 121 while the first one runs
WHILE(res == 0) DO
res = SDOSTATE 2 value
ENDWHILE
PRINT "abort ", res, " ", value
x = SDOREAD 2 0x1234 0
PRINT "after the error ", x
SUBMAINPROG
SUBPROG failed
PRINT "error ", ERRNO
ERRCLR
RETURN
ENDPROG
""", 2: ""})
    sim.run_for(700)
    assert prints(sim, 1) == [f"timeout -2 {0x100000} at {cansdo.SDO_TIMEOUT_MS + 1}", "error 121",
                              f"abort -50 {0x06020000}", "error 189", "after the error 0"]
    assert errors(sim, 1) == [121, 189]
    assert "0x06020000" in sim[1].error_history[-1].detail


def test_at_most_five_non_waiting_transfers_are_pending():
    """DG 11606-11612: "If a SDOREAD or SDOWRITE is used with a negative index, then the command returns immediately
    and stores the running SDO in a channel. It is freed when the result is read." — error 121 beyond 5."""
    sim = bus({1: "\n".join(f"r = SDOREAD -{n} 0x1000 0" for n in range(2, 8)) + "\n", **{n: "" for n in range(2, 8)}})
    sim.run_for(20)
    assert errors(sim, 1) == [121]
    assert sim[1].error_history[-1].line == 6


def test_segmented_reads_fill_an_array_one_byte_or_four_bytes_per_element():
    """CR 3712-3728: SDOREADSEG "delivers the result in the array given as parameter. This array contains one byte
    of the segmented data (character) in one array element"; CR 3758-3770: SDOREADSEGP packs four bytes per element.
    The manual's C24 program, reading our device name (0x1008) instead of an FC 300's software version."""
    source = (MANUAL / "C24_sdoreadsegp.m").read_text().replace("(0x2000 + para), 0", "0x1008, 0")
    sim = bus({1: source, 3: ""})
    sim.run_for(300)
    name = "MCO 305 (simulated)"
    assert prints(sim, 1)[-2:] == [f"Parameter 1549 has the length {len(name)}", name + " "]
    sim = bus({1: """DIM t[30]
n = SDOREADSEG 2, 0x1008, 0, t
PRINT n, ": ", chr(t[1]), chr(t[2]), chr(t[3]), " ", t[n + 1]
""", 2: ""})
    sim.run_for(100)
    assert prints(sim, 1) == [f"{len(name)}: MCO 0"]


def test_the_manuals_segmented_read_of_an_fc_parameter_fails_as_the_manual_handles_it():
    """C24 as printed reads FC 300 parameter 15-49 (object 0x2000 + 1549) from node 3: our simulated node 3 is an
    MCO, which has no such object, and the program's own error branch reports the SDOSTATE code -50 (CR 3831)."""
    sim = bus({1: (MANUAL / "C24_sdoreadsegp.m").read_text(), 3: ""})
    sim.run_for(300)
    assert prints(sim, 1)[-1] == "Read of 1549 failed - error -50"
    sim = bus({1: (MANUAL / "C24_sdoreadsegp.m").read_text()})     # nobody at node 3: a timeout
    sim.run_for(1000)
    assert prints(sim, 1)[-1] == "Read of 1549 failed - error -2"


def test_the_c23_example_reads_parameter_1549_as_object_0x2000_plus_1549():
    """CR 3716-3717: "index = 0x2000  subindex = parameter number"; CR 3748-3749 (C23): `subindex = 1549 // Sw
    Version`, `value = SDOREADSEG id, 0x2000, subindex, test`. 1549 cannot be an 8-bit sub-index: it addresses
    object 0x2000 + 1549 = 0x260D, sub 0, as C24 writes it (CR 3800), instead of error 183 before anything is sent
    (K116 revised). Node 3 is a simulated MCO without FC 300 parameter objects, so the node aborts the transfer;
    SDOREADSEG with a positive id waits and reports the abort as error 189 naming the object."""
    sim = bus({1: (MANUAL / "C23_sdoreadseg.m").read_text(), 3: ""})
    sim.run_for(300)
    assert [(e.number, e.detail) for e in sim[1].error_history] == [
        (189, "SDO to node 3, object 0x260D/0: aborted with code 0x06020000")]
    sim = bus({1: "DIM test[20]\nx = SDOREADSEG 3, 0x2001, 300, test\n", 3: ""})   # not 0x2000: still refused
    sim.run_for(100)
    assert [e.number for e in sim[1].error_history] == [183]


def test_out_and_in_above_256_address_the_io_of_another_controller():
    """DG 7363-7365: "If you specify a number bigger than 256, then automatically a CAN I/O is assumed. So by using
    the command OUT 257 1 you can set the output number 1 on the CAN I/O module with the Node ID 1." A simulated
    MCO serves the DS401 I/O objects 0x6000/0x6200/0x6401/0x6411 (decision N7)."""
    sim = bus({1: """OUT 515 1 // node 2, output 3
OUTB 512 0x81 // node 2, output byte 0
PRINT IN 514, " ", IN 513, " ", INB 512, " ", INAD 513 // node 2: inputs 2 and 1, byte 0, analog 1 (53)
OUTDA 513 700 // node 2: analog output 1 (42)
""", 2: ""})
    sim[2].io.inputs[2] = 1
    sim[2].io.analog[53] = -250
    sim.run_for(50)
    assert prints(sim, 1) == ["1 0 2 -250"]
    assert {n: v for n, v in sim[2].io.outputs.items() if v} == {1: 1, 8: 1}
    assert sim[2].io.analog[42] == 700


def test_canini_guards_its_modules_and_reports_error_188_for_a_silent_one():
    """CR 449-453: "a guarding telegram is sent every 20 ms to one device … No response within 100 ms indicates an
    error 188"; CR 471: "read the SYSVAR 67 [0x01220244] GuardErrorId to find out which id caused the problem";
    CR 474: for every module "a NMT0 message is sent to set the module on the status operational"."""
    sim = bus({1: """ON ERROR GOSUB guard
CANINI 2, -4, 3
WAITI 8 ON
SUBMAINPROG
SUBPROG guard
PRINT "error ", ERRNO, " node ", SYSVAR[67], " ", SYSVAR[0x01220244], " at ", TIME
ERRCLR
RETURN
ENDPROG
""", 2: "", 4: ""})
    sim.run_for(300)
    assert prints(sim, 1) == ["error 188 node 3 3 at 141"]
    sim[2].can.nmt_state = 0x7F
    sim = bus({1: "CANINI 2\nWAITI 8 ON\n", 2: ""})
    sim[2].can.tick(0)
    sim.run_for(500)
    assert errors(sim, 1) == []
