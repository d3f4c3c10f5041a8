"""Raw CAN telegrams, buffered and global messages between two simulated controllers (DG 7274-7315).

DG 7276-7278: "you can define mailboxes with the commands DEFCANIN and DEFCANOUT for reading and writing telegrams.
Those commands allow the length and telegram id (standard 11 bit identifiers) to be chosen. Once defined, you can
use those mailboxes to receive and send those telegrams using the commands CANOUT and CANIN."
"""

from __future__ import annotations

from motiontool.kernel.canbus import CanFrame
from tests.kernel.can_helpers import bus, errors, prints, tap

# CR 503-507 (CANOUT syntax example) and CR 780-784 (DEFCANIN program sample), one on each controller
CANOUT_EXAMPLE = """valhi = 21
vallo = 41
tx1 = DEFCANOUT 500 8
/* TX object is defined with Id=500 and data length = 8 bytes */
PRINT "tx1 = ", tx1
DELAY 20
CANOUT tx1 valhi vallo /* a CAN message is sent */
"""
DEFCANIN_EXAMPLE = """var1 = 0 /* declare variables */
var2 = 0
rx1= DEFCANIN 500 8
/* RX object with Id=500 and data length=8 bytes is defined */
st = CANIN rx1 0 0 var1 var2 /* a CAN message is read */
PRINT "CANIN ", st, ": ", var1, " ", var2, " at ", TIME
"""


def test_the_manuals_canout_example_reaches_the_manuals_defcanin_example_on_the_other_controller():
    """CR 804-806: "defines an object with ld=500 and length 8 bytes / the function returns a 1"; CR 366-369:
    CANIN copies bytes 0-3 into varhi and 4-7 into varlo; timeout 0 "waits until data arrives"."""
    sim = bus({1: CANOUT_EXAMPLE, 2: DEFCANIN_EXAMPLE})
    frames = tap(sim)
    sim.run_for(100)
    assert prints(sim, 1) == ["tx1 = 1"]
    assert prints(sim, 2) == ["CANIN 0: 21 41 at 22"]     # sent in tick 21, received one tick later
    raw = [f for _, f in frames if f.can_id == 500]
    assert raw == [CanFrame(500, bytes([0, 0, 0, 21, 0, 0, 0, 41]))]   # byte 0 = high byte of valhi (K100)
    assert sim[1].program_state == sim[2].program_state == "ended"


def test_canin_with_a_timeout_returns_minus_one_when_nothing_arrives():
    """CR 426-429: `STAT = CANIN rx1 1000 0 MSG temp /* wait 1s for data */`; CR 376-377: "–1 no data has
    arrived"."""
    sim = bus({1: "", 2: """msg = 0
temp = 0
rx1 = DEFCANIN 42 8
st = CANIN rx1 1000 0 msg temp /* wait 1s for data */
PRINT st, " after ", TIME, " ms"
st = CANIN rx1 (-1) 0 msg temp
PRINT st
"""})
    sim.run_for(1200)
    assert prints(sim, 2) == ["-1 after 1001 ms", "-1"]


def test_a_shorter_telegram_fills_the_high_bytes_and_a_remote_frame_fetches_the_last_one_sent():
    """CR 371: control = 1 "Sends a remote frame and waits for data"; a transmit object answers it with its data."""
    sim = bus({1: """tx = DEFCANOUT 0x123 2
CANOUT tx 0x11223344 0x55667788
WAITI 8 ON
""", 2: """hi = 0
lo = 0
DELAY 50 // the first telegram went by before the mailbox existed
rx = DEFCANIN 0x123 2
st = CANIN rx 100 1 hi lo
PRINT st, " ", hi, " ", lo
"""})
    frames = tap(sim)
    sim.run_for(100)
    assert prints(sim, 2) == [f"0 {0x11220000} 0"]
    assert [f for _, f in frames if f.can_id == 0x123] == [CanFrame(0x123, b"\x11\x22"),
                                                         CanFrame(0x123, rtr=True, dlc=2),
                                                         CanFrame(0x123, b"\x11\x22")]


def test_candel_and_the_mailbox_limit():
    """CR 354-365: CANDEL –1 deletes all objects; a deleted object is no object any more (error 189 names the
    handle, DG 11806); DEFCANIN returns a negative value when no object is left (CR 771, DG 11417 NO_CANMEMORY)."""
    program = "\n".join(f"a{i} = DEFCANIN {100 + i} 8" for i in range(15)) + """
PRINT a1, " ", a14, " ", a0
CANDEL -1
b = DEFCANOUT 7 8
PRINT b
CANDEL b
CANOUT b 1 2
"""
    sim = bus({1: program})
    sim.run_for(10)
    assert prints(sim, 1) == ["2 -10 1", "1"]
    assert errors(sim, 1) == [189]


def test_buffered_messages_go_to_the_receive_buffer_of_cannr_times_2_plus_1():
    """DG 7299-7305: RxMessage ID = CANNR * 2 + 1, TxMessage ID = CANNR * 2, 8 bytes; CR 1739-1761: INMSG returns
    bytes 2 and 3 and MSGVAL bytes 4-7; CR 2490-2504: ON CANMSG is called while a message is in the buffer;
    CR 3260-3275: `temperature = INAD 1 / OUTMSG 20 temperature`."""
    sim = bus({1: """tx = DEFCANOUT 5 8 // RxMessage of node 2
rx = DEFCANIN 4 8  // TxMessage of node 2
hi = 0
lo = 0
CANOUT tx 0x0000BEEF 123456
CANOUT tx 0x00000007 -5
st = CANIN rx 500 0 hi lo
PRINT "from 2: ", hi, " ", lo
""", 2: """ON CANMSG GOSUB canproc
WAITI 8 ON
SUBMAINPROG
SUBPROG canproc
  a = INMSG -1
  IF (a > -1) THEN
    b = MSGVAL
    PRINT "INMSG ", a, " MSGVAL ", b
    OUTMSG 20 b
  ENDIF
RETURN
ENDPROG
"""}, settings={2: {}})
    sim.run_for(100)
    assert prints(sim, 2) == ["INMSG 48879 MSGVAL 123456", "INMSG 7 MSGVAL -5"]
    assert prints(sim, 1) == ["from 2: 20 123456"]
    assert sim[2].can.take_message() is None


def test_a_global_telegram_calls_on_caninput_and_is_read_with_inglb_and_msgval():
    """CR 2467-2488: ON CANINPUT calls the subroutine "when a global CAN telegram with the identifier '0' arrives.
    This is the same input telegram, which can be read out with INGLB and MSGVAL" — bytes 0 and 1 must be 0;
    CR 1677-1696: INGLB returns bytes 2 and 3, MSGVAL bytes 4 to 7. An NMT command on identifier 0 (bytes 0-1 not
    0) is no global telegram."""
    sim = bus({1: """g = DEFCANOUT 0 8
DELAY 10
CANOUT g 0x00000102 77
DELAY 10
nmt = DEFCANOUT 0 2
CANOUT nmt 0x01000000 0 // NMT start all: not a global message
""", 2: """ON CANINPUT 0 GOSUB global
WAITI 8 ON
SUBMAINPROG
SUBPROG global
  PRINT "global ", INGLB (-1), " ", MSGVAL, " at ", TIME
  PRINT "again ", INGLB (-1)
RETURN
ENDPROG
"""})
    sim.run_for(100)
    assert prints(sim, 2) == ["global 258 77 at 12", "again -1"]


def test_inglb_waits_for_the_next_global_telegram():
    """CR 1681-1684: p = 0 waits until a message arrives, p > 0 waits at most p ms."""
    sim = bus({1: """g = DEFCANOUT 0 8
DELAY 300
CANOUT g 5 6
""", 2: """PRINT INGLB 100, " at ", TIME
PRINT INGLB 0, " ", MSGVAL, " at ", TIME
"""})
    sim.run_for(400)
    assert prints(sim, 2) == ["-1 at 101", "5 6 at 302"]


def test_the_node_id_of_a_controller_in_a_simulation_is_its_cannr():
    """DG 10815-10819: CANNR "Defines the CAN-Node ID"; decision K101: node n of a simulation has CANNR n."""
    sim = bus({3: 'PRINT GET CANNR\n', 7: ""})
    sim.run_for(5)
    assert prints(sim, 3) == ["3"]
    assert sim[7].can.node_id == 7


def test_motiontool_run_with_several_nodes_shares_one_can_bus(tmp_path):
    """`motiontool run a.m --node 2:b.m`: the nodes' programs exchange telegrams (issue 15 item 5)."""
    import subprocess
    import sys

    (tmp_path / "a.m").write_text(CANOUT_EXAMPLE)
    (tmp_path / "b.m").write_text(DEFCANIN_EXAMPLE)
    proc = subprocess.run([sys.executable, "-m", "motiontool", "run", "a.m", "--node", "2:b.m", "--seconds", "1"],
                          capture_output=True, text=True, timeout=120, cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert sorted(proc.stdout.splitlines()) == ["1: tx1 = 1", "2: CANIN 0: 21 41 at 22"]


def test_a_new_cannr_takes_effect_at_the_next_power_up():
    """Decision K118: the controller keeps the node id it had when it was switched on (DG 10815-10819: CANNR
    "Defines the CAN-Node ID"; DG 10849-10853: a new CANBAUD needs SAVE GLBPARS and a restart)."""
    from motiontool.controller.service import ControllerService

    sim = bus({2: "SET CANNR 9\nSAVE GLBPARS\n"})
    sim.run_for(10)
    assert sim[2].params.get("CANNR") == 9 and sim[2].can.node_id == 2
    ControllerService(sim[2]).op_power_on()
    assert sim[2].can.node_id == 9
