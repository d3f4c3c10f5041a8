"""ApcDrive: one Unidrive SP with an SM-Applications module running the APC — the public object (docs/apc.md).

    drive = ApcDrive()                     # 1 ms POS period (#81.12 = 3), drive encoder on both sides
    drive.pos0 = my_pos0                   # user tasks run inside the tick, before and after the kernel
    drive.APCSetRunMode(2)                 # the manual's calls, names and argument orders
    drive.tick()                           # one POS sample;  drive.run_ms(1000) for a second
    value, status = drive.APCReadPar(48)   # read parameters by number, 1000 + n raw, or drive.read("APC_FB_POS")

`SIGNATURES` lists every call with its DPL arguments and outputs, and `call_dpl` runs a call by name the way a
DPL statement does (case-insensitive name, the outputs padded with the Status% some quick-reference forms add).
"""

from __future__ import annotations

import inspect
from collections.abc import Callable
from dataclasses import dataclass

from motiontool.apc import intmath
from motiontool.apc.commands import OK, ControlCommands
from motiontool.apc.commands_refs import ReferenceCommands
from motiontool.apc.core import APC_VERSION, KernelCore
from motiontool.apc.plant import PlantConfig
from motiontool.apc.profile import ProfileGenerator
from motiontool.apc.readpars import READ_PARAMETERS, parameter_number
from motiontool.apc.sources import Source
from motiontool.apc.units import EmbeddedConverter, UserDefinedConverter, pos_rate_code


class ApcDrive(ControlCommands, ReferenceCommands, KernelCore):
    """A simulated Unidrive SP + SM-Applications APC axis (module docstring)."""

    def __init__(self, plant: PlantConfig | None = None, *, pos_rate: int | None = None):
        """`pos_rate` is the #81.12 code (1 = 0.25 ms … 6 = 8 ms; default 3 = 1 ms)."""
        self.converter = EmbeddedConverter()
        self.user_converter = UserDefinedConverter()
        self.ctsync_out: tuple[int, int, int] | None = None
        # Reference1, Reference2, AuxRef of the last message received and the status of this sample's: nothing
        # received yet is "zero or fewer bytes than expected" (L3276); CTSyncGetSlaveReferences returns it as is
        self.ctsync_received: tuple[int, int, int, int] = (0, 0, 0, 0)
        self.ctsync_counts = [0, 0, 0]    # valid, invalid, missing messages (91.17-91.19)
        super().__init__(plant, pos_rate=pos_rate)
        for i, key in enumerate(((91, 17), (91, 18), (91, 19))):
            self.params.readers[key] = self._ctsync_count_reader(i)
        self._readers = self._make_readers()

    def _ctsync_count_reader(self, i: int) -> Callable[[], int]:
        return lambda: self.ctsync_counts[i]

    # --- running ---------------------------------------------------------------------------------------------
    def run_ms(self, ms: float) -> None:
        """Tick the POS samples that fall within the next `ms` milliseconds; the period is read before each sample,
        so a REINIT by a task acts from the next sample on (L4678-4723)."""
        end = self.time_ns + round(ms * 1_000_000)
        while self.time_ns + self.period_ns <= end:
            self.tick()

    def read(self, key: int | str) -> int:
        """A read parameter by number ("48", "[1048]") or alias ("APC_FB_POS"), as APCReadPar reports it."""
        number = parameter_number(key)
        value = self.read_parameter(number)
        if value is None:
            raise ValueError(f"no APC read parameter [{number}]")
        return value[0]

    # --- DPL binding -------------------------------------------------------------------------------------------
    def call_dpl(self, name: str, args: tuple | list = (), targets: int = 1) -> tuple:
        """Run the call `name` (any case) with `args`; return exactly `targets` values for the assignment
        `(a, b, …) = Name(args)`: the printed outputs in order, plus a Status% of 1 where the quick reference
        prints one more output than the command page (APCGetOutputSpeed, the word blocks, ConvertForwards…).
        0 targets (a call as a statement) returns ()."""
        sig = signature(name)
        if len(args) != len(sig.args):
            raise TypeError(f"{sig.name} takes {len(sig.args)} argument(s) ({', '.join(sig.args) or 'none'}), "
                            f"{len(args)} given")
        fn = getattr(intmath, sig.name) if sig.builtin else getattr(self, sig.name)
        result = fn(*args)
        values = result if isinstance(result, tuple) else (result,)
        if targets == len(values) + 1 and sig.quick_status:
            values = (*values, OK)
        if targets > len(values):
            raise TypeError(f"{sig.name} gives {len(values)} output(s) ({', '.join(sig.outputs)}), "
                            f"{targets} wanted")
        return values[:targets]

    # --- the read parameters -----------------------------------------------------------------------------------
    def _make_readers(self) -> dict[int, Callable[[], int]]:
        ref, fb, pg, opg, cam, dl, loop = self.ref, self.fb, self.pg, self.opg, self.cam, self.dl, self.loop
        uu = lambda: self.user_units  # noqa: E731
        r: dict[int, Callable[[], int]] = {
            0: lambda: int(self.run_mode == 2), 1: lambda: int(self.absolute_mode),
            2: lambda: self.position_reset_offset, 3: lambda: int(self.reset_sources_on_disable),
            4: lambda: self.enabled, 5: lambda: self.reset_status, 6: lambda: self.ref_reset_offset,
            13: lambda: pos_rate_code(self.period_us) - 1, 14: lambda: self.turns_bits,   # in force (REINIT)
            15: lambda: APC_VERSION,
            60: lambda: int(dl.rigid), 61: lambda: dl.mode, 62: lambda: dl.ratio.numerator,
            63: lambda: dl.ratio.denominator, 64: lambda: dl.lock_speed, 65: lambda: dl.lock_position,
            74: lambda: cam.start_index, 75: lambda: cam.size, 76: lambda: cam.seg_limit, 77: lambda: cam.mode,
            78: lambda: int(cam.single_shot), 79: lambda: int(cam.absolute_reset),
            80: lambda: cam.ratio.numerator, 81: lambda: cam.ratio.denominator, 82: lambda: cam.segment,
            83: lambda: cam.position, 84: lambda: cam.array_size, 85: lambda: cam.reset_index,
            86: lambda: cam.reset_position, 87: lambda: cam.complete, 88: lambda: int(cam.rearm),
            89: lambda: cam.wrapped,
            90: lambda: self.stop_mode, 91: self.stop_position, 92: lambda: self.position_setpoint,
            93: lambda: self.position_offset, 94: lambda: self.speed_setpoint, 95: lambda: self.speed_offset,
            96: lambda: u.conv_n if (u := uu()) else 1, 97: lambda: u.conv_d if (u := uu()) else 1,
            100: lambda: self.reference, 101: lambda: self.action_on_freeze, 102: lambda: self.offset_select,
            130: lambda: loop.error, 131: lambda: loop.kp, 132: lambda: loop.p_clamp,
            133: lambda: loop.ratio_num, 134: lambda: loop.ratio_den, 135: lambda: loop.output,
            136: lambda: int(loop.ext_pos_selected), 137: lambda: loop.ext_position,
            138: lambda: int(loop.ext_speed_selected), 139: lambda: loop.ext_speed, 140: lambda: loop.output_clamp,
            141: lambda: loop.ff_gain, 142: lambda: loop.position_ref, 143: lambda: loop.speed_ref,
            144: self._total_position, 145: lambda: pg.output_acceleration() + opg.output_acceleration(),
            170: lambda: self.position_setpoint, 171: lambda: self.setpoint_rem,
            172: lambda: self.setpoint_user_rem, 173: lambda: self.position_offset, 174: lambda: self.offset_rem,
            175: lambda: self.offset_user_rem, 176: self.stop_position,
            178: lambda: self._pos_out(self.stop_position())[1],
            180: lambda: pg.input_position, 181: lambda: pg.position, 182: lambda: opg.input_position,
            183: lambda: opg.position, 184: lambda: loop.position_ref, 185: self._total_position,
            186: lambda: pg.flags() | opg.flags() << 16,
            187: pg.output_jerk, 189: opg.output_jerk,
        }
        for base, side in ((20, ref), (40, fb)):
            r.update(self._source_readers(base, side))
        for base, gen in ((110, pg), (150, opg)):
            r.update(_generator_readers(base, gen))
        missing = set(READ_PARAMETERS) - set(r)
        assert not missing, f"read parameters without a reader: {sorted(missing)}"
        return r

    def _source_readers(self, base: int, s: Source) -> dict[int, Callable[[], int]]:
        """[20]-[32] of the reference source, [40]-[52] of the feedback source."""
        return {
            base: lambda: s.position, base + 1: lambda: s.freeze_position,
            base + 2: lambda: s.freeze_flag, base + 3: lambda: s.marker_position,
            base + 4: lambda: s.marker_flag, base + 5: lambda: int(s.marker_reset),
            base + 6: lambda: s.speed(self.turns_bits, self.quarters),
            base + 7: lambda: int(s.inverted),
            base + 8: lambda: s.integrated, base + 9: lambda: s.freeze_integrated,
            base + 10: lambda: s.marker_integrated, base + 11: lambda: s.input,
            base + 12: lambda: int(s.input_disabled),
        }

    def _total_position(self) -> int:
        return intmath.wrap32(self.pg.position + self.opg.position)


def _generator_readers(base: int, g: ProfileGenerator) -> dict[int, Callable[[], int]]:
    """[110]-[129] of the profile generator, [150]-[169] of the offset profile generator."""
    def flag(b: int) -> Callable[[], int]:
        return lambda: (g.flags() >> b) & 1

    r: dict[int, Callable[[], int]] = {
        base: lambda: g.accel, base + 1: lambda: g.decel, base + 2: lambda: g.jerk,
        base + 3: lambda: g.max_speed, base + 4: lambda: int(g.disabled),
        base + 5: lambda: g.input_position, base + 6: lambda: g.input_speed,
        base + 7: lambda: g.position, base + 8: g.output_speed, base + 9: g.output_acceleration,
    }
    for bit in range(10):
        r[base + 10 + bit] = flag(bit)
    return r


# --- signatures -------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Signature:
    name: str
    args: tuple[str, ...]
    outputs: tuple[str, ...]
    builtin: bool = False         # a DPL built-in (MULDIV, word blocks), not a drive call
    quick_status: bool = False    # the quick reference prints one more output, a Status%


_PREFIXES = ("APC", "CTSync", "SetUPR", "GetUPR", "UserToAPC", "SetConverter", "Convert")
# calls whose quick-reference line adds a Status% to the command page's single output (L7509-7510, L7670-7699)
_QUICK_STATUS = {"APCGetOutputSpeed", "APCGetOutputSpeedRpmx10", "ConvertForwards", "ConvertBackwards",
                 "UnsignedTopWord", "SignedTopWord", "UnsignedBottomWord", "SignedBottomWord", "PutTopWord",
                 "PutBottomWord"}
_BUILTINS = {"MULDIV": ("Result%",), "MULDIVRM": ("Quotient%", "Remainder%"),
             "UnsignedTopWord": ("Output%",), "SignedTopWord": ("Output%",), "UnsignedBottomWord": ("Output%",),
             "SignedBottomWord": ("Output%",), "PutTopWord": ("Output%",), "PutBottomWord": ("Output%",)}


def _collect() -> dict[str, Signature]:
    table: dict[str, Signature] = {}
    for name, fn in inspect.getmembers(ApcDrive, inspect.isfunction):
        if name.startswith(_PREFIXES):
            args = tuple(p for p in inspect.signature(fn).parameters if p != "self")
            outs = getattr(fn, "apc_outputs", ("Status%",))
            table[name] = Signature(name, args, outs, quick_status=name in _QUICK_STATUS)
    for name, outs in _BUILTINS.items():
        args = tuple(p.lower() for p in inspect.signature(getattr(intmath, name)).parameters)
        table[name] = Signature(name, args, outs, builtin=True, quick_status=name in _QUICK_STATUS)
    return table


SIGNATURES: dict[str, Signature] = _collect()
_BY_UPPER = {name.upper(): sig for name, sig in SIGNATURES.items()}


def signature(name: str) -> Signature:
    """The call `name` in any case (DPL is not case-sensitive; the quick reference writes CTSYNC…)."""
    sig = _BY_UPPER.get(name.replace(" ", "").upper())
    if sig is None:
        raise KeyError(f"no APC call {name!r}")
    return sig
