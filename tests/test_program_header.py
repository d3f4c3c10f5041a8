"""A program header's Test-inputs/Test-settings as the IDE reads them (motiontool/program_header.py) and the link's
`start` with `inputs` (decision I23): the same inputs and the same run as tests/test_samples.py gives them."""

from __future__ import annotations

import pytest

from motiontool.aposs.driver import compile_source
from motiontool.comms.protocol import LinkError
from motiontool.controller.embedded import EmbeddedLink
from motiontool.program_header import HeaderError, read_test_settings
from tests.test_samples import SAMPLES, SAMPLES_DIR, parse_header


def test_the_ide_reads_every_samples_header_as_the_sample_test_does():
    for path in SAMPLES:
        header = parse_header(path)
        wanted = read_test_settings(path.read_text(encoding="utf-8"), path.name)
        assert wanted.inputs == header.inputs and wanted.settings == header.settings, path.name


@pytest.mark.parametrize(("line", "message"), [
    ("// Test-inputs: 1=1@500 2", "p.m line 2: Test-inputs entry 2: give N=V@T (input, value, ms)"),
    ("// Test-inputs: 1=1@-5", "p.m line 2: Test-inputs entry 1=1@-5: time -5: give a whole number from 0 to"),
    ("// Test-settings: KPROP", "p.m line 2: Test-settings entry KPROP: give NAME=V (parameter, value)"),
    ("// Test-settings: KPROP=x", "p.m line 2: Test-settings entry KPROP=x: give a whole number"),
])
def test_a_bad_entry_names_file_line_and_entry(line, message):
    with pytest.raises(HeaderError) as caught:
        read_test_settings(f"// Title: t\n{line}\nPRINT 1\n", "p.m")
    assert str(caught.value).startswith(message)
    assert "\n" not in str(caught.value)


def test_only_the_leading_comment_header_counts():
    text = "// Title: t\n\nPRINT 1\n// Test-inputs: 1=1@0\n"
    assert not read_test_settings(text)


def run(path, inputs, *, with_start: bool) -> list[str]:
    link = EmbeddedLink()
    link.service.controller.time_ms = 3_600_000   # up for an hour: times count from the start, not power-up
    prints: list[str] = []
    link.subscribe(lambda e: prints.append(e.text) if e.kind == "print" else None)
    if not with_start:
        for n, v, t in inputs:
            link.call("schedule_input", number=n, value=v, time_ms=3_600_000 + t)
    link.download(compile_source(path=path).image.to_bytes())
    link.start(inputs=inputs if with_start else None)
    for _ in range(40):
        link.advance(500)
    link.close()
    return prints


@pytest.mark.parametrize("name", ["05_jog_inputs.m", "25_analog_speed.m"])
def test_start_with_inputs_runs_as_the_headers_schedule(name):
    path = SAMPLES_DIR / name
    inputs = read_test_settings(path.read_text(encoding="utf-8")).inputs
    assert run(path, inputs, with_start=True) == run(path, inputs, with_start=False) == parse_header(path).expect


def test_start_refuses_an_input_the_controller_does_not_have_before_it_starts():
    link = EmbeddedLink()
    link.download(compile_source("PRINT 1\n", "p.m").image.to_bytes())
    with pytest.raises(LinkError, match="no digital input 13"):
        link.start(inputs=[(13, 1, 0)])
    with pytest.raises(LinkError, match="a digital input is 0 or 1, not 2"):
        link.start(inputs=[(1, 2, 0)])
    assert link.status().program_state == "idle"
    link.set_input(53, -250)                         # the I/O panel's slider: INAD 53 reads it
    link.download(compile_source("PRINT INAD 53\n", "p.m").image.to_bytes())
    prints: list[str] = []
    link.subscribe(lambda e: prints.append(e.text) if e.kind == "print" else None)
    link.start()
    link.advance(10)
    assert prints == ["-250"]
