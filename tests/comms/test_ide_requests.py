"""Requests the IDE's Controller dialogs use (issue 16): name, programs with their source, memory, error
history, stack size — on the embedded controller, synchronously."""

import pytest

from motiontool.aposs.driver import compile_source
from motiontool.comms.protocol import LinkError
from motiontool.controller.embedded import EmbeddedLink


def image(text):
    result = compile_source(text, "p.m")
    assert result.ok
    return result.image.to_bytes()


@pytest.fixture
def link():
    link = EmbeddedLink()
    yield link
    link.close()


def test_name_is_upper_case_and_at_most_8_characters(link):
    """DG 2870-2882: "Names cannot be longer than 8 characters and must be uppercase"."""
    assert link.call("identify")["name"] == ""
    link.call("set_name", name="BLUE")
    assert link.call("identify")["name"] == "BLUE"
    for bad in ("toolongname", "blue", "NINECHARS"):
        with pytest.raises(LinkError, match="8 characters, upper case"):
            link.call("set_name", name=bad)
    assert link.call("identify")["name"] == "BLUE"


def test_a_program_stored_with_its_source_uploads_it(link):
    """DG 2643-2675: Include Sourcecode stores the source and its include files; Upload gives them back."""
    link.download(image('PRINT "a"\n'), number=5, name="PRINT3", source={"print3.m": 'PRINT "a"\n',
                                                                           "lib.inc": "// lib\n"})
    link.download(image('PRINT "b"\n'), number=6, name="PLAIN")
    listing = {p["number"]: p for p in link.call("list_programs")}
    assert listing[5]["source"] and listing[5]["stored_at"] and not listing[6]["source"]
    up = link.call("upload_source", number=5)
    assert up["main"] == "print3.m" and up["files"]["lib.inc"] == "// lib\n"
    with pytest.raises(LinkError, match="without its source"):
        link.call("upload_source", number=6)
    assert link.call("upload_program", number=6)
    link.call("delete_program", number=5)
    with pytest.raises(LinkError):
        link.call("upload_source", number=5)


def test_the_stack_size_of_settings_compiler_reaches_the_program(link):
    """DG 3078-3080: the stack size reserves the memory of function calls: a function with a local array of
    50 longs runs with the default 200 and fails with 20 (error 193)."""
    source = ("long big()\n{\n    long buf[50]\n    buf[50] = 7\n    return(buf[50])\n}\nx = big()\nPRINT x\n")
    for stack, fails in ((200, False), (20, True)):
        link.download(image(source), stack_size=stack)
        link.start()
        link.advance(200)
        assert (link.status().error != 0) == fails, stack
        link.call("clear_error")


def test_memory_saves_and_delete_eprom_takes_effect_at_power_on(link):
    link.write_parameter("KPROP", 77)
    link.call("save_memory", what="ram")
    link.download(image('PRINT "x"\n'), number=1, name="X")
    link.call("delete_eprom")
    assert link.read_parameter("KPROP") == 77 and link.call("list_programs")   # not before the power cycle
    link.call("power_on")
    assert link.read_parameter("KPROP") == 30 and link.call("list_programs") == []
    with pytest.raises(LinkError, match="choose one of"):
        link.call("save_memory", what="everything")


def test_error_history_is_cleared_by_clear(link):
    link.download(image("DIM a[2]\nx = a[5]\n"))
    link.start()
    link.advance(50)
    assert [e["number"] for e in link.call("error_history")] == [171]
    link.call("clear_error_history")
    assert link.call("error_history") == []


def test_power_on_clears_the_error_history(link):
    """DG 2996: "The list is cleared each time that the controller is powered on." Controller ▸ Restart is the
    link's power_on; an error of the Autostart program after it is the new list's first entry."""
    link.download(image("DIM a[2]\nx = a[5]\n"), number=1, name="BAD")
    link.start(1)
    link.advance(50)
    assert [e["number"] for e in link.call("error_history")] == [171]
    link.call("power_on")
    assert link.call("error_history") == [] and link.status().error == 0
    link.call("set_autostart", number=1)
    link.call("power_on")
    link.advance(50)
    assert [e["number"] for e in link.call("error_history")] == [171]
