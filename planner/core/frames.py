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
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace

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
    def rotation_rad(self) -> float:
        """The XY rotation in radians (the turn of a G18/G19 arc's plane about Z)."""
        return math.radians(self.rotation_deg)

    def _cos_sin(self) -> tuple[float, float]:
        theta = self.rotation_rad
        return math.cos(theta), math.sin(theta)

    @property
    def total(self) -> tuple[float, ...]:
        """G5x + G92 + tool per axis: the whole offset of an axis the rotation leaves alone."""
        return tuple(w + g + t for w, g, t in zip(self.g5x, self.g92, self.tool))

    @property
    def is_identity(self) -> bool:
        """Program coordinates are the machine's (no offset, no rotation)."""
        return not (any(self.g5x) or any(self.g92) or any(self.tool) or self.rotation_deg)

    def without_tool(self) -> Frame:
        """This frame without its tool length offset (what a G49 program reads)."""
        return replace(self, tool=(0.0,) * len(self.axes), tool_number=0)

    # ------------------------------------------------------------------ machine -> program
    def to_program(self, machine: Sequence[float] | np.ndarray) -> np.ndarray:
        """Program coordinates of machine position(s) (one row per position, or one vector):
        R(-rotation) (machine - G5x - tool) - G92 on X and Y, machine - (G5x + G92 + tool) on
        the rest (and on X and Y without a rotation)."""
        rel = np.array(machine, dtype=float)
        self.to_program_in_place(rel)
        return rel

    def to_program_in_place(self, points: np.ndarray) -> None:
        """``to_program`` written over ``points`` (float rows, or one vector): a drawn path of
        millions of points is converted without a copy of it."""
        xy = self._xy()
        if xy is None:
            points -= np.asarray(self.total)
            return
        ix, iy = xy
        x = points[..., ix] - self.g5x[ix] - self.tool[ix]
        y = points[..., iy] - self.g5x[iy] - self.tool[iy]
        points -= np.asarray(self.total)
        c, s = self._cos_sin()
        points[..., ix] = c * x + s * y - self.g92[ix]
        points[..., iy] = -s * x + c * y - self.g92[iy]

    def point_to_program(self, machine: Sequence[float]) -> list[float]:
        """``to_program`` of one position, in plain floats (the same operations in the same
        order: a reader that converts one point at a time pays no array per point)."""
        out = [q - t for q, t in zip(machine, self.total)]
        xy = self._xy()
        if xy is not None:
            ix, iy = xy
            out[ix], out[iy] = self.xy_to_program(machine[ix], machine[iy])
        return out

    def xy_to_program(self, x: float, y: float) -> tuple[float, float]:
        """Program X and Y of machine X and Y: R(-rotation) (machine - G5x - tool) - G92."""
        ix, iy = self.axes.index("X"), self.axes.index("Y")
        u, v = self.turn_back(x - self.g5x[ix] - self.tool[ix], y - self.g5x[iy] - self.tool[iy])
        return u - self.g92[ix], v - self.g92[iy]

    def turn_back(self, x: float, y: float) -> tuple[float, float]:
        """A machine XY vector in the system's turned frame: R(-rotation) (x, y)."""
        if self.rotation_deg == 0.0:
            return x, y
        c, s = self._cos_sin()
        return c * x + s * y, -s * x + c * y

    # ------------------------------------------------------------------ program -> machine
    def to_machine(self, program: Sequence[float] | np.ndarray) -> np.ndarray:
        """Machine coordinates of program position(s): R(rotation) (program + G92) + G5x + tool."""
        p = np.array(program, dtype=float) + np.asarray(self.g92)
        xy = self._xy()
        if xy is not None:
            ix, iy = xy
            c, s = self._cos_sin()
            x, y = p[..., ix].copy(), p[..., iy].copy()
            p[..., ix] = c * x - s * y
            p[..., iy] = s * x + c * y
        return p + np.asarray(self.g5x) + np.asarray(self.tool)

    def xy_to_machine(self, x: float, y: float) -> tuple[float, float]:
        """Machine X and Y of program X and Y: R(rotation) (program + G92) + G5x + tool."""
        ix, iy = self.axes.index("X"), self.axes.index("Y")
        u, v = self.turn(x + self.g92[ix], y + self.g92[iy])
        return u + self.g5x[ix] + self.tool[ix], v + self.g5x[iy] + self.tool[iy]

    def turn(self, x: float, y: float) -> tuple[float, float]:
        """A vector of the system's turned frame on the machine: R(rotation) (x, y)."""
        if self.rotation_deg == 0.0:
            return x, y
        c, s = self._cos_sin()
        return c * x - s * y, s * x + c * y

    # ------------------------------------------------------------------ offsets that read a value
    def origin_for(self, machine: Sequence[float] | np.ndarray, axis: int, value: float) -> tuple[float, ...]:
        """The G5x origin that makes machine position ``machine`` read ``value`` on ``axis`` in
        this frame, its other axes reading what they read now (``origin_reading``)."""
        return self.origin_reading(machine, {axis: float(value)})

    def origin_reading(self, machine: Sequence[float] | np.ndarray,
                       values: Mapping[int, float]) -> tuple[float, ...]:
        """The G5x origin with which machine position ``machine`` reads ``values`` (by axis
        column) in this frame, the other axes' origins kept (LinuxCNC's G10 L20). In a rotated
        system X and Y go together: the position read there keeps the one not given, and the
        origin moves so that both read as wanted."""
        m = [float(v) for v in machine]
        new = list(self.g5x)
        xy = self._xy()
        for i, value in values.items():
            if xy is None or i not in xy:
                new[i] = m[i] - self.g92[i] - self.tool[i] - value
        if xy is not None and (xy[0] in values or xy[1] in values):
            ix, iy = xy
            px, py = self.xy_to_program(m[ix], m[iy])
            px, py = values.get(ix, px), values.get(iy, py)
            u, v = self.turn(px + self.g92[ix], py + self.g92[iy])
            new[ix], new[iy] = m[ix] - self.tool[ix] - u, m[iy] - self.tool[iy] - v
        return tuple(new)

    def g92_reading(self, machine: Sequence[float], values: Mapping[int, float]) -> tuple[float, ...]:
        """The G92 offsets with which machine position ``machine`` reads ``values`` (by axis
        column), the other axes' kept (G92); on X and Y of a rotated system, in its turned
        frame."""
        new = list(self.g92)
        xy = self._xy()
        for i, value in values.items():
            if xy is not None and i in xy:
                unshifted = replace(self, g92=(0.0,) * len(self.axes)).xy_to_program(machine[xy[0]],
                                                                                    machine[xy[1]])
                new[i] = unshifted[xy.index(i)] - value
            else:
                new[i] = machine[i] - self.g5x[i] - self.tool[i] - value
        return tuple(new)

    def tool_reading(self, machine: Sequence[float], values: Mapping[int, float],
                     old: Sequence[float]) -> tuple[float, ...]:
        """The tool length offsets (machine frame) with which machine position ``machine``
        reads ``values`` (by axis column) in this frame, ``old`` kept on the other axes
        (LinuxCNC's G10 L10/L11). On X and Y of a rotated system the values are read in its
        turned frame, and an axis not given keeps the old offset's component along it."""
        new = [float(v) for v in old]
        xy = self._xy()
        for i, value in values.items():
            if xy is None or i not in xy:
                new[i] = machine[i] - self.g5x[i] - self.g92[i] - value
        if xy is not None and (xy[0] in values or xy[1] in values):
            ix, iy = xy
            tx, ty = self.without_tool().xy_to_program(machine[ix], machine[iy])
            old_u, old_v = self.turn_back(new[ix], new[iy])
            u = tx - values[ix] if ix in values else old_u
            v = ty - values[iy] if iy in values else old_v
            new[ix], new[iy] = self.turn(u, v)
        return tuple(new)
