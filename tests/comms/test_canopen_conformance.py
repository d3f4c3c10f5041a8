"""CiA 301 details of the virtual drive's CANopen nodes (issue 24 item 6), against the drive process through
python-can's own slcan client: nothing of motiontool between the test and the node."""

from __future__ import annotations

import time

import can
import pytest

from tests.comms.drive_process import drive_process
from tests.comms.test_live_links import CANOPEN, _ask, _bare_client, _nmt_state_and_heartbeat

pytestmark = pytest.mark.wire


def sdo_write(bus, index: int, sub: int, data: bytes) -> bytes:
    """An expedited download with the size indicated (CiA 301 7.2.4.3.3); the server's answer."""
    command = 0x23 | (4 - len(data)) << 2
    return _ask(bus, can.Message(arbitration_id=0x601, is_extended_id=False, data=bytes(
        [command, index & 0xFF, index >> 8, sub, *data.ljust(4, b"\0")])), 0x581)


def sdo_read(bus, index: int, sub: int) -> bytes:
    return _ask(bus, can.Message(arbitration_id=0x601, is_extended_id=False,
                                 data=bytes([0x40, index & 0xFF, index >> 8, sub, 0, 0, 0, 0])), 0x581)


def abort_code(answer: bytes) -> int | None:
    return int.from_bytes(answer[4:8], "little") if answer[0] == 0x80 else None


def nmt(bus, command: int, node: int = 1) -> None:
    bus.send(can.Message(arbitration_id=0, data=bytes([command, node]), is_extended_id=False))


def wait_state(bus, state: int) -> None:
    end = time.monotonic() + 10
    while time.monotonic() < end:
        guard = _ask(bus, can.Message(arbitration_id=0x701, is_remote_frame=True, dlc=1, is_extended_id=False),
                     0x701)
        if guard[0] & 0x7F == state:
            return
        time.sleep(0.05)
    raise AssertionError(f"the node did not reach NMT state {state:#x}")


@pytest.fixture
def bus():
    with drive_process("--node", "1", listen=CANOPEN) as drive:
        client = _bare_client(drive.url)
        try:
            yield client
        finally:
            client.shutdown()
        _, _, err = drive.stop()
        assert "Traceback" not in err


def test_writes_of_the_wrong_length_are_aborted_as_cia_301_says(bus):
    """Two bytes into KPROP (0x2000 sub 0? here the INTEGER32 parameter object) made it 16; four bytes into the
    UNSIGNED16 0x1017 were taken. 0x06070012: length too high, 0x06070013: too low."""
    assert abort_code(sdo_write(bus, 0x1017, 0, (100).to_bytes(4, "little"))) == 0x06070012
    assert abort_code(sdo_write(bus, 0x1017, 0, b"\x64")) == 0x06070013
    assert int.from_bytes(sdo_read(bus, 0x1017, 0)[4:6], "little") == 0
    assert abort_code(sdo_write(bus, 0x1017, 0, (100).to_bytes(2, "little"))) is None   # the right length
    assert int.from_bytes(sdo_read(bus, 0x1017, 0)[4:6], "little") == 100


def test_an_extended_frame_is_not_an_nmt_command(bus):
    """Extended (29-bit) id 0 with 01 01 stopped node 1: CANopen's services use base frames."""
    nmt(bus, 0x80)
    wait_state(bus, 0x7F)
    bus.send(can.Message(arbitration_id=0, data=bytes([0x02, 1]), is_extended_id=True))
    time.sleep(0.3)
    assert _nmt_state_and_heartbeat(bus)[0] == 0x7F


def test_a_stopped_node_serves_no_sdo_and_node_guarding_still_answers(bus):
    """CiA 301 7.3.2.2.3: in STOPPED only NMT (and node guarding / heartbeat) is active."""
    nmt(bus, 0x02)
    wait_state(bus, 0x04)
    bus.send(can.Message(arbitration_id=0x601, is_extended_id=False, data=bytes([0x40, 0x17, 0x10, 0, 0, 0, 0, 0])))
    end = time.monotonic() + 1.0
    while time.monotonic() < end:
        msg = bus.recv(0.2)
        assert msg is None or msg.arbitration_id != 0x581, "a STOPPED node answered an SDO request"
    nmt(bus, 0x80)
    wait_state(bus, 0x7F)
    assert sdo_read(bus, 0x1017, 0)[0] == 0x4B


def test_reset_communication_gives_the_heartbeat_its_power_on_value(bus):
    """CiA 301 7.3.2.2.2: Reset Communication sets the communication objects (0x1000-0x1FFF) to their power-on
    values; 0x1017 was kept."""
    assert abort_code(sdo_write(bus, 0x1017, 0, (200).to_bytes(2, "little"))) is None
    nmt(bus, 0x82)
    end = time.monotonic() + 10
    while time.monotonic() < end:      # the boot-up message
        msg = bus.recv(0.5)
        if msg is not None and msg.arbitration_id == 0x701 and bytes(msg.data) == b"\x00":
            break
    else:
        raise AssertionError("no boot-up message after Reset Communication")
    assert int.from_bytes(sdo_read(bus, 0x1017, 0)[4:6], "little") == 0


@pytest.mark.parametrize("data", [b"", b"\x40", b"\x40\x17\x10", b"\x23\x17\x10\x00\x64"])
def test_short_sdo_frames_are_refused_without_a_traceback(bus, data):
    """python-canopen's server printed a traceback on the drive's stderr for a malformed frame (the fixture checks
    stderr); the node goes on answering."""
    bus.send(can.Message(arbitration_id=0x601, is_extended_id=False, data=data))
    if data:
        answer = bus.recv(2.0)
        while answer is not None and answer.arbitration_id != 0x581:
            answer = bus.recv(2.0)
        assert answer is not None and abort_code(bytes(answer.data)) == 0x05040001
    assert sdo_read(bus, 0x1017, 0)[0] == 0x4B


def test_reset_node_powers_the_controller_off_and_on(tmp_path):
    """CiA 301 7.3.2.2.2: Reset Node sets the application's objects to their power-on values too: the program
    stopped by it, as Controller ▸ Restart does (decision N51); it kept running."""
    from motiontool.comms.links import open_link

    program = tmp_path / "loop.m"
    program.write_text("main:\nDELAY 10\nGOTO main\n")
    with drive_process("--node", f"1:{program}", listen=CANOPEN) as drive:
        client = _bare_client(drive.url)
        link = open_link(drive.url + "#1")
        try:
            assert link.status().program_state == "running"
            nmt(client, 0x81)
            end = time.monotonic() + 10
            while link.status().program_state == "running" and time.monotonic() < end:
                time.sleep(0.05)
            assert link.status().program_state == "idle"
        finally:
            link.close()
            client.shutdown()


@pytest.mark.parametrize("command", [0x82, 0x81], ids=["reset-communication", "reset-node"])
def test_a_reset_disables_the_second_sdo_server_again(bus, command):
    """CiA 301 7.3.2.2.2: the communication objects take their power-on values; 0x1201's is NOT_VALID (DG 7329-7331,
    decisions N51/N52). Before, Reset Communication left SDO 2 enabled."""
    def sdo2_answers() -> bool:
        bus.send(can.Message(arbitration_id=0x101, is_extended_id=False, data=bytes([0x40, 0, 0x10, 0, 0, 0, 0, 0])))
        end = time.monotonic() + 1.0
        while time.monotonic() < end:
            msg = bus.recv(0.2)
            if msg is not None and msg.arbitration_id == 0x681:
                return True
        return False

    for sub, cob in ((1, 0x101), (2, 0x681)):
        assert abort_code(sdo_write(bus, 0x1201, sub, cob.to_bytes(4, "little"))) is None
    assert sdo2_answers()
    nmt(bus, command)
    end = time.monotonic() + 10
    while time.monotonic() < end:      # the boot-up message
        msg = bus.recv(0.5)
        if msg is not None and msg.arbitration_id == 0x701 and bytes(msg.data) == b"\x00":
            break
    else:
        raise AssertionError("no boot-up message after the reset")
    assert [int.from_bytes(sdo_read(bus, 0x1201, sub)[4:8], "little") for sub in (1, 2)] == [0x80000101, 0x80000681]
    assert not sdo2_answers()
