"""Gantry axes: one axis driven by two drives, cycle by cycle.

The second drive of a gantry (the *follower*, e.g. Y2) is a worker axis of its own after the
machine's axes (its own position, following error, home switch, limit switches and alarms),
but nobody sends it set-points: every cycle the loop sends it the leader's set-point plus the
pair's offset ``d``,

    ref[follower] = ref[leader] + d

so the two sides move as one. ``d`` is what the two drives' positions differ by while the
gantry is square: taken as the pair stands whenever the drives are enabled (nothing jumps),
and set by homing, which latches each side on its own switch and then moves the follower
alone until ``d`` is the difference of the two latches less the difference of the two
switches' machine positions (``GantrySpec.switch_offset``).

The pair is watched every cycle the drives follow set-points: the *skew*
``act[follower] - act[leader] - d`` beyond ``skew_window`` for more than the loop's
following-error cycles is a quick stop of every drive with its own alarm (a motor that
stalled, a coupling that slipped, a side that hit something). Nothing here allocates.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import ConfigurationError

__all__ = ["Gantry", "GantrySpec", "check_gantries", "widen", "with_followers"]


@dataclass(frozen=True, slots=True)
class GantrySpec:
    """Axis ``axis`` is driven with worker axis ``follower`` too (its second drive).
    ``skew_window``: the largest skew (axis units) the pair may show while it moves.
    ``switch_offset``: the follower's home switch's machine position less the leader's (the
    squareness their two switches are set at)."""

    axis: int
    follower: int
    skew_window: float
    switch_offset: float = 0.0

    def __post_init__(self) -> None:
        if not self.skew_window > 0.0:
            raise ConfigurationError(f"gantry of axis {self.axis}: skew_window must be > 0, "
                                     f"got {self.skew_window}")
        if self.axis == self.follower:
            raise ConfigurationError(f"gantry of axis {self.axis}: the follower is another axis")


def check_gantries(specs: tuple[GantrySpec, ...], n_axes: int) -> None:
    """The followers are the last axes, each one gantry's, and each leader a machine axis."""
    g = len(specs)
    followers = sorted(s.follower for s in specs)
    if followers != list(range(n_axes - g, n_axes)):
        raise ConfigurationError(f"gantry followers {followers}: they are the last {g} of "
                                 f"{n_axes} axes, one each")
    for s in specs:
        if not 0 <= s.axis < n_axes - g:
            raise ConfigurationError(f"gantry of axis {s.axis}: not one of the {n_axes - g} "
                                     "machine axes")
    leaders = [s.axis for s in specs]
    if len(set(leaders)) != len(leaders):
        raise ConfigurationError(f"gantry leaders {leaders}: one follower each")


def widen(q: np.ndarray, specs: tuple[GantrySpec, ...]) -> np.ndarray:
    """Set-points of the machine's axes (N, n) with a column for each follower (its leader's:
    the loop adds the pair's offset)."""
    if not specs:
        return q
    out = np.empty((q.shape[0], q.shape[1] + len(specs)))
    out[:, :q.shape[1]] = q
    for s in specs:
        out[:, s.follower] = q[:, s.axis]
    return out


def with_followers(mask: int, specs: tuple[GantrySpec, ...]) -> int:
    """An axis mask with the followers of the gantries whose leaders it holds."""
    for s in specs:
        if mask >> s.axis & 1:
            mask |= 1 << s.follower
    return mask


class Gantry:
    """The pairs' offsets and skews (module docstring). ``skew`` is a per-axis array written
    at the followers' places (the snapshot's ``gantry_skew``)."""

    def __init__(self, specs: tuple[GantrySpec, ...], skew: np.ndarray, limit_cycles: int) -> None:
        self.leaders = [s.axis for s in specs]
        self.followers = [s.follower for s in specs]
        self.windows = [s.skew_window for s in specs]
        self.pairs = list(range(len(specs)))
        self.d = np.zeros(len(specs))
        self.over = [0] * len(specs)
        self.skew = skew
        self.limit_cycles = limit_cycles

    def hold(self, ref: np.ndarray) -> None:
        """The pairs as they stand in ``ref`` are square from now on."""
        for k in self.pairs:
            self.d[k] = ref[self.followers[k]] - ref[self.leaders[k]]
            self.over[k] = 0

    def follow(self, ref: np.ndarray) -> None:
        """Each follower's set-point: its leader's plus the pair's offset."""
        for k in self.pairs:
            ref[self.followers[k]] = ref[self.leaders[k]] + self.d[k]

    def check(self, act: np.ndarray) -> int:
        """The skews of this cycle; the follower of a pair whose skew stayed beyond its window
        longer than the limit (-1: none)."""
        for k in self.pairs:
            f = self.followers[k]
            e = act[f] - act[self.leaders[k]] - self.d[k]
            self.skew[f] = e
            if abs(e) > self.windows[k]:
                self.over[k] += 1
                if self.over[k] > self.limit_cycles:
                    return f
            else:
                self.over[k] = 0
        return -1
