"""APC CAM tables to and from DPL (seed 004 §5.2.4.5 L3435-3697, the examples §6.4.8 and §7.3).

Export writes what the Initial task needs: the arrays (``DIM`` and one assignment per element, as the manual's
examples do, or ``CONST`` arrays in flash) and the matching ``APCCamInitialise*`` / interpolation mode / start /
size / ratio / single-shot calls. `table_program` wraps that in a complete program with a virtual master, to run
a table on the simulator. Import runs a program's Initial task in a sandbox and reads back the arrays and
settings the CAM calls registered, so any DPL that sets up a CAM (the manual's too) becomes a table.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from motiontool.apc import intmath
from motiontool.cameditor.apctable import MODE_ARRAY, MODE_COSINE, ApcCamTable, ApcSegment
from motiontool.dpl.driver import check_source
from motiontool.dpl.runtime import DplRuntime

_MODE_ALIAS = {MODE_ARRAY: "APC_ARRAY_CAM", 0: "APC_LINEAR_CAM", MODE_COSINE: "APC_COSINE_CAM"}


class DplImportError(ValueError):
    """A DPL program that does not set up a CAM (the message says why, GCC style where it is the program's)."""


def array_names(table: ApcCamTable) -> dict[str, str]:
    stem = table.name
    return {"in": f"{stem}In%", "out": f"{stem}Out%", "out2": f"{stem}Out2%", "law": f"{stem}Int%"}


def table_to_dpl(table: ApcCamTable, *, const: bool = False, status: str = "CamStatus%") -> str:
    """The lines of an Initial task that set up `table` (arrays, APCCamInitialise*, mode, start, size, ratio)."""
    names = array_names(table)
    segments = table.segments
    columns = [("in", [s.master for s in segments]), ("out", [s.slave for s in segments])]
    if table.has_slave2:
        columns.append(("out2", [s.slave2 for s in segments]))
    mode = table.mode
    if mode == MODE_ARRAY:
        columns.append(("law", [s.law for s in segments]))
    lines = [f"// APC CAM table '{table.name}' ({len(segments)} segments; one cycle: master {table.master_length}, "
             f"slave {table.slave_travel} counts) - motiontool CAM editor"]
    for key, values in columns:
        name = names[key]
        if const:
            lines.append(f"CONST {name}[{len(values)}] = {{ {', '.join(map(str, values))} }}")
        else:
            lines.append(f"DIM {name}[{len(values)}]")
            lines += [f"{name}[{i}] = {v}" for i, v in enumerate(values)]
    arrays = [names[key] for key, _ in columns]
    initialise = {("in", "out"): "APCCamInitialise1", ("in", "out", "law"): "APCCamInitialise2",
                  ("in", "out", "out2"): "APCCamInitialise3", ("in", "out", "out2", "law"): "APCCamInitialise"}
    call = initialise[tuple(key for key, _ in columns)]
    lines += [f"{status} = {call}({', '.join(arrays)})",
              f"{status} = APCSetCAMInterpolationMode({_MODE_ALIAS[mode]})",
              f"{status} = APCSetCAMStartIndex({table.start})",
              f"{status} = APCSetCAMSize({table.used})",
              f"{status} = APCSetCAMDeltaSegLimit({table.delta_seg_limit})",
              f"{status} = APCSetCAMOutRatioNumerator({table.ratio[0]})",
              f"{status} = APCSetCAMOutRatioDenominator({table.ratio[1]})",
              f"{status} = APCSelectCAMZeroReset()",
              f"{status} = {'APCEnableCAMSingleShot' if table.single_shot else 'APCDisableCAMSingleShot'}()"]
    return "\n".join(lines) + "\n"


def table_program(table: ApcCamTable, *, master_rpm: int = 60, counts_per_rev: int = 65536) -> str:
    """A complete DPL program that runs `table` on the simulator: the table in Initial, a virtual master of
    `master_rpm` (the manual's §6.4.8 counter) fed to the user-program reference, CAM selected at once."""
    return "\n".join([
        "Initial {",
        "RunModeStatus% = APCSetRunMode(APC_DISABLE)",
        "SourceStatus% = APCSetReferenceSource(APC_USER_ENC)",
        "ChannelStatus% = APCSetupOutputChannel(2, 0, 0)",
        "ChannelStatus% = APCEnableOutputChannel()",
        table_to_dpl(table).rstrip("\n"),
        "MasterCounter% = 0",
        "}",
        "Pos0{",
        "RunModeStatus% = APCSetRunMode(APC_ENABLE)",
        "RefStatus% = APCSelectReference(APC_CAM_REF)",
        f"MasterCounter% = MasterCounter% + MULDIV({master_rpm}, {counts_per_rev}, 60000)",
        "UserRefStatus% = APCSetReferencePosition(UnsignedTopWord(MasterCounter%), "
        "UnsignedBottomWord(MasterCounter%), 0)",
        "}",
    ]) + "\n"


@dataclass
class _CamCalls:
    """What the CAM calls set, named as in `_Sandbox.call_dpl`'s table; unset values are the drive's defaults."""

    arrays: dict[str, list[int]] = field(default_factory=dict)
    start: int = 0
    size: int | None = None
    mode: int = 0
    num: int = 1000
    den: int = 1000
    single: bool = False
    limit: int = 256


class _Sandbox:
    """Stands in for the drive while a program's Initial task runs: it answers the language's built-ins and
    records the CAM calls; every other call succeeds and does nothing."""

    def __init__(self) -> None:
        self.cam = _CamCalls()
        self.params = _Parameters()
        self.task = None
        self.pos0 = self.pos1 = None

    def reinit(self) -> None:
        pass

    def tick(self) -> None:
        pass

    def call_dpl(self, name: str, args: tuple, targets: int = 1) -> tuple:
        key = name.upper()
        builtin = {n.upper(): getattr(intmath, n) for n in ("MULDIV", "MULDIVRM", "UnsignedTopWord",
                                                              "SignedTopWord", "UnsignedBottomWord",
                                                              "SignedBottomWord", "PutTopWord", "PutBottomWord")}
        if key in builtin:
            result = builtin[key](*args)
            values = result if isinstance(result, tuple) else (result, 1)
            return values[:targets]
        record = {"APCCAMINITIALISE": ("arrays", lambda a: dict(zip(("in", "out", "out2", "law"), a, strict=True))),
                  "APCCAMINITIALISE1": ("arrays", lambda a: dict(zip(("in", "out"), a, strict=True))),
                  "APCCAMINITIALISE2": ("arrays", lambda a: dict(zip(("in", "out", "law"), a, strict=True))),
                  "APCCAMINITIALISE3": ("arrays", lambda a: dict(zip(("in", "out", "out2"), a, strict=True))),
                  "APCSETCAMSTARTINDEX": ("start", lambda a: a[0]), "APCSETCAMSIZE": ("size", lambda a: a[0]),
                  "APCSETCAMINTERPOLATIONMODE": ("mode", lambda a: a[0]),
                  "APCSETCAMOUTRATIONUMERATOR": ("num", lambda a: a[0]),
                  "APCSETCAMOUTRATIODENOMINATOR": ("den", lambda a: a[0]),
                  "APCENABLECAMSINGLESHOT": ("single", lambda a: True),
                  "APCDISABLECAMSINGLESHOT": ("single", lambda a: False),
                  "APCSETCAMDELTASEGLIMIT": ("limit", lambda a: a[0])}.get(key)
        if record is not None:
            setattr(self.cam, record[0], record[1](args))
        return (1, 1, 1, 1)[:targets]


class _Parameters(dict):
    def read(self, key) -> int:
        return self.get(key, 0)

    def write(self, key, value: int) -> None:
        self[key] = value


def import_dpl(text: str, path: str = "<cam>.dpl", *, name: str | None = None) -> ApcCamTable:
    """The CAM that the Initial task of a DPL program sets up (arrays as they stand at the end of Initial)."""
    checked = check_source(text, path)
    if not checked.ok:
        raise DplImportError("\n".join(d.format() for d in checked.errors))
    sandbox = _Sandbox()
    runtime = DplRuntime(sandbox, checked)
    runtime.start()
    for _ in range(10_000):
        if runtime.state != "initial":
            break
        runtime.slice()
    if runtime.error is not None:
        raise DplImportError(str(runtime.error))
    if runtime.state == "initial":
        raise DplImportError(f"{path}: the Initial task did not end (it waits for something the CAM editor "
                             "cannot give it)")
    cam = sandbox.cam
    arrays = cam.arrays
    if not arrays:
        raise DplImportError(f"{path}: the Initial task calls no APCCamInitialise")
    count = min(len(a) for a in arrays.values())
    laws = arrays.get("law") if cam.mode == MODE_ARRAY else None
    segments = [ApcSegment(arrays["in"][i], arrays["out"][i], laws[i] if laws else max(cam.mode, 0),
                           arrays["out2"][i] if "out2" in arrays else 0) for i in range(count)]
    stem = name or _stem(text, runtime.memory.arrays, arrays["in"])
    try:
        return ApcCamTable(stem, tuple(segments), start=cam.start, size=cam.size,
                           ratio=(cam.num, cam.den), single_shot=cam.single, delta_seg_limit=cam.limit)
    except ValueError as exc:
        raise DplImportError(f"{path}: {exc}") from None


def _stem(text: str, memory: dict[str, list[int]], master: list[int]) -> str:
    """A table name from the master array's name as written: CamIn% → Cam, InArray% → InArray."""
    for key, data in memory.items():
        if data is master:
            written = re.search(rf"\b{re.escape(key[:-1])}(?=%)", text, re.IGNORECASE)
            base = written.group() if written else key[:-1]
            return base[:-2] if base.upper().endswith("IN") and len(base) > 2 else base
    return "Cam"
