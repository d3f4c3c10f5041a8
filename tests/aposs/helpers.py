from pathlib import Path

import pytest

from motiontool.aposs.driver import compile_source

EXAMPLES = Path(__file__).with_name("manual")


def compile_text(text: str, name: str = "prog.m", **kw):
    return compile_source(text, name, **kw)


def messages(text: str, severity: str = "error") -> list[str]:
    """`line:col: message` of every diagnostic of one severity."""
    result = compile_text(text)
    return [f"{d.loc.line}:{d.loc.col}: {d.message}" for d in result.diagnostics if d.severity == severity]


@pytest.fixture
def compile_ok():
    def run(text: str, **kw):
        result = compile_text(text, **kw)
        assert result.ok, "\n".join(d.format() for d in result.diagnostics)
        return result.image
    return run
