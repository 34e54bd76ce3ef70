"""Machine description the planner needs: axes, limits, planner settings, work offsets.

Read from the machine configuration TOML (resources/machines/*.toml), declared once in
``planner.core.schema``. The controller (app/machine) reads the same file, through the same schema,
for the sections the planner does not use ([homing], [bus], [controller]).
"""

from __future__ import annotations

import math
import os
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from planner.core.errors import PlannerError
from planner.core.frames import SYSTEM_NAMES
from planner.core.reading import CONFIGURATION, parse_toml, read_text
from planner.core.rules import SectionRule, check_sections
from planner.core.schema import Locator, check_complete, validate

#: the coordinate systems the machine keeps, G54 ... G59.3 (LinuxCNC's nine)
WORK_OFFSET_NAMES: tuple[str, ...] = SYSTEM_NAMES
#: those a machine has a value for even when its file names none (zero). G59.1-G59.3 come from
#: the file when it names them, else from the parameters a program left (G10 L2 P7-P9)
TABLE_OFFSET_NAMES: tuple[str, ...] = SYSTEM_NAMES[:6]
PLANNER_MODES: tuple[str, ...] = ("lookahead", "paper")
INTERPOLATIONS: tuple[str, ...] = ("exact", "taylor", "classic")
AXIS_LETTERS: str = "XYZABC"


@dataclass(frozen=True, slots=True)
class AxisSpec:
    """One machine axis. Units are mm for linear axes and degrees for rotary axes."""

    name: str
    rotary: bool = False
    # LinuxCNC's WRAPPED_ROTARY: absolute moves go the short way, the position reads modulo
    # 360, and the travel limits do not apply
    wrapped: bool = False
    drive_position: int = 0
    counts_per_unit: float = 10_000.0
    direction: int = 1
    min_pos: float = -1000.0
    max_pos: float = 1000.0
    v_max: float = 30.0
    a_max: float = 1000.0
    j_max: float = 10_000.0
    following_error_window: float = 1.0
    # leadscrew compensation: backlash, or a table file (LinuxCNC's COMP_FILE of type 0 or 1);
    # a compensated axis moves with (1 - comp_reserve) of its limits (``motion``)
    backlash: float = 0.0
    comp_file: str = ""
    comp_file_type: int = 0
    comp_reserve: float = 0.1
    # a gantry: the second drive (its slave position; None: one drive), its motor's direction
    # and the largest skew of the two sides while they move
    gantry_drive: int | None = None
    gantry_direction: int = 1
    gantry_skew_window: float = 0.5

    @property
    def unit(self) -> str:
        return "deg" if self.rotary else "mm"

    @property
    def compensated(self) -> bool:
        return self.backlash > 0.0 or bool(self.comp_file)

    @property
    def motion_share(self) -> float:
        """The share of ``v_max``, ``a_max`` and ``j_max`` that motion (programs, jogs, homing,
        the handwheel, holds) may use: all of it, or what the compensation leaves."""
        return 1.0 - self.comp_reserve if self.compensated else 1.0

    @property
    def v_motion(self) -> float:
        return self.v_max * self.motion_share

    @property
    def a_motion(self) -> float:
        return self.a_max * self.motion_share

    @property
    def j_motion(self) -> float:
        return self.j_max * self.motion_share


@dataclass(frozen=True, slots=True)
class PathLimits:
    """Limits along the tool path (the paper's Vmax, Amax, Jmax) and the rapid speed, for moves
    with a linear axis in them; and along the rotary distance for moves of rotary axes alone
    (LinuxCNC's MAX_ANGULAR_VELOCITY and the like, deg/s ...; infinite: the rotary axes' own
    limits govern, as for a rotary-only rapid in LinuxCNC)."""

    v_max_mm_s: float = 30.0
    a_max_mm_s2: float = 1000.0
    j_max_mm_s3: float = 10_000.0
    rapid_mm_s: float = 30.0
    v_max_deg_s: float = math.inf
    a_max_deg_s2: float = math.inf
    j_max_deg_s3: float = math.inf
    rapid_deg_s: float = math.inf


@dataclass(frozen=True, slots=True)
class PlannerSettings:
    ts_s: float = 0.001
    mode: str = "lookahead"
    interpolation: str = "exact"
    subroutine_dirs: tuple[str, ...] = ()    # as written; relative ones to MachineSpec.config_dir
    blend_tolerance_mm: float = 0.0  # G64 without P: corner blend tolerance (0: programmed path)
    max_program_mb: float = 1024.0   # the largest program read
    # at a joint that is not blended, the largest change of an axis' velocity in one sample
    # beyond what its jerk limit allows (0: none, every axis within its jerk limit there)
    corner_velocity_step_mm_s: float = 0.0

    @property
    def max_program_bytes(self) -> int:
        return int(self.max_program_mb * (1 << 20))


@dataclass(frozen=True)
class MachineSpec:
    name: str
    axes: tuple[AxisSpec, ...]
    limits: PathLimits = field(default_factory=PathLimits)
    planner: PlannerSettings = field(default_factory=PlannerSettings)
    work_offsets: dict[str, tuple[float, ...]] = field(default_factory=dict)
    config_dir: str = ""        # folder of the configuration file ("" when not read from a file)
    # digital outputs: number -> (drive index, bit, name), a terminal's channel as drive
    # -(its slave position + 1) (``io_place``); user M-codes: code -> (action, message, output
    # number, on)
    output_bits: dict[int, tuple[int, int, str]] = field(default_factory=dict)
    mcodes: dict[int, tuple[str, str, int, bool]] = field(default_factory=dict)
    # digital inputs (M66): number -> (drive index, bit of its 0x60FD, name), as outputs
    input_bits: dict[int, tuple[int, int, str]] = field(default_factory=dict)
    # the spindle's highest speed ([controller] spindle_max_rpm): G96 without D runs at it
    spindle_max_rpm: float = 24000.0
    # the subroutines shipped with the control (probing, tool measuring): searched after the
    # configured folders, so an integrator's file of the same name takes their place
    shipped_subroutine_dir: str = ""
    # an O-word call run after every M6 that changes the tool ("" none), as LinuxCNC's REMAP
    # of M6 runs an ngc: ``o<tool_measure> call [...]`` measures the new tool on the setter
    after_tool_change: str = ""

    @property
    def outputs(self) -> tuple[int, ...]:
        return tuple(sorted(self.output_bits))

    @property
    def inputs(self) -> tuple[int, ...]:
        return tuple(sorted(self.input_bits))

    def subroutine_paths(self) -> tuple[str, ...]:
        """The subroutine folders, relative ones taken from the configuration file's folder,
        then the shipped subroutines' folder."""
        configured = tuple(d if os.path.isabs(d) or not self.config_dir else os.path.join(self.config_dir, d)
                           for d in self.planner.subroutine_dirs)
        return configured + ((self.shipped_subroutine_dir,) if self.shipped_subroutine_dir else ())

    @property
    def axis_names(self) -> tuple[str, ...]:
        return tuple(a.name for a in self.axes)

    @property
    def rotary(self) -> tuple[bool, ...]:
        return tuple(a.rotary for a in self.axes)

    def axis_index(self, name: str) -> int:
        return self.axis_names.index(name.upper())

    def offset(self, name: str) -> tuple[float, ...]:
        return self.work_offsets.get(name, (0.0,) * len(self.axes))

    @staticmethod
    def default() -> MachineSpec:
        """A 3-axis XYZ mill with the paper's path limits (Vmax 30, Amax 1000, Jmax 10000)."""
        axes = tuple(
            AxisSpec(name=n, drive_position=i, min_pos=-500.0, max_pos=500.0, v_max=100.0,
                     a_max=2000.0, j_max=20_000.0)
            for i, n in enumerate("XYZ")
        )
        return MachineSpec(name="default XYZ", axes=axes,
                           work_offsets={n: (0.0, 0.0, 0.0) for n in TABLE_OFFSET_NAMES})

    def with_limits(self, **changes: float) -> MachineSpec:
        """A copy with path limits replaced (v_max_mm_s=..., a_max_mm_s2=..., ...)."""
        from dataclasses import replace

        return replace(self, limits=replace(self.limits, **changes))

    def with_planner(self, **changes: Any) -> MachineSpec:
        from dataclasses import replace

        new = replace(self, planner=replace(self.planner, **changes))
        _validate_planner(new.planner, "<settings>")
        return new


def _validate_planner(p: PlannerSettings, where: str) -> None:
    if p.mode not in PLANNER_MODES:
        raise PlannerError(f"{where}: planner mode must be one of {PLANNER_MODES}, got {p.mode!r}")
    if p.interpolation not in INTERPOLATIONS:
        raise PlannerError(
            f"{where}: interpolation must be one of {INTERPOLATIONS}, got {p.interpolation!r}")
    if not 1e-4 <= p.ts_s <= 0.1:
        raise PlannerError(f"{where}: ts_s must be between 0.0001 and 0.1 s, got {p.ts_s}")
    if not 0.0 <= p.blend_tolerance_mm <= 10.0:
        raise PlannerError(f"{where}: blend_tolerance_mm must be between 0 and 10 mm, "
                           f"got {p.blend_tolerance_mm}")
    if not 0.0 <= p.corner_velocity_step_mm_s <= 1000.0:
        raise PlannerError(f"{where}: corner_velocity_step_mm_s must be between 0 and 1000 mm/s, "
                           f"got {p.corner_velocity_step_mm_s}")


#: position counts must stay within int32 (CiA 402 0x607A/0x6064) with this margin over the travel
COUNTS_LIMIT = 2**31 * 0.9


def machine_from_dict(data: dict[str, Any], where: str | Locator = "<config>", text: str | None = None,
                      extra: SectionRule | None = None) -> MachineSpec:
    """Validate a parsed configuration (``planner.core.schema``, strict) and build the planner's
    view of it; every message names the file, the line when ``text`` is given, the key and
    the value."""
    loc = where if isinstance(where, Locator) else Locator(where, text)
    return machine_from_valid(validate(data, loc), loc, extra)


def _first_repeat(values: list[Any]) -> int | None:
    """Index of the first value that repeats an earlier one (None: all differ)."""
    return next((k for k in range(len(values)) if values[k] in values[:k]), None)


def machine_from_valid(valid: dict[str, Any], loc: Locator, extra: SectionRule | None = None) -> MachineSpec:
    """The planner's sections of a configuration already checked by ``schema.validate``, with
    the checks across keys: travel, unique names and drives, offsets per axis, counts, and the
    rules every reader applies (``rules.check_sections``, with the caller's ``extra``)."""
    axes: list[AxisSpec] = []
    for i, a in enumerate(valid["axes"]):
        name = a["name"]
        kind = a["kind"] or ("rotary" if name in "ABC" else "linear")
        lo, hi = a["min"], a["max"]
        if lo >= hi:
            raise loc.fail(("axes", i, "max"), f"min ({lo}) must be below max ({hi}) (axis {name})")
        counts = max(abs(lo), abs(hi)) * a["counts_per_unit"]
        if counts > COUNTS_LIMIT:
            raise loc.fail(("axes", i, "counts_per_unit"),
                           f"{a['counts_per_unit']:g} counts per unit over a travel to "
                           f"{max(abs(lo), abs(hi)):g} "
                           f"gives {counts:.4g} counts, beyond what the drive's 32-bit position holds "
                           f"with a 10 % margin ({COUNTS_LIMIT:.4g}) (axis {name})")
        if a.get("wrapped") and kind != "rotary":
            raise loc.fail(("axes", i, "wrapped"),
                           f"only a rotary axis can be wrapped (axis {name} is linear)")
        axes.append(AxisSpec(
            name=name, rotary=kind == "rotary", wrapped=bool(a.get("wrapped")),
            drive_position=a["drive_position"] if a["drive_position"] is not None else i,
            counts_per_unit=a["counts_per_unit"], direction=a["direction"], min_pos=lo, max_pos=hi,
            v_max=a["v_max"], a_max=a["a_max"], j_max=a["j_max"],
            following_error_window=a["following_error_window"],
            backlash=a["backlash"], comp_file=a["comp_file"], comp_file_type=a["comp_file_type"],
            comp_reserve=a["comp_reserve"], gantry_drive=a["gantry_drive"],
            gantry_direction=a["gantry_direction"], gantry_skew_window=a["gantry_skew_window"],
        ))
        if a["backlash"] > 0.0 and a["comp_file"]:
            raise loc.fail(("axes", i, "backlash"),
                           f"backlash and comp_file together (axis {name}): the table's forward and "
                           "reverse columns hold the backlash (LinuxCNC ignores BACKLASH beside COMP_FILE)")
    names = [a.name for a in axes]
    j = _first_repeat(names)           # the copy's line is named
    if j is not None:
        raise loc.fail(("axes", j, "name"), f"axis names must be unique, got {names}")
    positions = [a.drive_position for a in axes]
    j = _first_repeat(positions)
    if j is not None:
        raise loc.fail(("axes", j, "drive_position"), f"drive positions must be unique, got {positions}")
    for i, a in enumerate(axes):
        if a.gantry_drive is not None and a.gantry_drive in positions + [
                b.gantry_drive for b in axes[:i]]:
            raise loc.fail(("axes", i, "gantry_drive"), f"slave {a.gantry_drive} already drives an axis: "
                                                        f"a gantry's second drive is a slave of its own")
    lim = valid["limits"]
    def angular(key: str) -> float:
        return math.inf if lim.get(key) is None else float(lim[key])

    limits = PathLimits(v_max_mm_s=lim["v_max_mm_s"], a_max_mm_s2=lim["a_max_mm_s2"],
                        j_max_mm_s3=lim["j_max_mm_s3"], rapid_mm_s=lim["rapid_mm_s"],
                        v_max_deg_s=angular("v_max_deg_s"), a_max_deg_s2=angular("a_max_deg_s2"),
                        j_max_deg_s3=angular("j_max_deg_s3"), rapid_deg_s=angular("rapid_deg_s"))
    pl = valid["planner"]
    planner = PlannerSettings(ts_s=pl["ts_s"], mode=pl["mode"], interpolation=pl["interpolation"],
                              subroutine_dirs=tuple(pl["subroutine_dirs"]),
                              blend_tolerance_mm=pl["blend_tolerance_mm"],
                              max_program_mb=pl["max_program_mb"],
                              corner_velocity_step_mm_s=pl["corner_velocity_step_mm_s"])
    offsets: dict[str, tuple[float, ...]] = {n: (0.0,) * len(axes) for n in TABLE_OFFSET_NAMES}
    for key, value in valid["offsets"].items():
        if len(value) != len(axes):
            raise loc.fail(("offsets", key),
                           f"[offsets] {key} needs {len(axes)} numbers ({' '.join(names)}), got {len(value)}")
        for ax, v in zip(axes, value, strict=True):
            # part zero is a point of the machine: outside the travel it is a typo
            if not ax.min_pos <= v <= ax.max_pos:
                raise loc.fail(("offsets", key), f"{ax.name} {v:g} is outside the axis travel "
                                                 f"[{ax.min_pos:g}, {ax.max_pos:g}]")
        offsets[key] = tuple(value)
    where = loc.where
    config_dir = os.path.dirname(os.path.abspath(where)) if where and not where.startswith("<") else ""
    # two outputs on one bit would fight; two inputs on one bit read the same wire, which is fine
    output_bits = _io_bits(loc, valid["outputs"], "outputs", "output", len(axes), exclusive=True)
    input_bits = _io_bits(loc, valid["inputs"], "inputs", "input", len(axes), exclusive=False)
    mcodes: dict[int, tuple[str, str, int, bool]] = {}
    for i, mc in enumerate(valid["mcodes"]):
        if mc["code"] in mcodes:
            raise loc.fail(("mcodes", i, "code"), f"M{mc['code']} is defined twice")
        out = mc["output"]
        if mc["action"] == "output" and out not in output_bits:
            raise loc.fail(("mcodes", i, "output"), f"action \"output\" needs the number of an [[outputs]] "
                           f"table ({', '.join(map(str, sorted(output_bits))) or 'none defined'})")
        mcodes[mc["code"]] = (mc["action"], mc["message"], -1 if out is None else out, mc["on"])
    check_sections(valid, loc, tuple(axes), extra)
    return MachineSpec(name=valid["machine"]["name"], axes=tuple(axes), limits=limits, planner=planner,
                       work_offsets=offsets, config_dir=config_dir, output_bits=output_bits, mcodes=mcodes,
                       input_bits=input_bits,
                       spindle_max_rpm=float(valid["controller"]["spindle_max_rpm"]))


def io_place(drive: int) -> tuple[str, int]:
    """Where an ``[[outputs]]`` / ``[[inputs]]`` bit is: ("drive", axis index) or ("slave", the
    terminal's bus position)."""
    return ("drive", drive) if drive >= 0 else ("slave", -drive - 1)


def _io_bits(loc: Locator, entries: list[dict[str, Any]], table: str, what: str, n_axes: int,
             exclusive: bool) -> dict[int, tuple[int, int, str]]:
    """``[[outputs]]`` / ``[[inputs]]``: number -> (drive index, bit, name), each number once,
    each drive one of the axes, or a terminal's channel (``io_place``; the terminal checked with
    the bus); ``exclusive``: each bit once."""
    bits: dict[int, tuple[int, int, str]] = {}
    for i, o in enumerate(entries):
        if o["number"] in bits:
            raise loc.fail((table, i, "number"), f"{what} {o['number']} is defined twice")
        if (o["drive"] is None) == (o["slave"] is None):
            raise loc.fail((table, i), f"give the drive (an axis index) or the slave (a terminal's bus "
                                       f"position) of {what} {o['number']}, one of them")
        if o["drive"] is not None and o["drive"] >= n_axes:
            raise loc.fail((table, i, "drive"), f"{o['drive']} must be below the axis count {n_axes}")
        place = o["drive"] if o["drive"] is not None else -int(o["slave"]) - 1
        if exclusive and any((d, b) == (place, o["bit"]) for d, b, _ in bits.values()):
            where = f"drive {o['drive']}" if o["drive"] is not None else f"slave {o['slave']}"
            raise loc.fail((table, i, "bit"), f"bit {o['bit']} of {where} is already an {what}")
        bits[o["number"]] = (place, o["bit"], o["name"])
    return bits


def load_machine(path: str | Path, extra: SectionRule | None = None) -> MachineSpec:
    """Read and validate a machine configuration TOML file (``extra``: the caller's rules for
    its own sections, as ``machine_from_valid`` takes them)."""
    p = Path(path)
    if not p.exists() and not p.is_symlink():
        raise PlannerError(f"{p}: machine configuration file not found")
    text = read_text(p, CONFIGURATION)
    try:
        check_complete(text, str(p))
        data = parse_toml(text, str(p))
    except tomllib.TOMLDecodeError as exc:
        raise PlannerError(f"{p}: not a valid TOML file: {exc}") from None
    return machine_from_dict(data, str(p), text, extra)


