"""The Unidrive SP + SM-Applications parameters an APC engineer reads and sets, by menu, with the APC user guide's
names, units, ranges and defaults (seed 004), and the parameter file the IDE's browser saves and restores
(docs/formats/apc-parameters.md; decision A75).

Where the guide prints a table (Table 6-2 drive setup L4638-4647, Tables 6-3 / 11-1 menu 81 L4683-4690 and
L8205-8212, §11.3 menus 90 and 91 L7880-7931) its range and default are used. For the application menus 18, 19, 20
and drive parameters the guide only uses in its programs it prints no range: those take any signed 32-bit value
(the width a DPL program writes, L455-457), as the simulated drive keeps it (apc/driveparams.py)."""

from __future__ import annotations

from dataclasses import dataclass

LONG = (-(2 ** 31), 2 ** 31 - 1)
FORMAT = "motiontool APC parameters"
VERSION = 1


@dataclass(frozen=True)
class ApcParam:
    menu: int
    par: int
    name: str
    units: str = ""
    low: int = LONG[0]
    high: int = LONG[1]
    default: str = ""            # as the guide prints it ("" when it prints none)
    read_only: bool = False
    source: str = ""             # the seed lines

    @property
    def label(self) -> str:
        return f"{self.menu}.{self.par:02d}"

    @property
    def printed_range(self) -> bool:
        return (self.low, self.high) != LONG


def _p(label: str, name: str, units: str = "", rng: tuple[int, int] = LONG, default: str = "", *,
       ro: bool = False, src: str = "") -> ApcParam:
    menu, par = (int(x) for x in label.split("."))
    return ApcParam(menu, par, name, units, rng[0], rng[1], default, ro, src)


_BIT = (0, 1)
_U8 = (0, 255)
_REVS = (0, 65535)
# the drive's own parameters the guide's setup and programs use (Table 6-2 gives values to set, not defaults)
_DRIVE = (
    _p("1.06", "Drive maximum speed (clamps the output channel)", "rpm", src="L4640, L2148"),
    _p("1.07", "Drive minimum speed", "rpm", src="L4641"),
    _p("1.10", "Bipolar reference select", "", src="L4642"),
    _p("1.11", "Reference on (healthy, enabled and run commanded)", "", _BIT, src="L4763-4778, L5273"),
    _p("1.14", "Reference selector (3: preset speed reference)", "", src="L4643, L4269"),
    _p("1.15", "Preset speed reference 1 selected", "", src="L4644"),
    _p("1.21", "Preset speed reference 1 (output channel mode 2)", "0.1 rpm", src="L4257, L4269"),
    _p("2.02", "Drive ramps (0: disabled)", "", src="L4645"),
    _p("2.04", "Ramp mode (0: fast decel ramps)", "", src="L4646"),
    _p("3.22", "Hard speed reference (output channel mode 0)", "0.1 rpm", src="L4255, L4268"),
    _p("3.23", "Hard speed reference select", "", _BIT, src="L4268"),
    _p("3.34", "Drive encoder lines per revolution", "lines", src="L463-469 (decision A74)"),
    _p("3.48", "Drive encoder initialised", "", _BIT, ro=True, src="L434-437"),
    _p("4.11", "Torque mode selector (4: speed and torque)", "", src="L1980"),
    _p("6.01", "Stop mode (2: stop with no ramps)", "", src="L4647"),
)
_MENU81 = (
    _p("81.06", "RS485 port mode (25 CTSync master, 26 CTSync slave)", "", _U8, "1", src="L8207"),
    _p("81.11", "Clock task scheduling rate", "ms", src="L943"),
    _p("81.12", "POS task scheduling rate (1: 0.25 2: 0.5 3: 1 4: 2 5: 4 6: 8 ms; at REINIT)", "", (0, 6), "0",
       src="L4685, L8208"),
    _p("81.13", "Auto-run enable", "", _BIT, "0", src="L4686, L8209"),
    _p("81.14", "Global trip enable", "", _BIT, "0", src="L4687"),
    _p("81.16", "Encoder data update rate (0: 0.25 ms 1: POS task 2: Clock task 3: never)", "", (0, 3), "0",
       src="L4688, L8210"),
    _p("81.17", "Parameter overrange trip enable", "", _BIT, "0", src="L4689"),
    _p("81.20", "Save PLC registers on power down", "", _BIT, src="§7.1 Initial"),
    _p("81.38", "Drive trip on APC runtime error (Tr81)", "", _BIT, "0", src="L4690, L8211"),
    _p("81.42", "Pass digital input 0 through to the freeze counters", "", _BIT, "0", src="L8212, L1076"),
    _p("81.43", "Freeze edge (0: rising 1: falling)", "", _BIT, src="L1076"),
)
_MENU90 = (
    _p("90.01", "Feedback encoder position", "counts", ro=True, default="NA", src="L7883"),
    _p("90.02", "Feedback encoder rev count", "revs", _REVS, "NA", ro=True, src="L7884"),
    _p("90.03", "Reference encoder position", "counts", ro=True, default="NA", src="L7885"),
    _p("90.04", "Reference encoder rev count", "revs", _REVS, "NA", ro=True, src="L7886"),
    _p("90.18", "Feedback encoder freeze flag", "", _BIT, "0", ro=True, src="L7887, L1080-1084"),
    _p("90.19", "Feedback encoder freeze position", "counts", ro=True, default="NA", src="L7888"),
    _p("90.21", "Disable drive encoder position check", "", _BIT, "0", src="L7890"),
    _p("90.25", "Feedback encoder marker position", "counts", ro=True, default="NA", src="L7893"),
    _p("90.28", "Reference encoder freeze flag", "", _BIT, "0", ro=True, src="L7895, L1080-1084"),
    _p("90.29", "Reference encoder freeze position", "counts", ro=True, default="NA", src="L7896"),
    _p("90.35", "Reference encoder marker position", "counts", ro=True, default="NA", src="L7902"),
    _p("90.41", "Reference encoder marker flag", "", _BIT, "0", ro=True, src="L7906"),
    _p("90.42", "Feedback encoder marker flag", "", _BIT, "0", ro=True, src="L7907"),
    _p("90.43", "Reference encoder source (0 drive, 1-3 slot, 4 user program, 5 none)", "", (0, 5), "0",
       src="L7913"),
    _p("90.44", "Feedback encoder source (0 drive, 1-3 slot, 4 user program, 5 none)", "", (0, 5), "0",
       src="L7914"),
    _p("90.45", "Reference marker flag enable", "", _BIT, "0", src="L7915"),
    _p("90.46", "Feedback marker flag enable", "", _BIT, "0", src="L7916"),
    _p("90.47", "Reference freeze enable", "", _BIT, "0", src="L7917"),
    _p("90.48", "Feedback freeze enable", "", _BIT, "0", src="L7918"),
    _p("90.49", "APC runtime error ID (1-4: CAM errors)", "", (0, 4), "0", ro=True, src="L7919"),
)
_MENU91 = (
    _p("91.01", "Shortcut enable", "", _U8, "0", src="L7921"),
    _p("91.02", "Speed setpoint", "0.001 rpm", default="0", src="L7922"),
    _p("91.03", "Hard speed reference", "0.001 rpm", default="0", src="L7923"),
    _p("91.04", "Torque reference (with 4.11 = 4)", "%", src="L1980"),
    _p("91.05", "Maximum speed clamp", "rpm", default="0", src="L7924"),
    _p("91.06", "Speed feedback", "0.01 rpm", default="NA", ro=True, src="L7925"),
    _p("91.17", "Number of valid CTSync messages", "", default="0", ro=True, src="L7926"),
    _p("91.18", "Number of invalid CTSync messages", "", default="0", ro=True, src="L7927"),
    _p("91.19", "Number of missing CTSync messages", "", default="0", ro=True, src="L7928"),
    _p("91.21", "Inter-option module synchronisation control", "", _U8, "0", src="L7930"),
    _p("91.22", "Inter-option module synchronisation status", "", _U8, "NA", ro=True, src="L7931"),
)
# what the guide's programs use an application parameter for (each program gives it its own meaning)
_USES = {
    "18.11": "position setpoint, 0.1 rev (§7.1-§7.6, L5068; §7.7 speed setpoint, 0.1 rpm, L6609)",
    "18.12": "actual position, 0.1 rev (L5509; §7.7 proportional gain, L6652)",
    "18.13": "speed setpoint, 0.1 rpm (§6.4, L4873)",
    "18.15": "CAM index (§6.4, L4924)",
    "18.16": "virtual master speed, rpm (§6.4, L4946)",
    "18.17": "digital lock ratio numerator (§6.4, L4977)",
    "18.18": "digital lock ratio denominator (§6.4, L4978)",
    "18.31": "absolute position mode (L5086)",
    "18.32": "enables digital lock / CAM / homing (L5248, L5487, L5807)",
    "18.33": "CAM reference / reverse profile (L4933, L5493)",
    "18.34": "single-shot CAM cycle (L4940, L5499)",
    "18.35": "digital lock reference (§6.4, L4992)",
    "18.36": "digital lock ratio update (§6.4, L4982)",
}


def _application(menu: int) -> tuple[ApcParam, ...]:
    out = []
    for par in range(1, 51):
        label = f"{menu}.{par:02d}"
        kind = "Application integer" if menu == 20 or par <= 30 else "Application bit"
        use = _USES.get(label)
        out.append(_p(label, f"{kind}: {use}" if use else kind, src="used in the guide's programs" if use else ""))
    return tuple(out)


MENUS: tuple[tuple[str, tuple[ApcParam, ...]], ...] = (
    ("Menus 1-6 Drive", _DRIVE),
    ("Menu 18 Application 1", _application(18)),
    ("Menu 19 Application 2", _application(19)),
    ("Menu 20 Application 3", _application(20)),
    ("Menu 81 SM-Applications setup", _MENU81),
    ("Menu 90 Encoder views", _MENU90),
    ("Menu 91 Fast access", _MENU91),
)
PARAMETERS: dict[str, ApcParam] = {p.label: p for _title, params in MENUS for p in params}


def parameter(text: str) -> ApcParam:
    """The parameter `text` names ("18.11", "#18.11", "18.011" is refused), else ValueError."""
    raw = text.strip().lstrip("#")
    menu, dot, par = raw.partition(".")
    key = f"{int(menu)}.{int(par):02d}" if dot and menu.isdigit() and par.isdigit() and len(par) <= 2 else raw
    if key not in PARAMETERS:
        raise ValueError(f"{text.strip()!r} is not a parameter of the APC browser (menus 1-6, 18-20, 81, 90, 91)")
    return PARAMETERS[key]


def checked(p: ApcParam, text: str) -> int:
    """The integer a typed value means, checked against the parameter; ValueError with the reason."""
    value = text.strip()
    if p.read_only:
        raise ValueError(f"#{p.label} {p.name} is read only")
    try:
        number = int(value, 0)
    except ValueError:
        raise ValueError(f"#{p.label} {p.name}: {value!r} is not a whole number") from None
    if not p.low <= number <= p.high:
        raise ValueError(f"#{p.label} {p.name}: {number} is outside {p.low} .. {p.high}")
    return number


def dump(values: dict[str, int]) -> str:
    """The parameter file: the header with the version, `menu.par = value ; name` in browser order, `end`."""
    lines = [f"{FORMAT} {VERSION}"]
    for label, p in PARAMETERS.items():
        if label in values and not p.read_only:
            lines.append(f"{label} = {values[label]} ; {p.name}")
    return "\n".join([*lines, "end"]) + "\n"


def load(text: str, where: str) -> dict[str, int]:
    """The values of a parameter file; ValueError "WHERE:LINE: reason" for the first bad line (nothing is taken)."""
    lines = text.splitlines()
    head = lines[0].strip() if lines else ""
    name, _, version = head.rpartition(" ")
    if name == FORMAT and version.isdigit() and int(version) > VERSION:
        raise ValueError(f"{where}:1: APC parameter file version {version} is newer than this motiontool reads "
                         f"(version {VERSION})")
    if head != f"{FORMAT} {VERSION}":
        found = head[:60] or "an empty file"
        raise ValueError(f"{where}:1: not an APC parameter file (expected '{FORMAT} {VERSION}', found {found!r})")
    values: dict[str, int] = {}
    for number, line in enumerate(lines[1:], start=2):
        body = line.split(";", 1)[0].strip()
        if body == "end":
            if any(rest.split(";", 1)[0].strip() for rest in lines[number:]):
                raise ValueError(f"{where}:{number + 1}: nothing may follow 'end'")
            return values
        if not body:
            continue
        label, eq, value = body.partition("=")
        try:
            if not eq:
                raise ValueError(f"{body[:40]!r}: write menu.par = value")
            p = parameter(label)
            if p.label in values:
                raise ValueError(f"#{p.label} is given twice")
            values[p.label] = checked(p, value)
        except ValueError as exc:
            raise ValueError(f"{where}:{number}: {exc}") from None
    raise ValueError(f"{where}:{len(lines)}: the file ends without 'end' (cut short?); nothing was taken")
