"""Link messages as bytes (comms/wire.py) and their chunked stop-and-wait transfer (comms/chunks.py): what every wire
link relies on — a damaged message is never decoded, a repeated frame or request is never applied twice."""

import contextlib
import random
import zlib

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from motiontool.comms import chunks, wire
from motiontool.comms.protocol import LinkError, Request, Response


def test_request_and_answer_round_trip():
    request = Request("write_parameter", {"key": "KPROP", "value": 50}, 7)
    data = wire.encode_request(request, session=1234)
    assert data[:4] == bytes((1, ord("Q"), 0, 0))
    assert wire.decode_request(data) == (request, 1234)
    answer = Response(7, False, None, "error 183: too big", 183)
    assert wire.decode_response(wire.encode_response(answer)) == answer
    ok = Response(8, True, {"values": [1.5, -2, None], "text": "ü"})
    assert wire.decode_response(wire.encode_response(ok)) == ok


def test_long_bodies_are_compressed_and_checked():
    image = "A" * 5000
    data = wire.encode_request(Request("download", {"image": image, "number": None, "name": "x"}, 1))
    assert data[2] == wire.FLAG_ZLIB and len(data) < 200
    assert int.from_bytes(data[4:8], "big") == zlib.crc32(data[8:])
    assert wire.decode_request(data)[0].args["image"] == image


def test_damage_is_found_and_named_by_byte_offset():
    data = bytearray(wire.encode_request(Request("status", {}, 3)))
    for offset, expected in ((0, "byte 0: message version"), (1, "byte 1: message kind"), (2, "byte 2: unknown flags"),
                             (5, "bytes 4-7: checksum mismatch"), (len(data) - 1, "bytes 4-7: checksum mismatch")):
        damaged = bytearray(data)
        damaged[offset] ^= 0x40
        with pytest.raises(wire.WireError, match=expected):
            wire.decode_request(bytes(damaged))
    with pytest.raises(wire.WireError, match="shorter than its 8-byte header"):
        wire.decode_request(bytes(data[:5]))
    with pytest.raises(wire.WireError, match="checksum"):
        wire.decode_request(bytes(data[:-1]))   # a truncated download is never applied


@given(st.binary(max_size=200))
def test_decoders_only_raise_wire_errors(data):
    for decode in (wire.decode_request, wire.decode_response):
        with contextlib.suppress(wire.WireError):
            decode(data)


# --- chunks -------------------------------------------------------------------------------------------------
class LossyWire:
    """A transfer with retries whose frames get lost, duplicated or answered late, at random (seeded)."""

    def __init__(self, slave, seed, loss=0.1, duplicate=0.1):
        self.slave, self.rng, self.loss, self.duplicate = slave, random.Random(seed), loss, duplicate
        self.frames = 0

    def transfer(self, frame):
        for _ in range(50):
            self.frames += 1
            if self.rng.random() < self.loss:
                continue                                  # the request is lost: the master times out, repeats
            reply = self.slave.on_frame(frame)
            if self.rng.random() < self.duplicate:
                reply = self.slave.on_frame(frame)        # a repeated telegram: answered again, not re-applied
            if self.rng.random() < self.loss:
                continue                                  # the answer is lost: the master repeats the same frame
            return reply
        raise LinkError("no answer")


@pytest.mark.parametrize("seed", range(20))
def test_every_message_is_handled_exactly_once_despite_losses_and_repeats(seed):
    handled = []

    def handler(message):
        handled.append(message)
        return message[::-1] * 3

    slave = chunks.SlaveChannel(handler, max_payload=16)
    lossy = LossyWire(slave, seed)
    master = chunks.MasterChannel(lossy.transfer, max_payload=16, first_seq=seed * 1000)
    rng = random.Random(seed)
    messages = [bytes(rng.getrandbits(8) for _ in range(rng.randrange(0, 100))) for _ in range(30)]
    for m in messages:
        assert master.exchange(m) == m[::-1] * 3
    assert handled == messages


def test_a_gap_restarts_the_message_and_a_slow_handler_answers_busy():
    calls = []

    def slow(message):
        calls.append(message)
        import time
        time.sleep(0.05)
        return b"done"

    slave = chunks.SlaveChannel(slow, max_payload=4, busy_after_s=0.01)
    replies = []

    def transfer(frame):
        reply = slave.on_frame(frame)
        replies.append(reply.op)
        return reply

    master = chunks.MasterChannel(transfer, max_payload=4)
    assert master.exchange(b"0123456789") == b"done"
    assert calls == [b"0123456789"]
    assert chunks.BUSY in replies and replies[-1] == chunks.RESULT
    # a chunk out of sequence is refused with ERROR
    error = slave.on_frame(chunks.Frame(999, chunks.DATA, first=False, index=5, payload=b"x"))
    assert error.op == chunks.ERROR and b"out of sequence" in error.payload
    slave.close()


def test_a_slave_that_keeps_refusing_ends_in_a_clear_error():
    master = chunks.MasterChannel(lambda f: chunks.Frame(f.seq, chunks.ERROR, payload=b"no room"), 8)
    with pytest.raises(LinkError, match="kept refusing the message \\(no room\\)"):
        master.exchange(b"abc")


@settings(max_examples=50, deadline=None)
@given(st.lists(st.binary(max_size=60), min_size=1, max_size=5), st.integers(1, 20), st.integers(0, 2**16 - 1))
def test_chunking_reassembles_any_messages(messages, size, first_seq):
    slave = chunks.SlaveChannel(lambda m: m + b"!", size)
    master = chunks.MasterChannel(slave.on_frame, size, first_seq)
    for m in messages:
        assert master.exchange(m) == m + b"!"
