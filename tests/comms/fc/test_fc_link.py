"""FcLink against the virtual drive's FC slave over a real pseudo-terminal and over pyserial's socket:// (the drive
in this process here; tests/comms/test_drive_process.py runs it as its own process)."""

import os
import threading

import pytest

from motiontool.aposs.driver import compile_source
from motiontool.comms.fc import telegram as fc
from motiontool.comms.fc.bus import BusSettings, FcBus
from motiontool.comms.fc.link import FcLink, scan
from motiontool.comms.links import open_link
from motiontool.comms.protocol import ConnectionLost, LinkError
from motiontool.controller.drive.listeners import open_listener
from motiontool.controller.drive.simulator import VirtualDrive
from motiontool.paramdb import database

pytestmark = pytest.mark.wire


@pytest.fixture(params=["pty", "socket"])
def served(request):
    drive = VirtualDrive([1, 2, 31, 32], clock="virtual")
    listener = open_listener("fc:pty" if request.param == "pty" else "fc:socket://127.0.0.1:0", drive)
    yield drive, listener.url
    listener.close()


def test_parameters_travel_as_public_protocol_telegrams(served):
    drive, url = served
    link = open_link(f"{url}#2,baud=115200")
    try:
        assert link.read_parameter("KPROP") == 30
        link.write_parameter("32-60", 77)
        assert drive.node(2).service.controller.params.get(3260) == 77
        assert drive.node(1).service.controller.params.get(3260) == 30     # another address, untouched
        link.write_parameter("POSERRTIME", 500)                              # Int16: a word
        link.write_parameter("19-00", -123456)                               # Int32, negative
        assert link.read_parameter("19-00") == -123456
        with pytest.raises(LinkError, match="error 183: 32-60 KPROP: 200000 is outside 0..100000") as e:
            link.write_parameter("KPROP", 200000)                            # checked before it is sent
        assert e.value.number == 183
        with pytest.raises(LinkError, match="error 112: Unknown param. \\(parameter NOPE\\)"):
            link.read_parameter("NOPE")
        with pytest.raises(LinkError, match="19-90 is read-only"):
            link.write_parameter("19-90", 1)                                 # an LCP read-out
        assert link.bus.stats.repeats == 0
    finally:
        link.close()


def test_every_parameter_reads_as_the_simulator_holds_it(served):
    drive, url = served
    link = open_link(f"{url}#31")
    try:
        controller = drive.node(31).service.controller
        for p in database():
            assert link.read_parameter(p.number) == controller.params.get(p.index), p.label
    finally:
        link.close()


def test_the_extension_carries_the_other_requests_and_events(served):
    drive, url = served
    link = open_link(f"{url}#32")           # address 32: format 2
    assert link.adr == 0xA0
    try:
        ident = link.identify()
        assert ident.node == 32 and ident.drive == "motiontool virtual drive"
        big = "\n".join(f'PRINT "line {i}"' for i in range(300)) + "\n"
        result = compile_source(big, "big.m")
        link.download(result.image.to_bytes(), name="big")                  # many chunks
        out = []
        link.subscribe(lambda e: out.append(e.text) if e.kind == "print" else None)
        link.start()
        link.advance(500)
        link.flush_events()
        assert out == [f"line {i}" for i in range(300)]
        values = list(range(-500, 500))
        link.call("restore_arrays", arrays=[{"name": "a", "values": values}])
        assert link.read_array(0) == values
    finally:
        link.close()


@pytest.mark.slow
def test_two_links_share_one_port_and_scan_finds_the_nodes(served):
    drive, url = served
    a, b = open_link(f"{url}#1"), open_link(f"{url}#2")
    try:
        assert a.bus is b.bus and a.bus.users == 2
        a.write_parameter("19-01", 11)
        b.write_parameter("19-01", 22)
        assert (a.read_parameter("19-01"), b.read_parameter("19-01")) == (11, 22)
        assert scan(a.bus, range(1, 34)) == [1, 2, 31, 32]
    finally:
        a.close()
        b.close()
    assert a.bus.closed


def test_closing_a_link_twice_leaves_the_shared_port_to_the_others(served):
    drive, url = served
    a, b = open_link(f"{url}#1"), open_link(f"{url}#2")
    try:
        a.close()
        a.close()                                     # a window and its registry may both close it
        assert not b.bus.closed and b.read_parameter("KPROP") == 30
    finally:
        b.close()
    assert b.bus.closed


def test_a_bad_option_leaves_no_port_open(served):
    drive, url = served
    with pytest.raises(LinkError, match="option poll=soon: give a number from 0.001 to 3600"):
        open_link(f"{url}#1,poll=soon")
    assert not [bus for bus in FcBus._open.values() if bus.settings.url == url.removeprefix("fc:")]


def test_a_pseudo_terminal_opens_again_after_it_was_closed():
    """Open Interface scans the port and closes it, then the controller's link opens it again. A Linux pty has no
    parity bit: it keeps PARENB off, so the second open's settings change nothing and the pty refused them."""
    drive = VirtualDrive([1], clock="virtual")
    listener = open_listener("fc:pty", drive)
    try:
        for _ in range(3):
            link = open_link(f"{listener.url}#1")
            assert link.read_parameter("KPROP") == 30
            link.close()
    finally:
        listener.close()


def test_broadcast_write_reaches_every_node_and_nobody_answers(served):
    drive, url = served
    link = open_link(f"{url}#1")
    try:
        assert link.bus.transact(fc.parameter(fc.encode_address(0, broadcast=True), fc.AK_WRITE_DWORD, 3260, 44)) \
            is None
        link.read_parameter("KPROP")        # the broadcast was applied before the next telegram is answered
        assert {drive.node(n).service.controller.params.get(3260) for n in drive.nodes} == {44}
    finally:
        link.close()


def test_a_silent_address_is_a_lost_connection_after_the_retries(served):
    drive, url = served
    link = open_link(f"{url}#9,timeout=0.02,retries=2")
    try:
        with pytest.raises(ConnectionLost, match="no valid answer from address 9 .* after 3 tries"):
            link.read_parameter("KPROP")
        assert not link.alive and link.bus.stats.timeouts == 3
    finally:
        link.close()


def test_a_drive_without_the_extension_offers_parameters_only():
    """A foreign FC slave on a pty: it knows parameter telegrams only and refuses PNU 4095 with AK 7."""
    master, slave = os.openpty()
    import tty
    tty.setraw(slave)
    stop = threading.Event()

    def plain_drive():
        reader = fc.TelegramReader()
        while not stop.is_set():
            import select
            if not select.select([master], [], [], 0.05)[0]:
                continue
            for t in reader.feed(os.read(master, 1024)):
                if isinstance(t, fc.Telegram):
                    answer = (fc.parameter(t.adr, fc.AK_REFUSED, t.pnu, 0) if t.pnu == 4095
                              else fc.parameter(t.adr, fc.AK_VALUE_DWORD, t.pnu, 1234))
                    os.write(master, fc.encode(answer))

    thread = threading.Thread(target=plain_drive, daemon=True)
    thread.start()
    link = FcLink(FcBus(BusSettings(os.ttyname(slave))), 1)
    try:
        assert link.read_parameter("KPROP") == 1234
        with pytest.raises(LinkError, match="offers parameter access only .*illegal parameter number"):
            link.status()
    finally:
        link.close()
        stop.set()
        thread.join()
        os.close(master)
        os.close(slave)


def test_a_process_block_is_answered_with_the_status_word(served):
    """decisions F17: bit 0 control ready, bit 1 drive ready, bit 7 a controller error, bit 11 a program runs."""
    drive, url = served
    link = open_link(f"{url}#1")
    try:
        answer = link.bus.transact(fc.Telegram(0x01, None, 0, 0, (0x047F, 0)))
        assert answer.pke is None and answer.pcd == (0x0003, 0)
        link.download(compile_source("main:\nDELAY 10\nGOTO main\n", "p.m").image.to_bytes())
        link.start()
        assert link.bus.transact(fc.Telegram(0x01, None, 0, 0, (0, 0))).pcd[0] == 0x0803
    finally:
        link.close()


def test_a_slow_line_is_polled_less_often(served):
    """Event polls take at most a quarter of a serial line, status displays a tenth; a socket is not paced."""
    drive, url = served
    link = open_link(f"{url}#1,baud=9600")
    try:
        serial = url.startswith("fc:/dev/")
        assert link.poll_interval_s == (pytest.approx(4 * 130 * 11 / 9600) if serial else 0.05)
        assert link.status_interval_s == (pytest.approx(10 * 230 * 11 / 9600) if serial else 0.0)
        assert link.bus.description.endswith("9600 baud") == serial
    finally:
        link.close()


class MeddlingLine:
    """A pseudo-terminal with the virtual drive's FC slave on its far side, where `meddle(request, answer)` returns
    what the line delivers instead of the slave's answer: an echo of the request before it, a late answer to an
    earlier telegram, nothing (a lost telegram)."""

    def __init__(self, meddle):
        import tty

        from motiontool.controller.fc.server import FcSlave

        self.drive = VirtualDrive([1], clock="virtual")
        self.slave = FcSlave(self.drive)
        self.meddle = meddle
        self.master, self.slave_fd = os.openpty()
        tty.setraw(self.slave_fd)
        self.path = os.ttyname(self.slave_fd)
        self.stop = threading.Event()
        self.thread = threading.Thread(target=self._serve, daemon=True)
        self.thread.start()

    def _serve(self):
        import select

        reader = fc.TelegramReader()
        while not self.stop.is_set():
            if not select.select([self.master], [], [], 0.05)[0]:
                continue
            for t in reader.feed(os.read(self.master, 4096)):
                if isinstance(t, fc.Telegram):
                    answer = self.slave.on_telegram(t)
                    os.write(self.master, self.meddle(t, fc.encode(answer) if answer else b""))

    def close(self):
        self.stop.set()
        self.thread.join()
        self.slave.close()
        os.close(self.master)
        os.close(self.slave_fd)


def test_a_line_that_echoes_the_requests_reads_and_writes_right():
    """A 2-wire RS-485 adapter hears its own telegrams: each request comes back before the drive's answer. An echo
    is not an answer — a read echoed as AK 1 would read 0, a word write echoed as AK 2 would "verify" a write the
    drive never answered."""
    line = MeddlingLine(lambda request, answer: fc.encode(request) + answer)
    link = FcLink(FcBus(BusSettings(line.path, timeout_s=0.1)), 1)
    try:
        assert link.read_parameter("KPROP") == 30
        link.write_parameter("POSERRTIME", 500)                     # Int16: a word write (AK 2)
        link.write_parameter("KPROP", 55)                           # a double word (AK 3)
        controller = line.drive.node(1).service.controller
        assert (controller.params.get(3260), link.read_parameter("POSERRTIME")) == (55, 500)
        assert link.status().program_state == "idle"                # the extension too
        assert link.bus.stats.repeats == 0
    finally:
        link.close()
        line.close()


def test_a_late_refusal_of_a_parameter_is_not_the_drive_refusing_the_extension():
    """A refusal (AK 7) that arrives late, after its request was given up, names its parameter: during an extension
    exchange it is a stray answer, not the drive saying it has no extension (which refuses PNU 4095)."""
    def late_refusal(request, answer):
        late = fc.encode(fc.parameter(request.adr, fc.AK_REFUSED, 3260, 2)) if request.text is not None else b""
        return late + answer

    line = MeddlingLine(late_refusal)
    link = FcLink(FcBus(BusSettings(line.path, timeout_s=0.1)), 1)
    try:
        assert link.identify().node == 1
        assert link.status().program_state == "idle"
    finally:
        link.close()
        line.close()


@pytest.mark.slow
def test_a_scan_leaves_the_retries_of_the_links_on_its_bus_alone():
    """Open Interface scans a port other windows' controllers may be using: each probe gets one short try, while a
    link's own request on the same bus keeps its repeats (here the line loses every first try)."""
    seen = set()

    def first_try_lost(request, answer):
        raw = fc.encode(request)
        if raw in seen:
            return answer
        seen.add(raw)
        return b""

    line = MeddlingLine(first_try_lost)
    link = FcLink(FcBus(BusSettings(line.path, timeout_s=0.05)), 1)
    found = []
    scanning = threading.Thread(target=lambda: found.extend(scan(link.bus, range(2, 40))))
    try:
        scanning.start()
        import time

        time.sleep(0.3)
        assert scanning.is_alive()                     # the scan waits for silent addresses 2..39
        assert link.read_parameter("KPROP") == 30      # one repeat: the link's retries hold during the scan
        scanning.join()
        assert found == [] and (link.bus.settings.retries, link.bus.settings.timeout_s) == (3, 0.05)
    finally:
        scanning.join()
        link.close()
        line.close()


def test_a_scan_asks_the_silent_addresses_once_more():
    """A drive that misses a probe (busy for a moment, or the PC is loaded) is still found by Open Interface: the
    addresses that did not answer get a second round (here the line loses every first try)."""
    seen = set()

    def first_try_lost(request, answer):
        raw = fc.encode(request)
        if raw in seen:
            return answer
        seen.add(raw)
        return b""

    line = MeddlingLine(first_try_lost)
    link = FcLink(FcBus(BusSettings(line.path, timeout_s=0.05)), 2)
    try:
        assert scan(link.bus, range(1, 4)) == [1]
        assert len(seen) == 3                          # each address probed; only the silent ones twice
    finally:
        link.close()
        line.close()
