"""The DPL program image a Link downloads (docs/formats/dpl-program-image.md): round trip, and readers that
refuse anything else naming the byte offset."""

from __future__ import annotations

import base64

import pytest
from hypothesis import given
from hypothesis import strategies as st

from motiontool.comms.protocol import LinkError
from motiontool.controller.dpl_program import dpl_link
from motiontool.dpl.image import MAX_SOURCE_BYTES, DplImage, DplImageError


@given(st.text().filter(lambda t: "\x00" not in t), st.text())
def test_round_trip(name, source):
    assert DplImage.from_bytes(DplImage(name, source).to_bytes()) == DplImage(name, source)


@pytest.mark.parametrize("data, message", [
    (b"MTIMG", "byte 0: not a DPL program image"),
    (b"DPL1\x00name without end", "byte 5: the program name is not terminated by a NUL"),
    (b"DPL1\x00ab\xff\x00x", "byte 7: the name is not UTF-8"),
    (b"DPL1\x00p\x00ok \xc3", "byte 10: the source is not UTF-8"),
    (b"DPL1\x00" + b"x" * MAX_SOURCE_BYTES, f"bytes: a DPL program image holds at most {MAX_SOURCE_BYTES}"),
])
def test_bad_images_are_refused_at_their_byte(data, message):
    with pytest.raises(DplImageError, match=message):
        DplImage.from_bytes(data)


def test_the_controller_refuses_a_program_with_errors_with_its_diagnostics():
    link = dpl_link()
    with pytest.raises(LinkError) as info:
        link.download(DplImage("p.dpl", "Pos0{\nx% = APC_NOPE\n}\n").to_bytes())
    assert str(info.value) == "p.dpl:2:6: error: unknown name 'APC_NOPE' (integer variables end with '%')"
    with pytest.raises(LinkError, match="not a DPL program image"):
        link.call("download", image=base64.b64encode(b"\x00\x01").decode(), number=None, name="")
    with pytest.raises(LinkError, match="no program downloaded"):
        link.start()
    link.download(DplImage("ok.dpl", "Pos0{\nn% = n% + 1\n}\n").to_bytes(), name="ok.dpl")
    assert link.call("list_programs") == [{"number": None, "name": "ok.dpl"}]
    link.start()
    link.advance(10)
    assert link.call("read_variables", names=["N%"]) == [10]
    with pytest.raises(LinkError, match="executing a program"):
        link.start()
    link.break_program()
    assert link.status().program_state == "idle"
