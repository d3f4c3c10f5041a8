"""Moving a configuration (.zbc) between a file and a controller, through a comms Link only.

Download = Controller → Parameters → Restore from file / `motiontool run --config` / the CAM editor's "Write to
controller": parameters first (raw values over the link, each checked by the controller), then the array memory
is replaced by the file's arrays in DIM order.  Upload = "Save to file" / "Read from controller": every
savable parameter and every array; curve arrays that decode become editable curves again.  Qt-free.
"""

from __future__ import annotations

from motiontool.camcurve.layout import CurveArrayError, decode
from motiontool.camcurve.model import CurveError
from motiontool.comms.link import Link
from motiontool.comms.protocol import LinkError
from motiontool.formats import zbc_drive
from motiontool.formats.zbc import ArrayEntry, ConfigError, ConfigFile, parameter_section
from motiontool.paramdb import database

#: The sets Restore from file offers as checkboxes (DG 2894-2900): parameter sections of the .zbc, and arrays;
#: "drive" is the FC 300's [fc300] section (decision C19).
SETS = ("global", "axis", "user", "drive", "arrays")


def download_config(link: Link, config: ConfigFile, sets: tuple[str, ...] = SETS) -> None:
    """Write ``config``'s parameters and arrays (those of ``sets``) to the controller; raises ConfigError
    naming what failed."""
    db = database()
    for number, value in config.parameters.items():
        parameter = db.get(number)
        if parameter_section(parameter) not in sets:
            continue
        try:
            link.write_parameter(parameter.number, parameter.to_raw(value))
        except LinkError as exc:
            raise ConfigError(f"parameter {parameter.label}: the controller refused {value}: {exc}") from None
    if "drive" in sets:
        try:
            zbc_drive.write_settings(link, config.drive)
        except LinkError as exc:
            raise ConfigError(str(exc)) from None
    if config.arrays and "arrays" in sets:
        try:
            link.restore_arrays([(a.name, a.values) for a in config.arrays])
        except LinkError as exc:
            raise ConfigError(f"arrays: the controller refused them: {exc}") from None


def upload_config(link: Link) -> ConfigFile:
    """Read every writable parameter and every array from the controller; curve arrays become curves."""
    config = ConfigFile()
    for parameter in database():
        if parameter.read_only:
            continue
        config.parameters[parameter.number] = parameter.from_raw(link.read_parameter(parameter.number))
    config.drive = _upload_drive(link)
    for info in link.list_arrays():
        values = link.read_array(info.index)
        entry = ArrayEntry(info.name, values)
        try:
            curve = decode(values).to_curve()
        except (CurveArrayError, CurveError):
            curve = None  # an ordinary array
        if curve is not None and config.curve(curve.name) is None:
            entry.curve = curve.name
            config.curves.append(curve)
        config.arrays.append(entry)
    return config


def _upload_drive(link: Link) -> dict[str, int]:
    """The FC 300 settings that differ from their defaults: the file says what was set (C19).  A link whose protocol
    does not carry the drive's parameters (error 112 for the first: the FC protocol's parameter channel names only
    the MCO 305's) gives none, as the file would from a drive at its defaults."""
    drive: dict[str, int] = {}
    for k, p in enumerate(zbc_drive.savable()):
        try:
            value = link.read_parameter(p.label)
        except LinkError as exc:
            if k == 0 and exc.number == 112:
                return {}
            raise
        if value != p.default:
            drive[p.label] = value
    return drive
