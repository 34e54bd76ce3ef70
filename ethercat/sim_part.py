"""A simulated workpiece for the simulated probe: a block on the table, turned about Z, with a
bore in it or a boss on it, touched by a ball-ended stylus.

The part is a signed distance function (mm): negative inside the material, the distance to
its surface outside. The stylus' ball of radius ``tip_radius_mm`` has its lowest point
``tip_length_mm`` below the spindle's gauge line (the tool length the table gives the probe),
so it touches when the distance at the ball's centre is at most its radius. The same function
answers the simulated bus once a cycle (``SimBus``) and the tests that check the probing
routines against the truth, so both see one part.

The block stands from ``top_mm - depth_mm`` up to ``top_mm``, its centre at (``x_mm``,
``y_mm``), ``half_x_mm`` by ``half_y_mm`` from it along its own axes, turned by
``angle_deg`` about Z (counter-clockwise seen from above). A bore goes through it; a boss
stands ``boss_height_mm`` on its top; both at (``feature_x_mm``, ``feature_y_mm``) in the
machine's frame with radius ``feature_radius_mm``. A pocket goes through it there, square to the
block, ``pocket_half_x_mm`` by ``pocket_half_y_mm`` from its centre. Lengths are machine
coordinates (mm).
"""

from __future__ import annotations

import enum
import math
from dataclasses import astuple, dataclass, fields

__all__ = ["Feature", "SimPart"]


class Feature(enum.IntEnum):
    NONE = 0
    BORE = 1
    BOSS = 2
    POCKET = 3


@dataclass(frozen=True, slots=True)
class SimPart:
    x_mm: float = 0.0
    y_mm: float = 0.0
    half_x_mm: float = 50.0
    half_y_mm: float = 30.0
    angle_deg: float = 0.0
    top_mm: float = 0.0
    depth_mm: float = 40.0
    feature: Feature = Feature.NONE
    feature_x_mm: float = 0.0
    feature_y_mm: float = 0.0
    feature_radius_mm: float = 10.0
    boss_height_mm: float = 10.0
    tip_radius_mm: float = 1.0
    tip_length_mm: float = 0.0
    pocket_half_x_mm: float = 10.0
    pocket_half_y_mm: float = 10.0

    def shifted(self, dx: float, dy: float, dz: float) -> SimPart:
        """The same part ``dx``, ``dy``, ``dz`` further (machine to drive coordinates)."""
        return SimPart(self.x_mm + dx, self.y_mm + dy, self.half_x_mm, self.half_y_mm, self.angle_deg,
                       self.top_mm + dz, self.depth_mm, self.feature, self.feature_x_mm + dx,
                       self.feature_y_mm + dy, self.feature_radius_mm, self.boss_height_mm,
                       self.tip_radius_mm, self.tip_length_mm, self.pocket_half_x_mm, self.pocket_half_y_mm)

    # ------------------------------------------------------------------ geometry
    def distance(self, x: float, y: float, z: float) -> float:
        """Signed distance from the point to the part's surface (mm; negative inside)."""
        a = math.radians(self.angle_deg)
        c, s = math.cos(a), math.sin(a)
        dx, dy = x - self.x_mm, y - self.y_mm
        u, v = c * dx + s * dy, -s * dx + c * dy          # in the block's own frame
        mid = self.top_mm - self.depth_mm / 2.0
        block = _box(u, v, z - mid, self.half_x_mm, self.half_y_mm, self.depth_mm / 2.0)
        if self.feature is Feature.NONE:
            return block
        if self.feature is Feature.POCKET:       # through the block, square to it
            fx, fy = self.feature_x_mm - self.x_mm, self.feature_y_mm - self.y_mm
            pu, pv = c * fx + s * fy, -s * fx + c * fy
            pocket = _box(u - pu, v - pv, 0.0, self.pocket_half_x_mm, self.pocket_half_y_mm, math.inf)
            return max(block, -pocket)
        r = math.hypot(x - self.feature_x_mm, y - self.feature_y_mm) - self.feature_radius_mm
        if self.feature is Feature.BORE:
            return max(block, -r)
        h = self.boss_height_mm / 2.0
        boss = _cylinder(r, z - (self.top_mm + h), h)
        return min(block, boss)

    def touches(self, x: float, y: float, z_gauge: float) -> bool:
        """Whether the stylus touches with the spindle's gauge line at (x, y, z_gauge)."""
        r = self.tip_radius_mm
        return self.distance(x, y, z_gauge - self.tip_length_mm + r) <= r

    # ------------------------------------------------------------------ as numbers
    def values(self) -> tuple[float, ...]:
        """Every field as a number, in order (what the worker's injections carry)."""
        return tuple(float(v) for v in astuple(self))

    @staticmethod
    def from_values(values: tuple[float, ...] | list[float]) -> SimPart:
        names = [f.name for f in fields(SimPart)]
        if len(values) != len(names):
            raise ValueError(f"a simulated part has {len(names)} values, got {len(values)}")
        kw: dict[str, float | Feature] = dict(zip(names, (float(v) for v in values), strict=True))
        kw["feature"] = Feature(int(kw["feature"]))
        return SimPart(**kw)  # type: ignore[arg-type]


#: how many numbers a part is (``SimPart.values``)
PART_VALUES = len(fields(SimPart))


def _box(x: float, y: float, z: float, bx: float, by: float, bz: float) -> float:
    qx, qy, qz = abs(x) - bx, abs(y) - by, abs(z) - bz
    outside = math.sqrt(max(qx, 0.0) ** 2 + max(qy, 0.0) ** 2 + max(qz, 0.0) ** 2)
    return outside + min(max(qx, qy, qz), 0.0)


def _cylinder(radial: float, z: float, half_height: float) -> float:
    """A capped cylinder from its radial distance (to the side) and its height's."""
    qz = abs(z) - half_height
    outside = math.sqrt(max(radial, 0.0) ** 2 + max(qz, 0.0) ** 2)
    return outside + min(max(radial, qz), 0.0)
