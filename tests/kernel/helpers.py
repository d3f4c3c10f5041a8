"""Run APOSS source on the real embedded controller through the link, as the IDE and CLI do."""

from __future__ import annotations

from dataclasses import dataclass, field

from motiontool.aposs.driver import compile_source
from motiontool.comms.protocol import LinkEvent
from motiontool.controller.embedded import EmbeddedLink


@dataclass
class Run:
    link: EmbeddedLink
    prints: list[str] = field(default_factory=list)
    errors: list[LinkEvent] = field(default_factory=list)
    print_times: list[int] = field(default_factory=list)

    @property
    def controller(self):
        return self.link.service.controller

    @property
    def state(self) -> str:
        return self.link.status().program_state

    def advance(self, ms: int) -> Run:
        self.link.advance(ms)
        return self


def start(source: str, settings: dict | None = None, inputs: list[tuple[int, int, int]] | None = None,
          plant=None, link: EmbeddedLink | None = None, master=None) -> Run:
    result = compile_source(source, "test.m")
    assert result.ok, "\n".join(d.format() for d in result.diagnostics)
    link = link or EmbeddedLink(plant, master=master)
    run = Run(link)

    def on_event(event: LinkEvent) -> None:
        if event.kind == "print":
            run.prints.append(event.text)
            run.print_times.append(event.time_ms)
        elif event.kind == "error":
            run.errors.append(event)

    link.subscribe(on_event)
    for key, value in (settings or {}).items():
        link.write_parameter(key, value)
    for number, value, at in inputs or []:
        link.call("schedule_input", number=number, value=value, time_ms=at)
    link.download(result.image.to_bytes())
    link.start()
    return run


def run_source(source: str, ms: int = 10_000, **kw) -> Run:
    """Start and advance until the program ends or `ms` of controller time have passed."""
    run = start(source, **kw)
    step = 100
    for _ in range(0, ms, step):
        if run.state != "running":
            break
        run.link.advance(step)
    return run
