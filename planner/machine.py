"""Machine description the planner needs: axes, limits, planner settings, work offsets.

Read from the machine configuration TOML (resources/machines/*.toml). The controller
(app/machine) reads the same file for the sections the planner does not use ([homing], [bus]).
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from planner.errors import PlannerError

WORK_OFFSET_NAMES: tuple[str, ...] = ("G54", "G55", "G56", "G57", "G58", "G59")
PLANNER_MODES: tuple[str, ...] = ("lookahead", "paper")
INTERPOLATIONS: tuple[str, ...] = ("exact", "taylor", "classic")
AXIS_LETTERS: str = "XYZABC"


@dataclass(frozen=True, slots=True)
class AxisSpec:
    """One machine axis. Units are mm for linear axes and degrees for rotary axes."""

    name: str
    rotary: bool = False
    drive_position: int = 0
    counts_per_unit: float = 10_000.0
    direction: int = 1
    min_pos: float = -1000.0
    max_pos: float = 1000.0
    v_max: float = 30.0
    a_max: float = 1000.0
    j_max: float = 10_000.0
    following_error_window: float = 1.0

    @property
    def unit(self) -> str:
        return "deg" if self.rotary else "mm"


@dataclass(frozen=True, slots=True)
class PathLimits:
    """Limits along the tool path (the paper's Vmax, Amax, Jmax) and the rapid speed."""

    v_max_mm_s: float = 30.0
    a_max_mm_s2: float = 1000.0
    j_max_mm_s3: float = 10_000.0
    rapid_mm_s: float = 30.0


@dataclass(frozen=True, slots=True)
class PlannerSettings:
    ts_s: float = 0.001
    mode: str = "lookahead"
    interpolation: str = "exact"


@dataclass(frozen=True)
class MachineSpec:
    name: str
    axes: tuple[AxisSpec, ...]
    limits: PathLimits = field(default_factory=PathLimits)
    planner: PlannerSettings = field(default_factory=PlannerSettings)
    work_offsets: dict[str, tuple[float, ...]] = field(default_factory=dict)
    raw: dict[str, Any] = field(default_factory=dict)

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
                           work_offsets={n: (0.0, 0.0, 0.0) for n in WORK_OFFSET_NAMES})

    def with_limits(self, **changes: float) -> MachineSpec:
        """A copy with path limits replaced (v_max_mm_s=..., a_max_mm_s2=..., ...)."""
        from dataclasses import replace

        return replace(self, limits=replace(self.limits, **changes))

    def with_planner(self, **changes: Any) -> MachineSpec:
        from dataclasses import replace

        new = replace(self, planner=replace(self.planner, **changes))
        _validate_planner(new.planner, "<settings>")
        return new


def _number(table: dict[str, Any], key: str, where: str, default: float | None = None,
            positive: bool = False) -> float:
    if key not in table:
        if default is None:
            raise PlannerError(f"{where}: missing '{key}'")
        return float(default)
    value = table[key]
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise PlannerError(f"{where}: '{key}' must be a number, got {value!r}")
    if positive and value <= 0:
        raise PlannerError(f"{where}: '{key}' must be greater than 0, got {value}")
    return float(value)


def _validate_planner(p: PlannerSettings, where: str) -> None:
    if p.mode not in PLANNER_MODES:
        raise PlannerError(f"{where}: planner mode must be one of {PLANNER_MODES}, got {p.mode!r}")
    if p.interpolation not in INTERPOLATIONS:
        raise PlannerError(
            f"{where}: interpolation must be one of {INTERPOLATIONS}, got {p.interpolation!r}")
    if not 1e-5 <= p.ts_s <= 0.1:
        raise PlannerError(f"{where}: ts_s must be between 1e-05 and 0.1 s, got {p.ts_s}")


def machine_from_dict(data: dict[str, Any], where: str = "<config>") -> MachineSpec:
    """Validate a parsed configuration; every message names the file, the key and the value."""
    axes_raw = data.get("axes")
    if not isinstance(axes_raw, list) or not axes_raw:
        raise PlannerError(f"{where}: at least one [[axes]] table is required")
    axes: list[AxisSpec] = []
    for i, a in enumerate(axes_raw):
        w = f"{where}: axes[{i}]"
        name = str(a.get("name", "")).upper()
        if len(name) != 1 or name not in AXIS_LETTERS:
            raise PlannerError(f"{w}: name must be one of X Y Z A B C, got {a.get('name')!r}")
        kind = a.get("kind", "rotary" if name in "ABC" else "linear")
        if kind not in ("linear", "rotary"):
            raise PlannerError(f"{w} ({name}): kind must be 'linear' or 'rotary', got {kind!r}")
        direction = int(_number(a, "direction", f"{w} ({name})", 1))
        if direction not in (1, -1):
            raise PlannerError(f"{w} ({name}): direction must be 1 or -1, got {direction}")
        lo = _number(a, "min", f"{w} ({name})")
        hi = _number(a, "max", f"{w} ({name})")
        if lo >= hi:
            raise PlannerError(f"{w} ({name}): min ({lo}) must be below max ({hi})")
        axes.append(AxisSpec(
            name=name, rotary=kind == "rotary",
            drive_position=int(_number(a, "drive_position", f"{w} ({name})", i)),
            counts_per_unit=_number(a, "counts_per_unit", f"{w} ({name})", 10_000, positive=True),
            direction=direction, min_pos=lo, max_pos=hi,
            v_max=_number(a, "v_max", f"{w} ({name})", positive=True),
            a_max=_number(a, "a_max", f"{w} ({name})", positive=True),
            j_max=_number(a, "j_max", f"{w} ({name})", positive=True),
            following_error_window=_number(a, "following_error_window", f"{w} ({name})", 1.0,
                                           positive=True),
        ))
    names = [a.name for a in axes]
    if len(set(names)) != len(names):
        raise PlannerError(f"{where}: axis names must be unique, got {names}")
    positions = [a.drive_position for a in axes]
    if len(set(positions)) != len(positions):
        raise PlannerError(f"{where}: drive positions must be unique, got {positions}")

    lim = data.get("limits", {})
    limits = PathLimits(
        v_max_mm_s=_number(lim, "v_max_mm_s", f"{where}: [limits]", 30.0, positive=True),
        a_max_mm_s2=_number(lim, "a_max_mm_s2", f"{where}: [limits]", 1000.0, positive=True),
        j_max_mm_s3=_number(lim, "j_max_mm_s3", f"{where}: [limits]", 10_000.0, positive=True),
        rapid_mm_s=_number(lim, "rapid_mm_s", f"{where}: [limits]", 30.0, positive=True),
    )
    pl = data.get("planner", {})
    planner = PlannerSettings(
        ts_s=_number(pl, "ts_s", f"{where}: [planner]", 0.001, positive=True),
        mode=str(pl.get("mode", "lookahead")),
        interpolation=str(pl.get("interpolation", "exact")),
    )
    _validate_planner(planner, f"{where}: [planner]")

    offsets: dict[str, tuple[float, ...]] = {n: (0.0,) * len(axes) for n in WORK_OFFSET_NAMES}
    for key, value in data.get("offsets", {}).items():
        if key not in WORK_OFFSET_NAMES:
            raise PlannerError(f"{where}: [offsets]: unknown work offset {key!r} (G54-G59)")
        if not isinstance(value, list) or len(value) != len(axes):
            raise PlannerError(
                f"{where}: [offsets] {key} needs {len(axes)} numbers ({' '.join(names)})")
        offsets[key] = tuple(_number({"v": v}, "v", f"{where}: [offsets] {key}") for v in value)

    machine = data.get("machine", {})
    return MachineSpec(name=str(machine.get("name", "machine")), axes=tuple(axes),
                       limits=limits, planner=planner, work_offsets=offsets, raw=data)


def load_machine(path: str | Path) -> MachineSpec:
    """Read and validate a machine configuration TOML file."""
    p = Path(path)
    try:
        data = tomllib.loads(p.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise PlannerError(f"{p}: machine configuration file not found") from None
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise PlannerError(f"{p}: not a valid TOML file: {exc}") from None
    return machine_from_dict(data, str(p))


