"""Locate the files under the project's resources/ folder (installed as package motiontool._resources)."""

from importlib.resources import files
from pathlib import Path


def resources_path(*parts: str) -> Path:
    """Path of a file in resources/, e.g. resources_path("parameters", "mco305.csv")."""
    return Path(str(files("motiontool._resources").joinpath(*parts)))
