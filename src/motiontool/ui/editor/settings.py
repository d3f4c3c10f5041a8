"""Settings → Editor (ide-spec 1.6, 1.22, 1.44): colours per element, tab size, convert tabs while typing.

Qt-free: colours are ``#rrggbb`` strings, so the settings can be stored as JSON or in QSettings.
"""

from __future__ import annotations

import re
from dataclasses import asdict, dataclass, field, fields, replace

_HEX = re.compile(r"#[0-9A-Fa-f]{6}")
MIN_TAB_SIZE = 2  # "This can be set to 2 or more" [DG L3146]


@dataclass(frozen=True)
class EditorColors:
    """Syntax colours. The manual's elements [DG L3121-3131] come first; the rest are editor extras."""

    comment: str = "#7a7a7a"       # grey, drawn italic
    keyword: str = "#0033b3"       # deep blue, drawn bold
    number: str = "#1750eb"        # blue
    operator: str = "#9c3d00"      # rust
    string: str = "#067d17"        # green
    text: str = "#1f1f1f"          # near-black
    window: str = "#ffffff"        # background
    parameter: str = "#871094"     # purple: parameter code names (KPROP)
    preprocessor: str = "#8a6d00"  # dark olive: #define / #include lines
    current_line: str = "#eef3fc"  # light blue band behind the caret line
    gutter: str = "#f4f4f4"        # line-number area
    gutter_text: str = "#8c8c8c"
    bookmark: str = "#1e5bd6"      # the blue triangle of the manual [DG L2306]
    error: str = "#e0201b"
    warning: str = "#e58a00"

    def __post_init__(self) -> None:
        for f in fields(self):
            value = getattr(self, f.name)
            if not isinstance(value, str) or not _HEX.fullmatch(value):
                raise ValueError(f"colour {f.name!r} must be '#rrggbb', got {value!r}")

    def to_dict(self) -> dict[str, str]:
        return asdict(self)

    @classmethod
    def from_dict(cls, data: dict[str, str]) -> EditorColors:
        """Colours from a dict; unknown keys are ignored, missing ones keep their default."""
        names = {f.name for f in fields(cls)}
        return replace(cls(), **{k: v for k, v in data.items() if k in names})


@dataclass(frozen=True)
class EditorSettings:
    tab_size: int = 4                       # the dialog's example [DG L3133]
    convert_tabs_while_typing: bool = False  # affects new typing only [DG L3148-3150]
    font_family: str = ""                   # "" = the system's fixed-width font
    font_size: int = 10
    colors: EditorColors = field(default_factory=EditorColors)

    def __post_init__(self) -> None:
        if not isinstance(self.tab_size, int) or self.tab_size < MIN_TAB_SIZE:
            raise ValueError(f"tab size must be {MIN_TAB_SIZE} or more, got {self.tab_size!r}")
        if self.font_size < 4:
            raise ValueError(f"font size too small: {self.font_size}")
