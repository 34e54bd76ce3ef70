"""Leadscrew compensation in the loop: what is added to each axis' set-point on its way to
the drive, and taken off its actual position on the way back, so that everything above the
loop (the planner, the DRO, the following error) stays in nominal positions.

For a compensated axis (``CompSpec``) the drive is sent

    set-point + curve(x) + take-up

where ``curve`` is the forward or reverse correction (``ScrewComp``), chosen by the direction
the set-point last moved: it keeps its direction while standing, and is 0 until the axis
first moves, as LinuxCNC's. ``x`` is the machine position (set-point - home offset) while the
axis is homed; while it is not (before its first homing, during a homing) the table is read
at a fixed position (where the axis was when it lost its homed state, else the table's first
line), so that the direction's part of it (the backlash) still acts and every homing latches
its switch with the same correction, whatever the axis did before. ``take-up`` absorbs every
step: when the direction reverses (forward to reverse at x: the backlash, the difference of
the two curves), when the axis first moves, or when homing changes where the table is read,
the take-up is shifted by the step so that the sum does not jump, and then runs to 0 along a
``Follower`` (acceleration and jerk limited, lands exactly) with the limits ``take_up`` leaves
from the axis' reserve. Nothing here allocates per cycle."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import ConfigurationError
from ..screw_comp import ScrewComp
from .handwheel import Follower

__all__ = ["REVERSAL", "CompSpec", "Compensation"]

#: a reversal of the set-point smaller than this share of (1 + |position|) is rounding, not a
#: change of direction
REVERSAL = 1e-9


@dataclass(frozen=True, slots=True)
class CompSpec:
    """Axis ``axis``'s corrections and the velocity, acceleration and jerk its take-up may use
    (``screw_comp.take_up_limits``)."""

    axis: int
    comp: ScrewComp
    take_up: tuple[float, float, float]

    def __post_init__(self) -> None:
        if self.axis < 0 or not all(x > 0.0 for x in self.take_up):
            raise ConfigurationError(f"compensation of axis {self.axis}: take-up limits {self.take_up} "
                                     "must be > 0")


class _Axis:
    """One compensated axis' state."""

    def __init__(self, spec: CompSpec, ts_s: float) -> None:
        self.i = spec.axis
        self.forward = spec.comp.forward
        self.reverse = spec.comp.reverse
        self.take = Follower(ts_s)
        self.take.start(0.0, *spec.take_up)
        self.on = False              # homed: the table read at the machine position
        self.fixed = spec.comp.nominal[0]   # where it is read while not homed
        self.up: bool | None = None  # the direction the set-point last moved (None: not yet)
        self.turn = 0.0              # the furthest set-point in that direction
        self.offset = 0.0            # the home offset: machine position = set-point - offset
        self.last = float("nan")     # the set-point of the last cycle

    def curve_at(self, ref: float, up: bool | None) -> float:
        if up is None:
            return 0.0
        x = ref - self.offset if self.on else self.fixed
        return self.forward(x) if up else self.reverse(x)

    def direction(self, ref: float) -> bool | None:
        """The direction after the set-point ``ref``: the first change sets it; a reversal
        counts once the set-point is back from its furthest point by more than the rounding
        of positions (``REVERSAL``), so noise in the last digits takes up no backlash."""
        last, up = self.last, self.up
        if last != last:
            return up                                    # (nan: the first cycle)
        if up is None:
            if ref != last:
                self.turn = ref
                return ref > last
            return None
        eps = REVERSAL * (1.0 + abs(ref))
        if (ref - self.turn > 0.0) == up:
            self.turn = ref                              # further on the way it goes
        elif abs(ref - self.turn) > eps:
            self.turn = ref
            return not up
        return up

    def step(self, ref: float) -> float:
        up = self.direction(ref)
        self.last = ref
        curve = self.curve_at(ref, up)
        if up != self.up:
            # a reversal (or the first move) switches curves: the step at x is the take-up's
            self.take.shift(self.curve_at(ref, self.up) - curve)
            self.up = up
        return curve + self.take.step(0.0)


class Compensation:
    """Every compensated axis of the loop; ``live`` (one float per axis) shows the correction
    sent last, ``live_on`` whether it is on."""

    def __init__(self, specs: tuple[CompSpec, ...], n_axes: int, ts_s: float, history: int,
                 live: np.ndarray | None = None, live_on: np.ndarray | None = None) -> None:
        self.axes = [_Axis(s, ts_s) for s in specs]
        self.by_axis: dict[int, _Axis] = {a.i: a for a in self.axes}     # (one each: WorkerConfig)
        self.active = bool(self.axes)
        self.value = np.zeros(n_axes)
        self.hist = np.zeros((history, n_axes))
        self.rows = [self.hist[k] for k in range(history)]
        self.live = live if live is not None else np.zeros(n_axes)
        self.live_on = live_on if live_on is not None else np.zeros(n_axes, dtype=np.int64)

    def switch(self, axis: int, on: bool, home_offset: float) -> bool:
        """``axis`` homed (the table read at its machine position, set-point - ``home_offset``)
        or not (read where it stands now); the step it makes is taken up. False: the axis has
        no compensation."""
        a = self.by_axis.get(axis)
        if a is None:
            return False
        if on == a.on and (not on or home_offset == a.offset):
            return True
        ref = a.last if a.last == a.last else 0.0
        before = a.curve_at(ref, a.up)
        if a.on and not on:
            a.fixed = ref - a.offset
        a.on, a.offset = on, home_offset
        a.take.shift(before - a.curve_at(ref, a.up))
        self.live_on[axis] = int(on)
        return True

    def command(self, ref: np.ndarray, out: np.ndarray, row: int) -> None:
        """``out`` := ``ref`` + the corrections of this cycle, kept in history row ``row``."""
        np.copyto(out, ref)
        if self.active:
            value = self.value
            for a in self.axes:
                value[a.i] = a.step(float(ref[a.i]))
            np.add(out, value, out=out)
            np.copyto(self.live, value)
        np.copyto(self.rows[row], self.value)

    def hold(self, row: int) -> None:
        """A cycle without set-points (drives off, homing by the drive): the corrections stay."""
        np.copyto(self.rows[row], self.value)

    def nominal(self, raw: np.ndarray, row: int) -> None:
        """``raw`` (the drives' positions) less the corrections sent with the set-points they
        answer (history row ``row``), in place."""
        if self.active:
            np.subtract(raw, self.rows[row], out=raw)
