"""The machine's leadscrew compensation, read with its configuration: per axis ``backlash`` or
a ``comp_file`` (LinuxCNC's COMP_FILE, ``comp_file_type`` 0 or 1; a relative name is found
beside the configuration file), checked against the axis' travel and against the share of its
limits ``comp_reserve`` keeps from motion (``ethercat.screw_comp``). The result is what the
1 ms loop applies (``ethercat.worker.CompSpec``)."""

from __future__ import annotations

import os
from pathlib import Path

from ethercat.errors import ConfigurationError
from ethercat.screw_comp import ScrewComp, read_comp_file, take_up_limits
from ethercat.worker import CompSpec
from planner.core.machine import AxisSpec, MachineSpec
from planner.core.schema import Locator

__all__ = ["axis_travel", "comp_path", "compensation_of"]


def comp_path(name: str, base: str | os.PathLike[str] | None) -> Path:
    """Where ``comp_file = name`` is: as written when absolute, else beside the configuration."""
    p = Path(name).expanduser()
    return p if p.is_absolute() or base is None else Path(base) / p


def axis_travel(ax: AxisSpec) -> tuple[float, float]:
    return float(ax.min_pos), float(ax.max_pos)


def compensation_of(machine: MachineSpec, loc: Locator, base: str | os.PathLike[str] | None
                    ) -> tuple[CompSpec, ...]:
    """Every compensated axis' corrections and take-up limits; a problem raises the reader's
    error at the axis' key (a file that cannot be read, a reserve too small) or at the table's
    own line."""
    specs: list[CompSpec] = []
    for i, ax in enumerate(machine.axes):
        if not ax.compensated:
            continue
        if ax.wrapped:
            raise loc.fail(("axes", i, "comp_file" if ax.comp_file else "backlash"),
                           f"a wrapped rotary axis has no ends for a table (axis {ax.name})")
        try:
            if ax.comp_file:
                path = comp_path(ax.comp_file, base)
                if not path.is_file():
                    raise loc.fail(("axes", i, "comp_file"), f"{path}: no such file (axis {ax.name})")
                comp: ScrewComp = read_comp_file(path, ax.comp_file_type, axis_travel(ax))
            else:
                comp = ScrewComp.backlash(ax.backlash)
            take = take_up_limits(comp, axis_travel(ax), (ax.v_max, ax.a_max, ax.j_max), ax.comp_reserve,
                                  machine.planner.ts_s)
        except ConfigurationError as exc:
            key = "comp_file" if ax.comp_file else "backlash"
            raise loc.fail(("axes", i, key), f"{exc} (axis {ax.name})") from None
        specs.append(CompSpec(i, comp, take))
    return tuple(specs)

