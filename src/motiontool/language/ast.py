"""The base of both syntax trees: every node has the Location of its first token."""

from __future__ import annotations

from dataclasses import dataclass

from motiontool.language.diagnostics import Location


@dataclass(eq=False)  # nodes are compared by identity: two equal-looking statements are still two places
class Node:
    loc: Location
