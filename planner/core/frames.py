"""Where program coordinates sit on the machine: the one model of the offsets in force.

A program position maps onto the machine as LinuxCNC's canon composes the offsets:

    machine = R(rotation) (program + G92) + G5x + tool      on X and Y
    machine = program + G92 + G5x + tool                     on every other axis

where R turns X and Y about Z by the XY rotation of the coordinate system (G10 L2 R), G5x is
the origin of the system in use (G54-G59.3), G92 the axis offset (G92, G52) and ``tool`` the
tool length offset in effect (G43, G43.1, G43.2; zero after G49). The tool length offset is
not turned with the plane: it is the controlled point's offset on the machine. The inverse,
``to_program``, is what a program reads as its position (#5420-#5428) and what a relative DRO
shows: the tool tip in the program's coordinates.

The interpreter, the canonical calls, the preview and the panel's DRO and touch-off all use
this class, so the machine and what the operator reads cannot disagree.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

__all__ = ["PARAMETER_AXES", "SYSTEM_NAMES", "Frame", "system_name", "system_parameter_base"]

#: coordinate systems 1-9 by name, as LinuxCNC numbers them (#5220 holds the number)
SYSTEM_NAMES: tuple[str, ...] = ("G54", "G55", "G56", "G57", "G58", "G59", "G59.1", "G59.2", "G59.3")


#: the axes in the order of their parameters (#5221 X of G54, #5222 Y, ... #5229 W)
PARAMETER_AXES = "XYZABCUVW"


def system_name(system: int) -> str:
    """The G code of coordinate system ``system`` (1-9)."""
    return SYSTEM_NAMES[system - 1]


def system_parameter_base(system: int) -> int:
    """The parameter of X of coordinate system ``system`` (1-9): #5221 for G54, #5241 for G55
    ... #5381 for G59.3; the axes follow in ``PARAMETER_AXES`` order, the XY rotation is base + 9."""
    return 5221 + 20 * (system - 1)


@dataclass(frozen=True, slots=True)
class Frame:
    """The offsets in force at one point of a program (or at the panel), per axis in machine
    units (mm, degrees for rotary axes)."""

    axes: tuple[str, ...]
    g5x: tuple[float, ...]
    g92: tuple[float, ...]
    tool: tuple[float, ...]
    rotation_deg: float = 0.0
    system: int = 1                 # 1-9: G54 ... G59.3
    tool_number: int = 0            # the tool whose length is ``tool`` (0: none or given as values)

    @staticmethod
    def identity(axes: Sequence[str]) -> Frame:
        zero = (0.0,) * len(axes)
        return Frame(tuple(axes), zero, zero, zero)

    @property
    def system_name(self) -> str:
        return system_name(self.system)

    @property
    def has_tool_offset(self) -> bool:
        return any(self.tool)

    @property
    def has_g92(self) -> bool:
        return any(self.g92)

    def _xy(self) -> tuple[int, int] | None:
        if self.rotation_deg == 0.0 or "X" not in self.axes or "Y" not in self.axes:
            return None
        return self.axes.index("X"), self.axes.index("Y")

    @property
    def is_identity(self) -> bool:
        """Program coordinates are the machine's (no offset, no rotation)."""
        return not (any(self.g5x) or any(self.g92) or any(self.tool) or self.rotation_deg)

    def to_program(self, machine: Sequence[float] | np.ndarray) -> np.ndarray:
        """Program coordinates of machine position(s) (one row per position, or one vector):
        R(-rotation) (machine - G5x - tool) - G92."""
        rel = np.array(machine, dtype=float)
        self.to_program_in_place(rel)
        return rel

    def to_program_in_place(self, points: np.ndarray) -> None:
        """``to_program`` written over ``points`` (float rows, or one vector): a drawn path of
        millions of points is converted without a copy of it."""
        points -= np.asarray(self.g5x)
        points -= np.asarray(self.tool)
        xy = self._xy()
        if xy is not None:
            ix, iy = xy
            c, s = math.cos(math.radians(self.rotation_deg)), math.sin(math.radians(self.rotation_deg))
            x, y = points[..., ix].copy(), points[..., iy].copy()
            points[..., ix] = c * x + s * y
            points[..., iy] = -s * x + c * y
        points -= np.asarray(self.g92)

    def point_to_program(self, machine: Sequence[float]) -> list[float]:
        """``to_program`` of one position, in plain floats (the same operations in the same
        order: a reader that converts one point at a time pays no array per point)."""
        rel = [q - w - t for q, w, t in zip(machine, self.g5x, self.tool)]
        xy = self._xy()
        if xy is not None:
            ix, iy = xy
            c, s = math.cos(math.radians(self.rotation_deg)), math.sin(math.radians(self.rotation_deg))
            x, y = rel[ix], rel[iy]
            rel[ix], rel[iy] = c * x + s * y, -s * x + c * y
        return [r - g for r, g in zip(rel, self.g92)]

    def to_machine(self, program: Sequence[float] | np.ndarray) -> np.ndarray:
        """Machine coordinates of program position(s): R(rotation) (program + G92) + G5x + tool."""
        p = np.array(program, dtype=float) + np.asarray(self.g92)
        xy = self._xy()
        if xy is not None:
            ix, iy = xy
            c, s = math.cos(math.radians(self.rotation_deg)), math.sin(math.radians(self.rotation_deg))
            x, y = p[..., ix].copy(), p[..., iy].copy()
            p[..., ix] = c * x - s * y
            p[..., iy] = s * x + c * y
        return p + np.asarray(self.g5x) + np.asarray(self.tool)

    def origin_for(self, machine: Sequence[float] | np.ndarray, axis: int, value: float) -> tuple[float, ...]:
        """The G5x origin that makes machine position ``machine`` read ``value`` on ``axis`` in
        this frame, its other axes reading what they read now (LinuxCNC's G10 L20: in a rotated
        system X and Y go together, the origin moving so that both read as wanted)."""
        now = self.to_program(machine)
        want = now.copy()
        want[axis] = float(value)
        # machine = R (want + g92) + origin + tool  ->  origin = machine - tool - R (want + g92)
        turned = Frame(self.axes, (0.0,) * len(self.axes), self.g92, (0.0,) * len(self.axes),
                       self.rotation_deg).to_machine(want)
        origin = np.asarray(machine, dtype=float) - np.asarray(self.tool) - turned
        new = list(self.g5x)
        new[axis] = float(origin[axis])
        xy = self._xy()
        if xy is not None and axis in xy:
            for k in xy:
                new[k] = float(origin[k])
        return tuple(new)
