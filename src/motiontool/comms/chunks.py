"""Messages over a half-duplex master/slave transport with small frames: chunking, sequence numbers, dedupe.

Transport-independent (docs/link-protocol.md "Chunks"): the FC link maps a `Frame` onto one telegram
(comms/fc/extension.py); any other bus with a frame of a few bytes can map it onto its own.

The master sends a message (comms/wire.py) as DATA frames and fetches the answer with FETCH frames; the slave
answers every frame (ACK, RESULT chunk, BUSY or ERROR). It is stop-and-wait:

- every new frame has the next sequence number (16 bit); a frame repeated after a lost or damaged answer is
  byte-identical, and the slave answers it from its cache without acting on it again (a lost or repeated
  telegram is never applied twice);
- the chunks of one message carry their index (16 bit) and FIRST/LAST flags: a gap is an ERROR, after which the
  master sends the whole message again (its request id lets the controller side answer a request it already
  applied from its cache, controller/drive/node.py);
- the message's CRC-32 (comms/wire.py) is checked before anything in it is applied.
"""

from __future__ import annotations

import concurrent.futures
import time
from collections.abc import Callable
from dataclasses import dataclass

from motiontool.comms.protocol import LinkError
from motiontool.comms.wire import HEADER, MAX_ANSWER_BYTES, MAX_REQUEST_BYTES

DATA, FETCH = 1, 2                     # master → slave
ACK, RESULT, BUSY, ERROR = 3, 4, 5, 6  # slave → master
OP_NAMES = {DATA: "DATA", FETCH: "FETCH", ACK: "ACK", RESULT: "RESULT", BUSY: "BUSY", ERROR: "ERROR"}
RESTARTS = 3          # whole-message repeats after ERROR answers
BUSY_WAIT_S = 0.005   # first wait after BUSY, doubled up to 0.1 s
MAX_BUSY_S = 60.0     # a slave that answers BUSY for longer than this is hung: the exchange fails


@dataclass(frozen=True)
class Frame:
    seq: int              # 0..65535, the next number for every new frame
    op: int
    first: bool = False
    last: bool = False
    index: int = 0        # chunk index within the message (mod 65536)
    payload: bytes = b""

    def __repr__(self) -> str:
        flags = ("F" if self.first else "") + ("L" if self.last else "")
        return f"Frame(#{self.seq} {OP_NAMES.get(self.op, self.op)}{'/' + flags if flags else ''} " \
               f"i{self.index} {len(self.payload)}B)"


def split(message: bytes, size: int) -> list[bytes]:
    """The chunks of a message, each at most `size` bytes; an empty message is one empty chunk."""
    return [message[i:i + size] for i in range(0, len(message), size)] or [b""]


class MasterChannel:
    """The master's side: `exchange(message) -> answer`; `transfer(frame) -> reply frame` is the transport (it
    repeats a frame on its own timeouts and raises LinkError when the slave does not answer)."""

    def __init__(self, transfer: Callable[[Frame], Frame], max_payload: int, first_seq: int = 0,
                 max_busy_s: float = MAX_BUSY_S):
        self.transfer = transfer
        self.max_payload = max_payload
        self.max_busy_s = max_busy_s
        self.seq = first_seq & 0xFFFF

    def _next(self) -> int:
        self.seq = (self.seq + 1) & 0xFFFF
        return self.seq

    def exchange(self, message: bytes) -> bytes:
        problem = ""
        for _ in range(RESTARTS + 1):
            try:
                return self._exchange_once(message)
            except _Restart as exc:
                problem = str(exc)
        raise LinkError(f"the controller kept refusing the message ({problem})")

    def _exchange_once(self, message: bytes) -> bytes:
        chunks = split(message, self.max_payload)
        reply: Frame | None = None
        for i, chunk in enumerate(chunks):
            last = i == len(chunks) - 1
            reply = self._send(Frame(self._next(), DATA, i == 0, last, i & 0xFFFF, chunk))
            if not last and reply.op != ACK:
                raise _Restart(f"chunk {i}: {OP_NAMES.get(reply.op, reply.op)} instead of ACK")
        assert reply is not None  # split gives an empty message one chunk
        answer = bytearray()
        wait = BUSY_WAIT_S
        index = 0
        busy_since = None
        while True:
            if reply.op == BUSY:
                busy_since = busy_since or time.monotonic()
                if time.monotonic() - busy_since > self.max_busy_s:
                    raise LinkError(f"the controller has answered BUSY for {self.max_busy_s:g} s: it does not "
                                    "finish the request")
                time.sleep(wait)
                wait = min(wait * 2, 0.1)
            elif reply.op == RESULT:
                if reply.first != (index == 0) or reply.index != index & 0xFFFF:
                    raise _Restart(f"answer chunk {reply.index} where {index} was expected")
                if len(answer) + len(reply.payload) > HEADER.size + MAX_ANSWER_BYTES:
                    raise LinkError(f"the controller's answer is longer than {HEADER.size + MAX_ANSWER_BYTES} bytes")
                answer += reply.payload
                index += 1
                if reply.last:
                    return bytes(answer)
            else:
                raise _Restart(f"{OP_NAMES.get(reply.op, reply.op)} while fetching the answer")
            reply = self._send(Frame(self._next(), FETCH, index=index & 0xFFFF))

    def _send(self, frame: Frame) -> Frame:
        reply = self.transfer(frame)
        if reply.op == ERROR:
            raise _Restart(reply.payload.decode("utf-8", "replace") or "ERROR")
        return reply


class _Restart(Exception):
    pass


MAX_MESSAGE = HEADER.size + MAX_REQUEST_BYTES   # the longest request a slave assembles


class SlaveChannel:
    """The slave's side of one master: `on_frame(frame) -> reply`; `handler(message) -> answer` runs once per
    complete message. With `busy_after_s` the handler runs on a worker thread: when it has not answered within
    that time the slave answers BUSY and the master fetches the answer later, so a long request (a big download,
    a long `advance`) never looks like a lost telegram."""

    def __init__(self, handler: Callable[[bytes], bytes], max_payload: int, busy_after_s: float | None = None):
        self.handler = handler
        self.max_payload = max_payload
        self.busy_after_s = busy_after_s
        self._worker: concurrent.futures.ThreadPoolExecutor | None = None
        self._pending: concurrent.futures.Future[bytes] | None = None
        self._last: tuple[Frame, Frame] | None = None     # the last frame and the answer it got
        self._incoming: bytearray | None = None
        self._next_index = 0
        self._outgoing: list[bytes] = []
        self._out_index = 0
        self.repeats = 0                                   # frames answered from the cache (statistics)

    def on_frame(self, frame: Frame) -> Frame:
        if self._last is not None and self._last[0] == frame:
            self.repeats += 1
            return self._last[1]                           # a repeat: answer again, do nothing again
        reply = self._handle(frame)
        self._last = (frame, reply)
        return reply

    def _error(self, frame: Frame, text: str) -> Frame:
        self._incoming = None
        return Frame(frame.seq, ERROR, payload=text.encode("utf-8"))

    def _handle(self, frame: Frame) -> Frame:
        if frame.op == DATA:
            if frame.first:
                self._incoming, self._next_index, self._outgoing = bytearray(), 0, []
            elif self._incoming is None or frame.index != self._next_index & 0xFFFF:
                return self._error(frame, f"chunk {frame.index} out of sequence")
            if len(self._incoming) + len(frame.payload) > MAX_MESSAGE:   # DATA without LAST, forever
                return self._error(frame, f"message longer than {MAX_MESSAGE} bytes")
            self._incoming += frame.payload
            self._next_index += 1
            if not frame.last:
                return Frame(frame.seq, ACK, index=frame.index)
            message, self._incoming = bytes(self._incoming), None
            if self.busy_after_s is None:
                return self._answer(frame, self.handler(message))
            if self._worker is None:
                self._worker = concurrent.futures.ThreadPoolExecutor(1, thread_name_prefix="slave-request")
            self._pending = self._worker.submit(self.handler, message)
            return self._wait(frame, self.busy_after_s)
        if frame.op == FETCH:
            if self._pending is not None:
                return self._wait(frame, 0.0) if frame.index == 0 else self._error(frame, "answer not ready")
            if not self._out_index < len(self._outgoing) or frame.index != self._out_index & 0xFFFF:
                return self._error(frame, f"no answer chunk {frame.index} to fetch")
            return self._result(frame)
        return self._error(frame, f"unknown frame operation {frame.op}")

    def _wait(self, frame: Frame, timeout: float) -> Frame:
        assert self._pending is not None  # called for a request handed to the worker and not yet answered
        try:
            answer = self._pending.result(timeout=timeout)
        except concurrent.futures.TimeoutError:
            return Frame(frame.seq, BUSY)
        self._pending = None
        return self._answer(frame, answer)

    def _answer(self, frame: Frame, answer: bytes) -> Frame:
        self._outgoing, self._out_index = split(answer, self.max_payload), 0
        return self._result(frame)

    def close(self) -> None:
        if self._worker is not None:
            self._worker.shutdown(wait=False, cancel_futures=True)

    def _result(self, frame: Frame) -> Frame:
        i = self._out_index
        self._out_index += 1
        return Frame(frame.seq, RESULT, i == 0, i == len(self._outgoing) - 1, i & 0xFFFF, self._outgoing[i])
