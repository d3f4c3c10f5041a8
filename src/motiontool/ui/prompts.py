"""The IDE's Prompts (session/prompts.py) are `motiontool.qtjobs.prompts.QtPrompts`, which the tool windows use
too (they may not import `ui`); re-exported here for the APOSS windows."""

from motiontool.qtjobs.prompts import CANCEL_BUTTONS, QtPrompts

__all__ = ["CANCEL_BUTTONS", "QtPrompts"]
