"""What the IDE asks its user in the middle of a command, without Qt (issue 27 item 5: "dialogs through one
injected prompts object").

A command (Execute's "Stop it?", Reset's "Continue?", a file to save to) asks through a `Prompts` it was given,
never by opening a dialog itself: the IDE gives every window a `qtjobs.prompts.QtPrompts` (the same message boxes,
input dialogs and file dialogs as before), a test or a script without a window a `ScriptedPrompts` with the answers it
wants. Each method returns None (or False) for Cancel, so "the user cancelled" is one test at the caller.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Protocol


class Prompts(Protocol):
    def within(self, owner: Any) -> Prompts:
        """The same prompts shown over `owner` (a dialog of the window asking from inside it)."""
        ...

    def confirm(self, title: str, text: str) -> bool:
        """A Yes/No question; True for Yes."""
        ...

    def choose(self, title: str, text: str, choices: Sequence[str], *, detail: str = "", warning: bool = False,
               cancel: str = "Cancel", destructive: bool = False) -> str | None:
        """One of `choices` (the first is the default) or None for the `cancel` button ("Cancel" or "Close").
        `destructive`: the choices cannot be undone, so they stand apart and Cancel is the default."""
        ...

    def decide(self, title: str, text: str, *, yes: str, no: str, cancel: str, detail: str = "") -> bool | None:
        """A Yes/No/Cancel question whose buttons say what they do: True for `yes` (the default), False for `no`,
        None for `cancel`."""
        ...

    def save_changes(self, title: str, text: str) -> str | None:
        """Save, Discard or Cancel for changed work: "save", "discard" or None."""
        ...

    def text(self, title: str, label: str, *, default: str = "") -> str | None:
        ...

    def integer(self, title: str, label: str, value: int, low: int, high: int) -> int | None:
        ...

    def pick(self, title: str, label: str, items: Sequence[str], current: int) -> str | None:
        """One of `items` from a list (`current` preselected)."""
        ...

    def save_path(self, title: str, suggested: str, filters: str) -> Path | None:
        ...

    def save_name(self, title: str, suggested: str | Path, filters: str) -> Path | None:
        """The name to save a document under; a name typed without an extension gets the selected filter's."""
        ...

    def open_path(self, title: str, directory: str, filters: str) -> Path | None:
        ...

    def folder(self, title: str, directory: str) -> Path | None:
        ...

    def warn(self, title: str, text: str, *, detail: str = "", critical: bool = False) -> None:
        """`critical`: something failed (a file not written), rather than a caution."""
        ...

    def inform(self, title: str, text: str) -> None:
        ...


class PromptRefused(AssertionError):
    """A ScriptedPrompts was asked something it has no answer for."""


@dataclass
class ScriptedPrompts:
    """Answers given in advance, in the order they will be asked (a Prompts for tests and scripts without a window).

    `answers` holds what each question returns (True/False, a choice's text, a path, a number, None for Cancel);
    a question with no answer left raises PromptRefused naming it, so a test sees an unexpected dialog at once.
    Warnings and notices need no answer; everything asked is kept in `asked` as (kind, title, text)."""

    answers: deque[Any] = field(default_factory=deque)
    asked: list[tuple[str, str, str]] = field(default_factory=list)

    @classmethod
    def answering(cls, answers: Iterable[Any] = ()) -> ScriptedPrompts:
        return cls(deque(answers))

    def within(self, owner: Any) -> ScriptedPrompts:
        return self

    def _answer(self, kind: str, title: str, text: str) -> Any:
        self.asked.append((kind, title, text))
        if not self.answers:
            raise PromptRefused(f"unexpected {kind} {title!r}: {text}")
        return self.answers.popleft()

    def confirm(self, title: str, text: str) -> bool:
        return bool(self._answer("confirm", title, text))

    def choose(self, title: str, text: str, choices: Sequence[str], *, detail: str = "", warning: bool = False,
               cancel: str = "Cancel", destructive: bool = False) -> str | None:
        answer = self._answer("choose", title, text)
        if answer is not None and answer not in choices:
            raise PromptRefused(f"{answer!r} is not one of {list(choices)} for {title!r}")
        return answer

    def decide(self, title: str, text: str, *, yes: str, no: str, cancel: str, detail: str = "") -> bool | None:
        answer = self._answer("decide", title, text)
        return None if answer is None else bool(answer)

    def save_changes(self, title: str, text: str) -> str | None:
        return self._answer("save_changes", title, text)

    def text(self, title: str, label: str, *, default: str = "") -> str | None:
        return self._answer("text", title, label)

    def integer(self, title: str, label: str, value: int, low: int, high: int) -> int | None:
        return self._answer("integer", title, label)

    def pick(self, title: str, label: str, items: Sequence[str], current: int) -> str | None:
        answer = self._answer("pick", title, label)
        if answer is not None and answer not in items:
            raise PromptRefused(f"{answer!r} is not one of {list(items)} for {title!r}")
        return answer

    def save_path(self, title: str, suggested: str, filters: str) -> Path | None:
        answer = self._answer("save_path", title, suggested)
        return None if answer is None else Path(answer)

    def save_name(self, title: str, suggested: str | Path, filters: str) -> Path | None:
        answer = self._answer("save_name", title, str(suggested))
        return None if answer is None else Path(answer)

    def open_path(self, title: str, directory: str, filters: str) -> Path | None:
        answer = self._answer("open_path", title, directory)
        return None if answer is None else Path(answer)

    def folder(self, title: str, directory: str) -> Path | None:
        answer = self._answer("folder", title, directory)
        return None if answer is None else Path(answer)

    def warn(self, title: str, text: str, *, detail: str = "", critical: bool = False) -> None:
        self.asked.append(("warn", title, text))

    def inform(self, title: str, text: str) -> None:
        self.asked.append(("inform", title, text))
