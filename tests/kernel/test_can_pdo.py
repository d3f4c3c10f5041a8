"""PDOs between simulated controllers: LINKSDO/LINKPDO, PDO[], CANINI 999, the PDO objects (CR 1910-2092,
3298-3404; DG 7399-7428).

DG 7405-7408: "This functionality, for example, allows very easy communication between two controllers. … the PDO
command could be used to transmit PDO's which can be easily read by all other controllers using, for example, the
extended CANINI 999 function."
"""

from __future__ import annotations

from pathlib import Path

from motiontool.kernel import objdict
from motiontool.kernel.canbus import CanFrame
from tests.kernel.can_helpers import bus, errors, prints, tap

MANUAL = Path(__file__).parents[1] / "aposs" / "manual"
IDLE = "WAITI 12 ON\n"               # the program stays (input 12 is never set)
LISTEN_TO_NODE_1 = "SYSVAR[0x01140001] = 0x181 // RxPDO 1 takes node 1's TxPDO 1 (0x1400 sub 1)\n"


def test_inputs_of_one_controller_drive_the_outputs_of_the_other_through_a_pdo():
    """CR 2085-2088 (LINKSDO example 2): inputs 1-8 / 9-16 (0x2202 sub 2/3) into TxPDO 1; CR 1988-1990 (LINKPDO
    example 2): 8 bits of RxPDO 1 to outputs 1-8 / 9-16 (0x2202 sub 10/11). CR 2058-2060: "a changed PDO is
    automatically dispatched"."""
    sim = bus({1: """LINKSDO 0x01220202 8 1 " " 1
LINKSDO 0x01220203 8 2 " " 1
""" + IDLE, 2: LISTEN_TO_NODE_1 + """LINKPDO 1 8 0x0122020A 1
LINKPDO 2 8 0x0122020B 1
""" + IDLE})
    frames = tap(sim)
    sim[1].io.schedule(100, 1, 1)
    sim[1].io.schedule(100, 3, 1)
    sim[1].io.schedule(200, 3, 0)
    sim.run_for(99)
    assert not any(sim[2].io.outputs.values())
    sim.run_for(3)
    assert {n for n, v in sim[2].io.outputs.items() if v} == {1, 3}
    sim.run_for(100)
    assert {n for n, v in sim[2].io.outputs.items() if v} == {1}
    sent = [(t, f.data) for t, f in frames if f.can_id == 0x181]
    assert (100, b"\x05\x00") in sent and (200, b"\x01\x00") in sent
    gaps = {b - a for (a, _), (b, _) in zip(sent, sent[1:], strict=False)}
    assert max(gaps) == 10                       # the event time: at least every 10 ms (CR 3359-3362)


def test_linkpdo_to_a_user_parameter_fires_on_param_each_time_it_changes():
    """The manual's C15 program (CR 2852-2860): `LINKPDO 1 32 0x01220101 0` + `ON PARAM 0x01220101 GOSUB
    UserParamUpdate`; node 1 sends its user parameter 19-00 (CR 1986: "user parameter 1 (= SDO 0x2201/01)")."""
    sim = bus({1: """LINKSDO 0x01220101 32 1 "" 1
k = 1
WHILE (k <= 3) DO
  DELAY 100
  SET 1900 (k * 1000)
  k = k + 1
ENDWHILE
""" + IDLE, 2: LISTEN_TO_NODE_1 + (MANUAL / "C15_on_param_user_param.m").read_text().replace(
        "SUBMAINPROG", IDLE + "SUBMAINPROG")})   # the example ends at once without a loop
    sim.run_for(450)
    assert prints(sim, 2) == [f"User Parameter 1 updated: {k * 1000}" for k in (1, 2, 3)]
    assert sim[2].params.get(1900) == 3000


def test_pdo_array_capture_with_canini_999():
    """CR 3366: "The command PDO writes directly in the outgoing PDO"; CR 3389-3397: PDO[1].b1 is byte 1 of the
    PDO; CR 380-420: after `CANINI 999`, `CANIN (id * 100) timeout 0 hi lo` reads the last TxPDO1 of node id, "as if
    you read them with PDO[]"."""
    sim = bus({1: """PDO[1001] = 0x12345678
PDO[1002] = -1
PRINT PDO[1].b1, " ", PDO[1001].b4, " ", PDO[2]
""" + IDLE, 2: """hi = 0
lo = 0
CANINI 999
r = CANIN (1 * 100) 100 0 hi lo
PRINT r, " ", hi, " ", lo
r = CANIN 100 (-1) 0 hi lo
PRINT r
"""})
    sim.run_for(50)
    assert prints(sim, 1) == [f"{0x78} {0x12} -1"]
    assert prints(sim, 2) == [f"0 {0x12345678} -1", "-1"]


def test_transmission_type_254_sends_only_on_a_remote_frame():
    """CR 2060-2065: "you can set the SDO-Index 0x1800 sub index 2 to another value (e.g. 254, instead of the
    standard 255). Thereby, dispatching no longer takes place automatically, but instead the PDO has to be collected
    per remote frame"."""
    sim = bus({1: 'LINKSDO 0x01250017 32 1 "sys_clock" 1\n' + IDLE, 2: """SDOWRITE 1 0x1800 2 254
DELAY 100
hi = 0
lo = 0
rx = DEFCANIN 0x181 4
r = CANIN rx 50 1 hi lo
PRINT r, " ", (hi >> 24) + ((hi >> 8) & 0xFF00)
"""})
    frames = tap(sim)
    sim.run_for(200)
    times = [t for t, f in frames if f.can_id == 0x181 and not f.rtr]
    assert len(times) == 1 and 100 < times[0] < 110   # only the answer to the remote frame after the switch
    assert prints(sim, 2) == [f"0 {times[0]}"]


def test_a_pdo_mapped_by_sdo_with_a_1_ms_event_timer():
    """The CANopen way a master sets up a TxPDO (CiA 301 7.5.2.36): invalidate it, clear the mapping, map objects,
    set the count, the event time, and validate it; here node 2 maps node 1's tracking error and clock into TxPDO 2
    sent every 1 ms."""
    sim = bus({1: IDLE, 2: """SDOWRITE 1 0x1801 1 (0x80000000 + 0x281)
SDOWRITE 1 0x1A01 0 0
SDOWRITE 1 0x1A01 1 0x25000620 // 0x2500 sub 6: REG_TRACKERR, 32 bits
SDOWRITE 1 0x1A01 2 0x25001720 // 0x2500 sub 23: sys_clock
SDOWRITE 1 0x1A01 0 2
SDOWRITE 1 0x1801 5 1
SDOWRITE 1 0x1801 1 0x281
""" + IDLE})
    frames = tap(sim)
    sim.run_for(100)
    clocks = [int.from_bytes(f.data[4:8], "little") for t, f in frames if f.can_id == 0x281]
    assert len(clocks) >= 80 and clocks == list(range(clocks[0], clocks[0] + len(clocks)))
    assert sim[1].can.pdo.tx[2].entries[1].mapping_value() == 0x25000620
    assert objdict.read(sim[1], 0x1A01, 2) == 0x25001720 and objdict.read(sim[1], 0x1801, 1) == 0x281


def test_nmt_stop_silences_pdos_and_the_heartbeat_reports_the_state():
    """CiA 301: PDOs travel only in OPERATIONAL; the heartbeat (0x1017) carries the NMT state. The MCO enters
    OPERATIONAL by itself after its boot-up message (decision K105)."""
    sim = bus({1: 'PDO[1001] = 7\n' + IDLE, 2: """SDOWRITE 1 0x1017 0 50
nmt = DEFCANOUT 0 2
DELAY 100
CANOUT nmt 0x02010000 0 // stop node 1
DELAY 100
CANOUT nmt 0x01010000 0 // start node 1
"""})
    frames = tap(sim)
    sim.run_for(300)
    pdo_times = [t for t, f in frames if f.can_id == 0x181]
    assert not [t for t in pdo_times if 104 <= t <= 201] and [t for t in pdo_times if t > 202]
    beats = [(t, f.data[0]) for t, f in frames if f.can_id == 0x701]
    assert beats[0] == (1, 0)                                # boot-up
    assert {state for t, state in beats if 110 < t < 200} == {0x04} and beats[-1][1] == 0x05


def test_the_object_dictionary_through_sysvar():
    """CR 2039: SYSVAR index = 0x01000000 + (SDO index << 8) + subindex; every parameter at 0x2000 + its number
    (decision N2); the manual's SDO2 example (DG 7339-7349) toggles the NOT_VALID bit of 0x1201."""
    sim = bus({5: (MANUAL / "F_D23_sysvar_sdo2.m").read_text() + """
PRINT SYSVAR[0x012CBC00], " ", SYSVAR[0x01250001] == SYSVAR[4097], " ", SYSVAR[0x01100800]
SYSVAR[0x01120101] = 0x685
PRINT SYSVAR[0x01120101] == 0x685
SYSVAR[0x01250001] = 5
"""})
    sim.run_for(10)
    assert prints(sim, 5) == ["30 1 0", "1"]
    assert errors(sim, 5) == [183]                          # 0x2500 sub 1 (REG_ACTPOS) is read-only
    assert objdict.read(sim[5], 0x1201, 2) == 0x80000105


def test_frames_from_outside_the_simulation_reach_every_controller():
    """CanBus.inject: what a bridge (the virtual drive) hands in arrives at the next tick."""
    sim = bus({1: "r = DEFCANIN 0x300 8\nhi = 0\nlo = 0\nx = CANIN r 0 0 hi lo\nPRINT hi\n",
               2: "r = DEFCANIN 0x300 8\nhi = 0\nlo = 0\nx = CANIN r 0 0 hi lo\nPRINT hi\n"})
    sim.run_for(5)
    sim.can_bus.inject(CanFrame(0x300, b"\x00\x00\x01\x00"))
    sim.run_for(2)
    assert prints(sim, 1) == prints(sim, 2) == ["256"]


def test_reset_communication_gives_sdo_server_2_its_power_on_value_again():
    """CiA 301 7.3.2.2.2: NMT Reset Communication sets the communication objects to their power-on values; the
    power-on value of 0x1201 is NOT_VALID (DG 7327-7337, decision N52). The virtual drive's CANopen server did so
    (N51); the simulation of the controllers alone kept SDO 2 valid."""
    sim = bus({5: "SYSVAR[0x01120101] = 0x105\nSYSVAR[0x01120102] = 0x685\nmain:\nDELAY 10\nGOTO main\n"})
    sim.run_for(10)
    assert (objdict.read(sim[5], 0x1201, 1), objdict.read(sim[5], 0x1201, 2)) == (0x105, 0x685)
    sim.can_bus.inject(CanFrame(0x000, bytes([0x82, 5])))      # NMT Reset Communication of node 5
    sim.run_for(5)
    assert (objdict.read(sim[5], 0x1201, 1), objdict.read(sim[5], 0x1201, 2)) == (0x80000105, 0x80000685)
