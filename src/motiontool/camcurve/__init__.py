"""Qt-free CAM curve core: curve model, spline maths, and the controller's curve-array layout.

Imported by the controller kernel (SETCURVE, CURVEPOS, SYNCC…) and by the CAM editor; see
docs/formats/cam-array.md for the array layout.
"""

from motiontool.camcurve.layout import (
    CURVE_ARRAY_ID,
    STRUCTURE_VERSION,
    CurveArrayError,
    DecodedCurve,
    decode,
    element_count,
    encode,
    max_start_stop_len,
)
from motiontool.camcurve.model import (
    FIX_POINT_TYPES,
    Curve,
    CurveError,
    CurveType,
    FixPoint,
    StartStopPair,
    segment_kinds,
    snap,
)
from motiontool.camcurve.spline import (
    CurveInfo,
    CurveProfile,
    acceleration,
    curve_info,
    disengage_path,
    engage_path,
    interpolation_points,
    jerk,
    profile,
    slave,
    slave_acceleration_limit,
    slave_velocity_limit,
    velocity,
)

__all__ = [
    "CURVE_ARRAY_ID", "FIX_POINT_TYPES", "STRUCTURE_VERSION", "Curve", "CurveArrayError", "CurveError", "CurveInfo",
    "CurveProfile", "CurveType", "DecodedCurve", "FixPoint", "StartStopPair", "acceleration", "curve_info", "decode",
    "disengage_path", "element_count", "encode", "engage_path", "interpolation_points", "jerk", "max_start_stop_len",
    "profile", "segment_kinds", "slave", "slave_acceleration_limit", "slave_velocity_limit", "snap", "velocity",
]
