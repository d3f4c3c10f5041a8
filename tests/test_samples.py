"""The sample programs of File → Sample (resources/samples/*.m) compile cleanly and run as their headers say.

Every sample starts with a comment header:

    // Title: …                 (required)
    // Shows: …                 (required)
    // Run: motiontool run …    (required)
    // Test-inputs: 3=1@500 …   inputs the test schedules (N=V@T, T in ms)
    // Test-settings: NAME=V …  parameters written before the start
    // Test-seconds: 10         how long the test runs the program
    // Expect: …                one line per expected PRINT line, in order
    // Expect-errors: 111 …     controller errors the program provokes (and handles), in order
    // Expect-warnings: INKEY …  commands the simulator serves only in part (aposs/simulated.py): their warning,
    //                           and no other diagnostic, is expected
    // Expect-end: ended | running

The simulated controller is deterministic, so the PRINT output is compared exactly.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

import pytest

from motiontool.aposs.driver import compile_source
from motiontool.aposs.simulated import unserved_note
from motiontool.comms.protocol import LinkEvent
from motiontool.controller.embedded import EmbeddedLink

SAMPLES_DIR = Path(__file__).resolve().parent.parent / "resources" / "samples"
SAMPLES = sorted(SAMPLES_DIR.glob("*.m"))

_HEADER = re.compile(r"^//\s*([A-Za-z][A-Za-z-]*):\s?(.*)$")
_INPUT = re.compile(r"^(\d+)=(-?\d+)(?:@(\d+))?$")
_NAME = re.compile(r"^\d\d_[a-z0-9_]+\.m$")

# Known simulator bugs found by the samples: file name → reason (the test is then a strict xfail).
KNOWN_BUGS: dict[str, str] = {}


@dataclass
class Header:
    fields: dict[str, str] = field(default_factory=dict)
    expect: list[str] = field(default_factory=list)
    expect_errors: list[int] | None = None
    expect_warnings: set[str] = field(default_factory=set)
    inputs: list[tuple[int, int, int]] = field(default_factory=list)
    settings: list[tuple[str, int]] = field(default_factory=list)
    seconds: float = 20.0
    expect_end: str | None = None


def parse_header(path: Path) -> Header:
    """Read the leading `// Key: value` comment lines (the header ends at the first other line)."""
    header = Header()
    for line in path.read_text(encoding="utf-8").splitlines():
        m = _HEADER.match(line.strip())
        if not m:
            if line.strip() in ("", "//"):
                continue
            break
        key, value = m.group(1).lower(), m.group(2).rstrip()
        if key == "expect":
            header.expect.append(value)
        elif key == "expect-errors":
            header.expect_errors = [int(v) for v in value.split()]
        elif key == "expect-warnings":
            header.expect_warnings = set(value.split())
        elif key == "test-inputs":
            for spec in value.split():
                im = _INPUT.match(spec)
                assert im, f"{path.name}: bad Test-inputs entry {spec!r}"
                header.inputs.append((int(im.group(1)), int(im.group(2)), int(im.group(3) or 0)))
        elif key == "test-settings":
            for spec in value.split():
                name, _, number = spec.partition("=")
                header.settings.append((name, int(number, 0)))
        elif key == "test-seconds":
            header.seconds = float(value)
        elif key == "expect-end":
            header.expect_end = value.strip()
        else:
            header.fields[key] = value
    return header


@dataclass
class Outcome:
    prints: list[str]
    errors: list[int]
    state: str


def run_sample(path: Path, header: Header, uptime_ms: int = 0) -> Outcome:
    """Run the sample as its header says; `uptime_ms`: the controller's clock (TIME) at the download, i.e. how
    long it has been up (tests/test_samples_uptime.py). Test-inputs times count from then."""
    result = compile_source(path=path)
    assert result.ok and result.image is not None, [d.format() for d in result.diagnostics]
    link = EmbeddedLink()
    link.service.controller.time_ms = uptime_ms
    prints: list[str] = []
    errors: list[int] = []

    def on_event(event: LinkEvent) -> None:
        if event.kind == "print":
            prints.append(event.text)
        elif event.kind == "error":
            errors.append(event.number)

    link.subscribe(on_event)
    try:
        for name, value in header.settings:
            link.write_parameter(name, value)
        for number, value, at in header.inputs:
            link.call("schedule_input", number=number, value=value, time_ms=uptime_ms + at)
        link.download(result.image.to_bytes())
        link.start()
        remaining = int(header.seconds * 1000)
        while remaining > 0 and link.status().program_state == "running":
            step = min(500, remaining)
            link.advance(step)
            remaining -= step
        state = link.status().program_state
    finally:
        link.close()
    return Outcome(prints, errors, state)


def _params(with_bugs: bool = False):
    for path in SAMPLES:
        marks = []
        if with_bugs and path.name in KNOWN_BUGS:
            marks.append(pytest.mark.xfail(reason=KNOWN_BUGS[path.name], strict=True))
        yield pytest.param(path, id=path.stem, marks=marks)


def test_there_are_enough_samples_and_every_header_is_complete():
    assert len(SAMPLES) >= 20
    for path in SAMPLES:
        assert _NAME.match(path.name), f"{path.name}: samples are named NN_topic.m"
        header = parse_header(path)
        for key in ("title", "shows", "run"):
            assert header.fields.get(key), f"{path.name}: header has no {key.title()}:"
        assert header.fields["run"].startswith(f"motiontool run {path.name}"), path.name
        assert header.expect_end in ("ended", "running"), f"{path.name}: Expect-end must be ended or running"
        assert len(path.read_text(encoding="utf-8").splitlines()) <= 100, f"{path.name} is too long"


def test_sample_numbers_are_unique_and_the_readme_lists_every_sample():
    numbers = [path.name[:2] for path in SAMPLES]
    assert len(numbers) == len(set(numbers))
    readme = (SAMPLES_DIR / "README.md").read_text(encoding="utf-8")
    for path in SAMPLES:
        assert path.name in readme, f"README.md does not list {path.name}"


@pytest.mark.parametrize("path", list(_params()))
def test_sample_compiles_without_diagnostics(path: Path):
    """Only the warnings of aposs/simulated.py that the header declares: a sample about the FC 300's parameters
    or its keypad cannot avoid them, and the user should see them in the IDE too."""
    expected = parse_header(path).expect_warnings
    result = compile_source(path=path)
    unexpected = [d.format() for d in result.diagnostics
                  if not (d.severity == "warning" and d.message.split(" ", 1)[0] in expected
                          and d.message == unserved_note(d.message.split(" ", 1)[0]))]
    assert unexpected == []
    assert {d.message.split(" ", 1)[0] for d in result.diagnostics} == expected, "Expect-warnings: names too many"


@pytest.mark.parametrize("path", list(_params(with_bugs=True)))
def test_sample_runs_as_its_header_says(path: Path):
    header = parse_header(path)
    outcome = run_sample(path, header)
    assert outcome.errors == (header.expect_errors or []), f"controller errors: {outcome.errors}"
    if header.expect:
        assert outcome.prints == header.expect
    assert outcome.state == header.expect_end
