"""The link syntax and scheme registry (comms/links.py), the virtual drive's nodes (controller/drive/): thread-safe
requests, events with sequence numbers for a polling master, answers kept for repeated requests, the link timeout."""

import re
import threading
import time

import pytest

from motiontool.aposs.driver import compile_source
from motiontool.comms import links, wire
from motiontool.comms.protocol import LinkError, LinkEvent, Request
from motiontool.comms.remote import RemoteLink
from motiontool.controller.drive.node import EventQueue
from motiontool.controller.drive.simulator import VirtualDrive
from motiontool.controller.embedded import EmbeddedLink


def image(source):
    result = compile_source(source, "p.m")
    assert result.ok, [d.format() for d in result.diagnostics]
    return result.image


def test_link_specs_parse_into_scheme_target_node_options():
    spec = links.parse_link_spec("fc:socket://127.0.0.1:4001#2,baud=115200,parity=E")
    assert (spec.scheme, spec.target, spec.node) == ("fc", "socket://127.0.0.1:4001", 2)
    assert spec.options == {"baud": "115200", "parity": "E"}
    assert links.parse_link_spec("fc:/dev/ttyUSB0").node is None
    assert links.parse_link_spec("fc:COM3#1").target == "COM3"
    assert links.parse_link_spec("canopen:slcan:socket://127.0.0.1:5000#3") == links.LinkSpec(
        "canopen", "slcan:socket://127.0.0.1:5000", 3, {}, "canopen:slcan:socket://127.0.0.1:5000#3")
    assert links.parse_link_spec(" sim ").scheme == "sim"


def test_bad_link_specs_say_what_is_wrong():
    with pytest.raises(LinkError, match="unknown scheme 'modbus'.*fc.*sim"):
        links.open_link("modbus:/dev/ttyS0")
    with pytest.raises(LinkError, match="the address #x: give a whole number from 0 to 255"):
        links.parse_link_spec("fc:/dev/ttyUSB0#x")
    with pytest.raises(LinkError, match="empty link"):
        links.parse_link_spec("")
    with pytest.raises(LinkError, match="unknown option 'bad'"):
        links.open_link("fc:socket://127.0.0.1:1#1,bad=1")
    with pytest.raises(LinkError, match="option baud=fast: give a whole number"):
        links.open_link("fc:socket://127.0.0.1:1#1,baud=fast")
    with pytest.raises(LinkError, match="FC addresses are 1..126"):
        links.open_link("fc:socket://127.0.0.1:1#127")
    with pytest.raises(LinkError, match="cannot open socket://127.0.0.1:1"):
        links.open_link("fc:socket://127.0.0.1:1#1")


def test_sim_is_the_embedded_link_and_other_schemes_plug_in():
    link = links.open_link("sim")
    assert isinstance(link, EmbeddedLink) and link.virtual_time
    link.close()
    opened = []
    links.register_link_scheme("test-loop", lambda spec: opened.append(spec) or EmbeddedLink(), "test-loop:X#N")
    links.open_link("test-loop:abc#4,speed=2")
    assert opened[0].target == "abc" and opened[0].node == 4 and opened[0].options == {"speed": "2"}
    assert "test-loop:X#N" in links.scheme_help()


def test_event_queue_numbers_events_and_forgets_what_the_master_saw():
    q = EventQueue(limit=3)
    for n in range(2):
        q.put(LinkEvent("print", n, f"line {n}"))
    first = q.after(0)
    assert [seq for seq, _ in first["events"]] == [1, 2] and first["last"] == 2 and first["lost"] == 0
    assert q.after(0)["events"][0][1]["text"] == "line 0"       # not acknowledged yet: sent again
    assert q.after(2) == {"events": [], "last": 2, "lost": 0, "more": False, "epoch": q.epoch}
    for n in range(2, 7):
        q.put(LinkEvent("print", n, f"line {n}"))
    overflow = q.after(2)                                        # 3..7 produced, only the newest 3 kept
    assert [seq for seq, _ in overflow["events"]] == [5, 6, 7] and overflow["lost"] == 2
    assert q.after(7, count=1)["last"] == 7
    many = EventQueue()
    for n in range(10):
        many.put(LinkEvent("print", n))
    batch = many.after(0, count=4)
    assert batch["more"] and batch["last"] == 4
    assert EventQueue().after(99)["last"] == 0                  # a master of an earlier drive starts over


@pytest.fixture
def local_link():
    """Makes RemoteLinks whose transport hands the message bytes straight to a drive node (no wire); closed at the
    end, so no event poller outlives its test."""
    made = []

    def make(drive, node=1):
        made.append(RemoteLink(drive.node(node).handle_message, f"local #{node}"))
        return made[-1]
    yield make
    for link in made:
        link.close()


def test_a_drive_node_answers_a_repeated_request_from_its_cache():
    drive = VirtualDrive([1], clock="virtual")
    node = drive.node(1)
    request = wire.encode_request(Request("write_parameter", {"key": "19-00", "value": 5}, 1), session=9)
    increment = wire.encode_request(Request("advance", {"ms": 10}, 2), session=9)
    assert wire.decode_response(node.handle_message(request)).ok
    node.handle_message(increment)
    node.handle_message(increment)                       # repeated: answered, not applied again
    assert node.service.controller.time_ms == 10
    other_session = wire.encode_request(Request("advance", {"ms": 10}, 2), session=10)
    node.handle_message(other_session)                   # same id, another master: a new request
    assert node.service.controller.time_ms == 20
    damaged = bytearray(request)
    damaged[-1] ^= 1
    answer = wire.decode_response(node.handle_message(bytes(damaged)))
    assert not answer.ok and "damaged request" in answer.error and "checksum" in answer.error


def test_remote_link_carries_requests_and_polls_events_in_order(local_link):
    drive = VirtualDrive([1, 2], clock="virtual")
    link = local_link(drive, 2)
    assert link.identify().node == 2 and link.virtual_time
    seen = []
    link.subscribe(lambda e: seen.append(e.text) if e.kind == "print" else None)
    link.download(image('i = 0\nWHILE i < 100 DO\n  PRINT "n", i\n  i = i + 1\nENDWHILE\n').to_bytes())
    link.start()
    link.advance(200)
    link.flush_events()
    assert seen == [f"n {i}" for i in range(100)]  # PRINT puts a blank between the items (K48)
    with pytest.raises(LinkError, match="no program 5"):
        link.start(5)
    link.close()


def test_realtime_drive_paces_and_refuses_advance(local_link):
    drive = VirtualDrive([1], clock="realtime")
    drive.start()
    try:
        link = local_link(drive)
        t0 = link.status().time_ms
        time.sleep(0.3)
        elapsed = link.status().time_ms - t0
        assert 200 <= elapsed <= 450
        with pytest.raises(LinkError, match="runs in real time"):
            link.advance(10)
        # requests from several threads at once: every answer belongs to its request
        errors = []

        def hammer(k):
            try:
                for i in range(30):
                    link.write_parameter(f"19-0{k}", i)
                    assert link.read_parameter(f"19-0{k}") == i
            except Exception as exc:  # noqa: BLE001
                errors.append(exc)

        threads = [threading.Thread(target=hammer, args=(k,)) for k in range(4)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        assert errors == []
    finally:
        drive.stop()


def test_link_timeout_stops_a_running_program_and_says_so(local_link):
    drive = VirtualDrive([1], clock="realtime", timeout_s=0.2, timeout_reaction="stop")
    drive.start()
    try:
        link = local_link(drive)
        link.download(image("main:\nDELAY 10\nGOTO main\n").to_bytes())
        link.start()
        assert link.status().program_state == "running"
        time.sleep(0.6)                                   # the master falls silent
        messages = []
        link.subscribe(lambda e: messages.append(e.text) if e.kind == "message" else None)
        link.flush_events()
        assert link.status().program_state == "break"
        assert any("link timeout" in m and "program was stopped" in m for m in messages)
    finally:
        drive.stop()


def test_install_program_saves_and_starts_it_once(local_link):
    drive = VirtualDrive([3], clock="virtual")
    drive.install_program(3, image('PRINT "up"\n'))
    link = local_link(drive, 3)
    out = []
    link.subscribe(lambda e: out.append(e.text) if e.kind == "print" else None)
    link.advance(5)
    link.flush_events()
    assert out == ["up"]
    assert link.call("list_programs") == [{"number": 0, "name": "p", "autostart": False, "source": False,
                                           "stored_at": ""}]
    with pytest.raises(ValueError, match="no node 4"):
        drive.node(4)


def test_a_remote_link_reports_a_loss_once_and_comes_back_by_itself():
    """A line that comes back (a drive that answers again) restores the link: `alive` and one `connection` event
    per change, while the poller keeps trying."""
    from motiontool.comms.protocol import ConnectionLost

    drive = VirtualDrive([1], clock="virtual")
    down = threading.Event()

    def exchange(message):
        if down.is_set():
            raise ConnectionLost("no answer")
        return drive.node(1).handle_message(message)

    link = RemoteLink(exchange, "flaky", poll_interval_s=0.01)
    events = []
    link.subscribe(lambda e: events.append(e.text) if e.kind == "connection" else None)
    assert link.read_parameter("KPROP") == 30
    down.set()
    with pytest.raises(ConnectionLost):
        link.status()
    time.sleep(0.1)                      # the poller fails a few times more: said once
    assert not link.alive and events == ["Lost connection: no answer"]
    down.clear()
    deadline = time.monotonic() + 5
    while not link.alive and time.monotonic() < deadline:
        time.sleep(0.01)
    assert link.alive and events == ["Lost connection: no answer", "Connection restored"]
    link.close()


def test_events_after_a_drive_restart_are_all_published():
    """A restarted drive numbers its events from 1 again (a new epoch): the master says so once and publishes every
    event of the new drive — also when the new drive has produced more events than the master had seen."""
    drives = [VirtualDrive([1], clock="virtual")]
    link = RemoteLink(lambda message: drives[0].node(1).handle_message(message), "restarting", poll_interval_s=60)
    seen = []
    link.subscribe(lambda e: seen.append(e.text) if e.kind in ("print", "message") else None)
    try:
        link.download(image('PRINT "old 1"\nPRINT "old 2"\n').to_bytes())
        link.start()
        link.advance(20)
        link.flush_events()
        assert seen == ["old 1", "old 2"]
        for count in (2, 9):                  # fewer events than the master saw before, then more
            drives[0] = VirtualDrive([1], clock="virtual")           # a power cycle
            link.download(image("".join(f'PRINT "new {i}"\n' for i in range(count))).to_bytes())
            link.start()
            link.advance(20)
            seen.clear()
            link.flush_events()
            assert seen == ["the controller restarted: its event numbers begin again",
                            *(f"new {i}" for i in range(count))]
    finally:
        link.close()


def test_drive_command_refuses_bad_set_ups_naming_them(tmp_path):
    import io

    from motiontool.controller.drive.command import DriveOptions, run_drive

    bad = tmp_path / "bad.m"
    bad.write_text("POSA\n")
    for options, expected in (
            (DriveOptions(["fc:socket://127.0.0.1:0"], [f"1:{bad}"]), "bad.m:1:1: error: POSA needs more arguments"),
            (DriveOptions(["fc:udp://x"]), "fc listens on socket://HOST:PORT or on pty"),
            (DriveOptions(["modbus:x"]), "unknown scheme 'modbus' (known: canopen:slcan:socket://127.0.0.1:PORT, "
                                         "fc:socket://HOST:PORT | fc:pty"),
            (DriveOptions(["fc:socket://127.0.0.1:0"], ["40"]), "node id 40 is outside 1..32"),
            (DriveOptions(["fc:socket://127.0.0.1:0"], ["1", "1"]), "--node 1 is given twice"),
            (DriveOptions(["fc:socket://127.0.0.1:0#3"]), "a listener serves every node"),
            (DriveOptions(["fc:pty"], clock="sometimes"), "clock 'sometimes'")):
        out, err = io.StringIO(), io.StringIO()
        assert run_drive(options, out, err) == 1
        assert expected in err.getvalue() and out.getvalue() == ""


def test_every_link_takes_requests_from_several_threads():
    """The IDE asks for the status on a worker thread while its window sends commands and a wire link polls events:
    request ids stay unique per link and every answer belongs to its request, on every kind of link."""
    from motiontool.controller.bus import EmbeddedBus

    class Recording(EmbeddedLink):
        def __init__(self):
            super().__init__()
            self.ids = []

        def request(self, request):
            self.ids.append(request.id)
            return super().request(request)

    recording = Recording()
    bus = EmbeddedBus([1, 2])
    for link in (recording, bus.link(2)):
        errors = []

        def hammer(k, link=link, errors=errors):
            try:
                for i in range(200):
                    link.write_parameter(f"19-0{k}", i)
                    link.advance(1)
                    assert link.read_parameter(f"19-0{k}") == i
                    link.status()
            except Exception as exc:  # noqa: BLE001
                errors.append(exc)

        threads = [threading.Thread(target=hammer, args=(k,)) for k in range(4)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        assert errors == []
    assert len(recording.ids) == len(set(recording.ids)) == 4 * 200 * 4


@pytest.mark.parametrize("spec, message", [
    ("fc:socket://127.0.0.1:1#1,poll=0", "option poll=0: give a number from 0.001 to 3600"),
    ("fc:socket://127.0.0.1:1#1,poll=-5", "option poll=-5: give a number from 0.001 to 3600"),
    ("fc:socket://127.0.0.1:1#1,timeout=nan", "option timeout=nan: give a number from 0.001 to 60"),
    ("fc:socket://127.0.0.1:1#1,baud=12", "option baud=12: give a whole number from 300 to 4000000"),
    ("fc:socket://127.0.0.1:1#1,format=3", "option format=3: give a whole number from 1 to 2"),
    ("canopen:slcan:socket://127.0.0.1:1#1,heartbeat=70000", "option heartbeat=70000: give a whole number from 0 to "
                                                             "65535"),
])
def test_link_options_are_refused_out_of_their_range_before_the_port_opens(spec, message):
    with pytest.raises(LinkError, match=re.escape(message)):
        links.open_link(spec)


@pytest.mark.parametrize("damaged", ["request", "answer"])
def test_a_damaged_request_or_answer_is_asked_again_under_the_same_id_and_applied_once(damaged):
    """Issue 24 item 9: a request or an answer damaged on the way failed the operation. It is sent again as the same
    (session, id): the drive applies it once and answers the repeat from its cache."""
    drive = VirtualDrive([1], clock="virtual")
    node = drive.node(1)
    spoiled = []

    def spoil(message: bytes) -> bytes:
        return message[:-1] + bytes([message[-1] ^ 0xFF])   # the last byte of the body: the CRC no longer fits

    def exchange(message: bytes) -> bytes:
        first = not spoiled
        if first and damaged == "request":
            spoiled.append(message)
            message = spoil(message)
        answer = node.handle_message(message)
        if first and damaged == "answer":
            spoiled.append(answer)
            answer = spoil(answer)
        return answer

    handled = []
    handle = node.handle
    node.handle = lambda request: handled.append(request.op) or handle(request)
    link = RemoteLink(exchange, "spoiling", poll_interval_s=60)
    try:
        link.call("events", now=True)    # the session's mark: the next request is the one that gets damaged
        spoiled.clear()
        link.write_parameter("KPROP", 45)
        assert spoiled and link.read_parameter("KPROP") == 45
        assert handled.count("write_parameter") == 1
    finally:
        link.close()


def test_an_answer_damaged_every_time_fails_with_words():
    drive = VirtualDrive([1], clock="virtual")
    node = drive.node(1)

    def exchange(message: bytes) -> bytes:
        answer = node.handle_message(message)
        return answer[:-1] + bytes([answer[-1] ^ 0xFF])

    link = RemoteLink(exchange, "a bad line", poll_interval_s=60)
    try:
        with pytest.raises(LinkError, match=r"events: 4 tries on a bad line, the last gave a damaged answer \(bytes "
                                             r"4-7: checksum mismatch"):
            link.status()
    finally:
        link.close()
