"""A program image is validated completely before a controller may run it; a bad one is refused at download with its
byte offset, and a controller never stays "running" after an internal fault (issue 18, item 6; decisions K81).

ProgramImage.from_bytes let TypeError escape on 47 of 3 000 mutated images, and 368 more were accepted and then
failed inside the VM with raw Python messages ("pop from empty list"), leaving the controller "running". The images
here are made the way a corrupted or hand-made file would be: a compiled program, its JSON body edited.
"""

from __future__ import annotations

import json
import zlib

import pytest

from motiontool.aposs.driver import compile_source
from motiontool.aposs.image import MAGIC, Op
from motiontool.comms.protocol import LinkError
from motiontool.controller.embedded import EmbeddedLink

PROGRAM = """DIM arr[4]
long n
double d
n = 3
d = 1.5
arr[2] = n + 1
PRINT "n=", n, " d=", d * 2.0
GOSUB show
SUBMAINPROG
SUBPROG show
  PRINT arr[2]
RETURN
ENDPROG
"""


def body() -> dict:
    return json.loads(zlib.decompress(compile_source(PROGRAM, "p.m").image.to_bytes()[6:]))


def pack(raw: dict | bytes | str) -> bytes:
    text = raw if isinstance(raw, (bytes, str)) else json.dumps(raw, separators=(",", ":"))
    return MAGIC + b"\x01" + zlib.compress(text.encode() if isinstance(text, str) else text)


def download(data: bytes) -> str:
    link = EmbeddedLink()
    try:
        link.download(data, name="p")
    except LinkError as exc:
        assert link.status().program_state == "idle"
        return str(exc)
    finally:
        link.close()
    raise AssertionError("the image was accepted")


def code_at(raw: dict, op: Op) -> int:
    """The index in `code` of the first instruction `op`."""
    return next(i for i in range(0, len(raw["code"]), 2) if raw["code"][i] == op)


def test_a_good_image_runs():
    link = EmbeddedLink()
    events = []
    link.subscribe(events.append)
    link.download(pack(body()), name="p")
    link.start()
    link.advance(50)
    assert [e.text for e in events if e.kind == "print"] == ["n=3 d=3.0", "4"]


def edited(change) -> bytes:
    raw = body()
    change(raw)
    return pack(raw)


def set_code(index_of, value):
    def change(raw):
        raw["code"][index_of(raw)] = value
    return change


@pytest.mark.parametrize(("change", "message"), [
    # stack effects
    (set_code(lambda r: code_at(r, Op.PRINTS), int(Op.POP)), "instruction 10 (POP): pops from an empty operand"),
    (lambda r: r["code"].__setitem__(slice(0, 2), [int(Op.POP), 0]), "instruction 0 (POP): pops from an empty"),
    # operand types
    (lambda r: r["code"].__setitem__(code_at(r, Op.BIND) + 1, 4), "operator mod is not defined on DOUBLE values"),
    (set_code(lambda r: code_at(r, Op.BIND), int(Op.BIN)), "needs a LONG operand, finds a DOUBLE"),
    (set_code(lambda r: code_at(r, Op.PUSHD), int(Op.PUSH)), "instruction 3 (STOREG): needs a DOUBLE operand, "
                                                              "finds a LONG"),
    (set_code(lambda r: code_at(r, Op.ARRDIM), int(Op.PUSH)), "needs a array operand, finds a LONG"),
    # jump targets, program parts, the end of the code
    (lambda r: r["code"].extend([int(Op.JMP), 10 ** 6]), "instruction 27 (JMP): refers to instruction 1000000"),
    (lambda r: r["code"].__setitem__(slice(38, 40), [int(Op.JMP), 21]), "instruction 21 (ARRDIM): reached from "
                                                                       "SUBPROG show but belongs to the main program"),
    (lambda r: r["code"].__setitem__(slice(-2, None), [int(Op.NOP), 0]), "runs past the end of the code"),
    (set_code(lambda r: code_at(r, Op.RETSUB), int(Op.RET)), "returns from a function in SUBPROG show"),
    # tables
    (lambda r: r["calls"].append({"command": "POSA", "argc": 0, "axis": False, "returns": "none"}),
     "calls[0].argc: POSA takes 1 arguments, not 0"),
    (lambda r: r["subprograms"][0].__setitem__("entry", -5), "subprograms[0].entry: -5 is outside the code"),
    (lambda r: r["arrays"].append({"name": "huge", "type": "long", "dims": [10 ** 12]}), "sizes 1 to 1000000"),
    # field types: these raised TypeError
    (lambda r: r["code"].__setitem__(3, "7"), "code[3]: expected an integer"),
    (lambda r: r["code"].__setitem__(0, 1.5), "code[0]: expected an integer"),
    (lambda r: r.__setitem__("globals", {"n": 1}), "globals: expected a list"),
    (lambda r: r["globals"][0].__setitem__("extra", 1), "globals[0]: expected the keys name, type, dims"),
    (lambda r: r.__delitem__("lines"), "body: expected the keys"),
    (lambda r: r["doubles"].__setitem__(0, "1.5"), "doubles[0]: expected a number"),
])
def test_a_bad_image_is_refused_at_download_naming_the_place(change, message):
    text = download(edited(change))
    assert "byte" in text, text
    if message:
        assert message in text, text


def test_the_byte_offset_points_at_the_bad_value():
    raw = body()
    raw["code"][5] = "seven"
    text = json.dumps(raw, separators=(",", ":"))
    message = download(pack(text))
    offset = int(message.split("(byte ")[1].split()[0])
    assert text.encode()[offset:offset + 7] == b'"seven"'


@pytest.mark.parametrize(("data", "message"), [
    (b"MTIMX\x01", "bytes 0-4 are not 'MTIMG'"),
    (MAGIC, "no version byte at offset 5"),
    (MAGIC + b"\x02" + zlib.compress(b"{}"), "version 2 (byte 5)"),
    (MAGIC + b"\x01" + zlib.compress(b"{}")[:-3], "compressed body after byte 6 ends at byte"),
    (MAGIC + b"\x01" + zlib.compress(b"[" * 100_000 + b"]" * 100_000), "nested too deeply"),
    (MAGIC + b"\x01" + zlib.compress(b'{"code": NaN}'), "NaN is not a number"),
    (MAGIC + b"\x01" + zlib.compress(b" " * (300 << 20)), "inflates to more than"),
])
def test_broken_containers_are_refused_with_the_byte_offset(data, message):
    assert message in download(data)


def test_a_controller_never_stays_running_after_an_internal_fault(monkeypatch):
    """A fault of the simulator itself (here: a command implementation that raises) ends the program with error 199
    Internal MCO fault [DG 11403: "199 Internal MCO fault"], even when the program has an ON ERROR handler."""
    from motiontool.kernel import commands

    def broken(controller, vm, args):
        return [][0]
    monkeypatch.setitem(commands.COMMANDS, "DELAY", broken)
    link = EmbeddedLink()
    events = []
    link.subscribe(events.append)
    image = compile_source('ON ERROR GOSUB handler\nPRINT "start"\nDELAY 10\nPRINT "never"\nSUBMAINPROG\n'
                           'SUBPROG handler\nPRINT "handled"\nRETURN\nENDPROG\n', "p.m").image
    link.download(image.to_bytes(), name="p")
    link.start()
    link.advance(100)
    status = link.status()
    assert (status.program_state, status.error) == ("error", 199)
    assert [e.text for e in events if e.kind == "print"] == ["start"]
    assert "error 199: Internal MCO fault" in [e.text for e in events if e.kind == "error"]
    history = link.call("error_history")
    assert history[-1]["number"] == 199 and "IndexError" in history[-1]["detail"]
