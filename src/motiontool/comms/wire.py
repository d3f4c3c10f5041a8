"""The Link's requests and responses as bytes, independent of the transport (docs/link-protocol.md "On the wire").

Every wire link carries the same messages: FC telegrams chunk them (comms/fc/), CANopen SDO domain objects carry
them whole. A message is

    offset 0  version (1)           1 = this layout
    offset 1  kind (1)              'Q' request, 'A' answer
    offset 2  flags (1)             bit 0: body is zlib-compressed
    offset 3  reserved (1)          0
    offset 4  CRC-32 (4, big-endian) of the body as sent (zlib.crc32, as Ethernet and PNG)
    offset 8  body                  JSON, UTF-8 (compressed when that saves bytes)

A request's body is ``{"s": session, "id": n, "op": name, "args": {...}}``: the session (a random 32-bit number the
master picks when it opens the link) and the id together name the request, so the controller side answers a
repeated request from its cache instead of applying it twice. An answer's body is
``{"id": n, "ok": bool, "value": …, "error": text, "en": error number}``.

The checksum covers a whole message, so a download is applied only when every byte of it arrived.
"""

from __future__ import annotations

import json
import struct
import zlib
from typing import Any

from motiontool.comms.protocol import LinkError, Request, Response

VERSION = 1
REQUEST, ANSWER = ord("Q"), ord("A")
FLAG_ZLIB = 0x01
HEADER = struct.Struct(">BBBBI")
COMPRESS_FROM = 96   # bodies shorter than this are sent as they are (zlib's header would eat the gain)
# The largest request body (inflated): a full array memory (1 000 000 values, ~12 MiB of JSON) or a program
# image fits; a few hundred bytes of zlib can no longer make the controller side allocate gigabytes.
MAX_REQUEST_BYTES = 16 << 20
DAMAGED_REQUEST = "damaged request"   # how a controller side begins its answer to a request it could not read
MAX_ANSWER_BYTES = 256 << 20   # answers (scope recordings, uploads) are read by the master, which asked for them


class WireError(LinkError):
    """Bytes that are not a valid message; the text names the byte offset."""


def _pack(kind: int, body: dict[str, Any]) -> bytes:
    raw = json.dumps(body, separators=(",", ":"), ensure_ascii=False).encode("utf-8")
    flags = 0
    if len(raw) >= COMPRESS_FROM:
        packed = zlib.compress(raw, 6)
        if len(packed) < len(raw):
            raw, flags = packed, FLAG_ZLIB
    return HEADER.pack(VERSION, kind, flags, 0, zlib.crc32(raw)) + raw


def _unpack(data: bytes, kind: int, limit: int) -> dict[str, Any]:
    if len(data) < HEADER.size:
        raise WireError(f"message of {len(data)} bytes is shorter than its {HEADER.size}-byte header")
    version, got_kind, flags, _reserved, crc = HEADER.unpack_from(data)
    if version != VERSION:
        raise WireError(f"byte 0: message version {version}, this tool reads version {VERSION}")
    if got_kind != kind:
        raise WireError(f"byte 1: message kind {chr(got_kind)!r} where {chr(kind)!r} was expected")
    if flags & ~FLAG_ZLIB:
        raise WireError(f"byte 2: unknown flags 0x{flags:02x}")
    if len(data) - HEADER.size > limit:
        raise WireError(f"byte 8: a body of {len(data) - HEADER.size} bytes, more than {limit}")
    body = bytes(data[HEADER.size:])
    if zlib.crc32(body) != crc:
        raise WireError(f"bytes 4-7: checksum mismatch over the {len(body)}-byte body (the message is damaged)")
    if flags & FLAG_ZLIB:
        inflater = zlib.decompressobj()
        try:
            body = inflater.decompress(body, limit + 1)   # inflated no further than the limit
        except zlib.error as exc:
            raise WireError(f"byte 8: compressed body does not inflate: {exc}") from None
        if len(body) > limit:
            raise WireError(f"byte 8: the compressed body inflates to more than {limit} bytes")
        if not inflater.eof:
            raise WireError("byte 8: compressed body does not inflate: it ends early")
    try:
        value = json.loads(body.decode("utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise WireError(f"byte 8: body is not JSON: {exc}") from None
    if not isinstance(value, dict):
        raise WireError("byte 8: body is not a JSON object")
    return value


def encode_request(request: Request, session: int = 0) -> bytes:
    return _pack(REQUEST, {"s": session, "id": request.id, "op": request.op, "args": request.args})


def decode_request(data: bytes) -> tuple[Request, int]:
    """(request, session) of a request message; WireError naming the byte offset when it is damaged."""
    body = _unpack(data, REQUEST, MAX_REQUEST_BYTES)
    op, args, rid, session = body.get("op"), body.get("args", {}), body.get("id", 0), body.get("s", 0)
    if not isinstance(op, str) or not isinstance(args, dict) or not isinstance(rid, int) \
            or not isinstance(session, int):
        raise WireError("byte 8: a request needs op (text), args (object), id and s (whole numbers)")
    return Request(op, args, rid), session


def encode_response(response: Response) -> bytes:
    body: dict[str, Any] = {"id": response.id, "ok": response.ok, "value": response.value}
    if not response.ok:
        body["error"], body["en"] = response.error, response.error_number
    return _pack(ANSWER, body)


def decode_response(data: bytes) -> Response:
    body = _unpack(data, ANSWER, MAX_ANSWER_BYTES)
    rid, ok = body.get("id"), body.get("ok")
    if not isinstance(rid, int) or not isinstance(ok, bool):
        raise WireError("byte 8: an answer needs id (whole number) and ok (true/false)")
    return Response(rid, ok, body.get("value"), str(body.get("error", "")), int(body.get("en", 0) or 0))
