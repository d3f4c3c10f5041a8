"""The program image: what the compiler produces and a controller executes (docs/formats/program-image.md).

A stack machine: `code` is a flat list [op, arg, op, arg, …]; pc counts instructions (pc*2 indexes `code`).
The image is versioned and serialised as ``MTIMG`` + version byte + zlib-compressed JSON.
"""

from __future__ import annotations

import json
import re
import zlib
from dataclasses import asdict, dataclass, field, fields

from motiontool.aposs.opcodes import (  # noqa: F401 - the image's vocabulary, imported from here by its users
    BINOP_OF,
    MATH_FUNCTIONS,
    OPERATOR_OF,
    PSEUDO_ARRAYS,
    SELECTOR_CODES,
    BinOp,
    ImageError,
    Op,
)
from motiontool.aposs.verify import verify

MAGIC = b"MTIMG"
FORMAT_VERSION = 1

MAX_IMAGE_BYTES = 64 << 20   # a compressed image (decisions R4)
MAX_BODY_BYTES = 96 << 20    # its inflated JSON, inflated no further: a 16 MiB program (the source limit) makes
                             # some 90 MiB; parsing 250 MB took 3.8 GB (decisions R16)


@dataclass
class Variable:
    name: str
    type: str                   # "long" | "double"
    dims: list[int] = field(default_factory=list)  # [] scalar, [n] or [rows, cols] array


@dataclass
class Function:
    name: str
    type: str
    entry: int                  # pc
    params: list[Variable]      # array parameters have dims [0]
    locals: list[Variable]      # params first, then declared locals (and hidden temporaries)


@dataclass
class Subprogram:
    name: str
    entry: int


@dataclass
class CommandCall:
    command: str                # the command's name in the command table, e.g. "POSA", "MOTOR ON"
    argc: int
    axis: bool                  # an axis designator x(n) was pushed before the arguments
    returns: str                # "none" | "long" | "double"


@dataclass
class Interrupt:
    kind: str                   # ERROR INT APOS IPOS MAPOS MCPOS MIPOS POSITION PERIOD TIME COMBIT STATBIT ...
    sign: int                   # +1 / -1 for position interrupts
    subprogram: int             # index into subprograms, -1 for SETOUT forms
    has_value: bool
    setout: bool
    toin: bool
    delete: bool


@dataclass
class LineEntry:
    pc: int
    file: int                   # index into files
    line: int
    col: int


@dataclass
class ProgramImage:
    name: str
    debug: bool = False
    code: list[int] = field(default_factory=list)
    doubles: list[float] = field(default_factory=list)
    strings: list[str] = field(default_factory=list)
    globals: list[Variable] = field(default_factory=list)       # scalars by slot
    arrays: list[Variable] = field(default_factory=list)        # global variable arrays (long a[10])
    dims: list[Variable] = field(default_factory=list)          # DIM arrays in DIM order
    functions: list[Function] = field(default_factory=list)
    subprograms: list[Subprogram] = field(default_factory=list)
    calls: list[CommandCall] = field(default_factory=list)
    interrupts: list[Interrupt] = field(default_factory=list)
    loops: list[list[int]] = field(default_factory=list)        # [counter global slot, target pc]
    files: list[str] = field(default_factory=list)
    lines: list[LineEntry] = field(default_factory=list)        # sorted by pc: the source of each statement
    version: int = FORMAT_VERSION

    def __len__(self) -> int:
        return len(self.code) // 2

    def line_of(self, pc: int) -> LineEntry | None:
        """The statement that instruction pc belongs to."""
        lo, hi, found = 0, len(self.lines) - 1, None
        while lo <= hi:
            mid = (lo + hi) // 2
            if self.lines[mid].pc <= pc:
                found, lo = self.lines[mid], mid + 1
            else:
                hi = mid - 1
        return found

    # --- serialisation ------------------------------------------------------------------------------
    def to_bytes(self) -> bytes:
        payload = json.dumps(asdict(self), separators=(",", ":"), allow_nan=False).encode("utf-8")
        return MAGIC + bytes([FORMAT_VERSION]) + zlib.compress(payload, 9)

    @classmethod
    def from_bytes(cls, data: bytes, max_body: int = MAX_BODY_BYTES) -> ProgramImage:
        """Read and completely validate an image (aposs/verify.py); ImageError names the byte offset. `max_body`:
        the most its JSON may inflate to (a controller's program memory is smaller than a file's limit)."""
        if data[:5] != MAGIC:
            raise ImageError("not a motiontool program image: bytes 0-4 are not 'MTIMG'")
        if len(data) < 6:
            raise ImageError("truncated program image: no version byte at offset 5")
        if data[5] != FORMAT_VERSION:
            raise ImageError(f"program image version {data[5]} (byte 5) is not supported; "
                             f"this motiontool reads version {FORMAT_VERSION}")
        if len(data) > MAX_IMAGE_BYTES:
            raise ImageError(f"program image of {len(data)} bytes: more than {MAX_IMAGE_BYTES}")
        inflate = zlib.decompressobj()
        try:
            body = inflate.decompress(data[6:], max_body)
            if inflate.unconsumed_tail:
                raise ImageError(f"the body after byte 6 inflates to more than {max_body} bytes")
            if not inflate.eof:
                raise ImageError(f"truncated program image: the compressed body after byte 6 ends at byte {len(data)}")
            if inflate.unused_data:
                raise ImageError(f"{len(inflate.unused_data)} bytes after the compressed body "
                                 f"(from byte {len(data) - len(inflate.unused_data)})")
            text = body.decode("utf-8")
            raw = json.loads(text, parse_constant=_no_constant)
        except zlib.error as exc:
            raise ImageError(f"corrupt program image body after byte 6: {exc}") from None
        except UnicodeDecodeError as exc:
            raise ImageError(f"program image body: not UTF-8 at byte {exc.start} of the inflated body") from None
        except json.JSONDecodeError as exc:
            raise ImageError(f"program image body: {exc.msg} at byte {exc.pos} of the inflated body") from None
        except ValueError as exc:  # an integer of thousands of digits
            raise ImageError(f"program image body: {exc}") from None
        except RecursionError:
            raise ImageError("program image body nested too deeply") from None
        try:
            image = _decode(raw)
            image.validate()
        except ImageError as exc:
            where = _offset(text, exc.field) if exc.field else None
            suffix = f" (byte {where} of the inflated body)" if where is not None else ""
            raise ImageError(f"{exc}{suffix}", exc.field) from None
        return image

    def validate(self) -> None:
        """Refuse an image a controller cannot run safely (aposs/verify.py: tables, stack effects, operand types,
        jump targets)."""
        verify(self)


# --- reading: every field with its type, nothing else --------------------------------------------------------------
def _no_constant(name: str):
    raise ImageError(f"program image body: {name} is not a number")


def _need(ok: bool, path: str, what: str) -> None:
    if not ok:
        raise ImageError(f"{path}: expected {what}", path)


def _exactly(kind: type, what: str):
    """A reader of one JSON value of exactly this type (1 is not true, true is not 1, 1.0 is not 1)."""
    def read(value, path: str):
        _need(type(value) is kind, path, what)
        return value
    return read


_int, _str, _bool, _list = (_exactly(int, "an integer"), _exactly(str, "a text"), _exactly(bool, "true or false"),
                            _exactly(list, "a list"))


def _obj(value, path: str, keys: tuple[str, ...]) -> dict:
    _need(type(value) is dict, path, "an object")
    _need(set(value) == set(keys), path, "the keys " + ", ".join(keys))
    return value


def _variable(value, path: str) -> Variable:
    v = _obj(value, path, ("name", "type", "dims"))
    return Variable(_str(v["name"], path + ".name"), _str(v["type"], path + ".type"),
                    [_int(d, f"{path}.dims[{k}]") for k, d in enumerate(_list(v["dims"], path + ".dims"))])


def _code(code) -> list[int]:
    if type(code) is list and all(type(x) is int for x in code):  # the usual case, at C speed
        return code
    return [_int(x, f"code[{k}]") for k, x in enumerate(_list(code, "code"))]


def _items(raw: dict, key: str, decode) -> list:
    return [decode(item, f"{key}[{k}]") for k, item in enumerate(_list(raw[key], key))]


def _decode(raw) -> ProgramImage:
    raw = _obj(raw, "body", tuple(f.name for f in fields(ProgramImage)))
    _need(raw["version"] == FORMAT_VERSION and type(raw["version"]) is int, "version", f"{FORMAT_VERSION}")

    def function(value, path):
        f = _obj(value, path, ("name", "type", "entry", "params", "locals"))
        return Function(_str(f["name"], path + ".name"), _str(f["type"], path + ".type"),
                        _int(f["entry"], path + ".entry"),
                        _items(f, "params", lambda v, p: _variable(v, path + "." + p)),
                        _items(f, "locals", lambda v, p: _variable(v, path + "." + p)))

    def subprogram(value, path):
        s = _obj(value, path, ("name", "entry"))
        return Subprogram(_str(s["name"], path + ".name"), _int(s["entry"], path + ".entry"))

    def call(value, path):
        c = _obj(value, path, ("command", "argc", "axis", "returns"))
        return CommandCall(_str(c["command"], path + ".command"), _int(c["argc"], path + ".argc"),
                           _bool(c["axis"], path + ".axis"), _str(c["returns"], path + ".returns"))

    def interrupt(value, path):
        i = _obj(value, path, ("kind", "sign", "subprogram", "has_value", "setout", "toin", "delete"))
        return Interrupt(_str(i["kind"], path + ".kind"), _int(i["sign"], path + ".sign"),
                         _int(i["subprogram"], path + ".subprogram"), *(_bool(i[k], f"{path}.{k}") for k in (
                             "has_value", "setout", "toin", "delete")))

    def loop(value, path):
        pair = _list(value, path)
        _need(len(pair) == 2, path, "[counter slot, target pc]")
        return [_int(pair[0], path + "[0]"), _int(pair[1], path + "[1]")]

    def line(value, path):
        e = _obj(value, path, ("pc", "file", "line", "col"))
        return LineEntry(*(_int(e[k], f"{path}.{k}") for k in ("pc", "file", "line", "col")))

    def double(value, path):
        _need(type(value) in (int, float), path, "a number")
        return float(value)

    return ProgramImage(
        name=_str(raw["name"], "name"), debug=_bool(raw["debug"], "debug"), code=_code(raw["code"]),
        doubles=_items(raw, "doubles", double), strings=_items(raw, "strings", _str),
        globals=_items(raw, "globals", _variable), arrays=_items(raw, "arrays", _variable),
        dims=_items(raw, "dims", _variable), functions=_items(raw, "functions", function),
        subprograms=_items(raw, "subprograms", subprogram), calls=_items(raw, "calls", call),
        interrupts=_items(raw, "interrupts", interrupt), loops=_items(raw, "loops", loop),
        files=_items(raw, "files", _str), lines=_items(raw, "lines", line), version=raw["version"])


def _offset(text: str, field: str) -> int | None:
    """The byte offset in the inflated body where the value at ``field`` (``functions[2].entry``) starts."""
    if field == "body":
        return 0
    path = re.findall(r"\.?([A-Za-z_]+)|\[(\d+)\]", field)
    try:
        pos = _JsonCursor(text).find([name if name else int(number) for name, number in path])
    except (ValueError, IndexError, RecursionError):
        return None
    return len(text[:pos].encode("utf-8")) if pos is not None else None


class _JsonCursor:
    """Finds where a value sits in JSON text without building it (only on the error path)."""

    _SCALAR = re.compile(r'"(?:[^"\\]|\\.)*"|[^,\]\}\s]+')

    def __init__(self, text: str):
        self.text = text

    def _ws(self, i: int) -> int:
        while i < len(self.text) and self.text[i] in " \t\r\n":
            i += 1
        return i

    def _skip(self, i: int) -> int:
        """The position after the value starting at i."""
        i = self._ws(i)
        c = self.text[i]
        if c in "[{":
            close = "]" if c == "[" else "}"
            i = self._ws(i + 1)
            while self.text[i] != close:
                if c == "{":
                    i = self._ws(self._skip(i))  # the key
                    i = self._ws(i + 1)           # the ':'
                i = self._ws(self._skip(i))
                if self.text[i] == ",":
                    i = self._ws(i + 1)
            return i + 1
        m = self._SCALAR.match(self.text, i)
        if m is None:  # no value here ('}' or ']' already): the caller then gives no offset
            raise ValueError(f"no JSON value at {i}")
        return m.end()

    def find(self, path: list, i: int = 0) -> int | None:
        i = self._ws(i)
        for step in path:
            c = self.text[i]
            if isinstance(step, int) and c == "[":
                i = self._ws(i + 1)
                for _ in range(step):
                    i = self._ws(self._skip(i))
                    i = self._ws(i + 1)  # the ','
            elif isinstance(step, str) and c == "{":
                i = self._ws(i + 1)
                while self.text[i] != "}":
                    key_end = self._skip(i)
                    key = self.text[i + 1:key_end - 1]
                    i = self._ws(self._ws(key_end) + 1)
                    if key == step:
                        break
                    i = self._ws(self._skip(i))
                    if self.text[i] == ",":
                        i = self._ws(i + 1)
                else:
                    return None
            else:
                return None
        return i
