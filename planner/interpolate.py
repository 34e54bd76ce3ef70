"""Interpolation at the sample period Ts (paper section 3.3, Eq. 16-17).

Sample k is at time t_k = k Ts on one global grid. Three methods (``planner.interpolation``):

* ``"exact"`` (default): s(t) of the move's closed-form profile, mapped through the exact
  geometry (for arcs and helices the angle parameter is s / |R'|, |R'| constant).
* ``"taylor"``: Eq. 16, step by step: s_{k+1} = s_k + V(t_k) Ts + A(t_k) Ts^2 / 2 with V, A
  of the move's profile; for our curves |R'| is constant and R'.R'' = 0, so stepping s is
  stepping the angle. Each move starts from the exact s of its first sample (the paper runs
  every G-code line from its own start); the step sum is a segmented cumulative sum.
* ``"classic"``: Eq. 17, constant parameter increment: every move at its cruise speed
  min(F, Vmax), a whole number of samples per move, no soft start (Fig. 11's comparison).

Everything is vectorised over chunks of samples spanning many moves: one ``searchsorted``
finds each sample's move, then the profile and the geometry are evaluated for the whole
chunk. Memory is bounded by the chunk size.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from planner.errors import PlannerError
from planner.lookahead import PlannedBlock
from planner.movetable import MoveTable, concat_tables
from planner.profile import Profiles, build_profiles

__all__ = ["INTERPOLATIONS", "Interpolator", "SampleChunk", "Segment", "first_sample_at", "make_segment"]

INTERPOLATIONS = ("exact", "taylor", "classic")


@dataclass(frozen=True, slots=True, eq=False)
class SampleChunk:
    """Consecutive set-points: time (N,), axis positions (N, n_axes) in mm/deg, cumulative
    path length s (N,) in mm, source line (N,) and move index (N,)."""

    t: np.ndarray
    q: np.ndarray
    s: np.ndarray
    line: np.ndarray
    move_index: np.ndarray

    def __len__(self) -> int:
        return int(self.t.shape[0])

    @staticmethod
    def concat(chunks: list[SampleChunk], n_axes: int) -> SampleChunk:
        if not chunks:
            return SampleChunk(np.zeros(0), np.zeros((0, n_axes)), np.zeros(0),
                               np.zeros(0, np.int32), np.zeros(0, np.int32))
        return SampleChunk(*(np.concatenate([getattr(c, f) for c in chunks]) for f in SampleChunk.__slots__))


@dataclass(frozen=True, slots=True, eq=False)
class Segment:
    """Moves with profiles and start times on the global clock."""

    table: MoveTable
    profiles: Profiles
    vs: np.ndarray
    ve: np.ndarray
    v_prog: np.ndarray
    t0: np.ndarray  # (n,) start time of each move
    t_end: float  # end of the segment's time span (after the last move's dwell)
    s0: np.ndarray  # (n,) cumulative path length at each move's start
    s_end: float


def first_sample_at(t: float, ts: float) -> int:
    """Smallest k with k * ts >= t (exact in floating point)."""
    k = max(math.ceil(t / ts), 0)
    while k > 0 and (k - 1) * ts >= t:
        k -= 1
    while k * ts < t:
        k += 1
    return k


def make_segment(blocks: list[PlannedBlock], interpolation: str, ts: float, t_start: float,
                 s_start: float) -> Segment:
    """Profiles and the timeline of consecutive planned blocks, from time t_start."""
    if interpolation not in INTERPOLATIONS:
        raise PlannerError(f"interpolation must be one of {INTERPOLATIONS}, got {interpolation!r}")
    table = concat_tables([b.table for b in blocks])
    vs = np.concatenate([b.vs for b in blocks])
    ve = np.concatenate([b.ve for b in blocks])
    vc = np.concatenate([b.limits.vc for b in blocks])
    a_t = np.concatenate([b.limits.a_t for b in blocks])
    j_t = np.concatenate([b.limits.j_t for b in blocks])
    v_prog = np.concatenate([b.limits.v_prog for b in blocks])
    dwell = np.concatenate([b.dwell_after for b in blocks])
    if interpolation == "classic":
        # Eq. 17: constant increment at min(F, Vmax) (the paper's cruise), whole samples per move.
        v = v_prog
        prof = build_profiles(table.length, v, v, v, a_t, j_t)
        steps = np.ceil(table.length / (v * ts) - 1e-9)
        dwell = dwell + np.maximum(steps * ts - prof.duration, 0.0)
    else:
        prof = build_profiles(table.length, vs, ve, vc, a_t, j_t)
    bounds = np.cumsum(np.concatenate([[t_start], prof.duration + dwell]))
    s_bounds = np.cumsum(np.concatenate([[s_start], table.length]))
    return Segment(table, prof, vs, ve, v_prog, bounds[:-1], float(bounds[-1]), s_bounds[:-1],
                   float(s_bounds[-1]))


class Interpolator:
    """Turns sample index ranges of segments into SampleChunks (keeps Taylor's state)."""

    def __init__(self, interpolation: str, ts: float):
        if interpolation not in INTERPOLATIONS:
            raise PlannerError(f"interpolation must be one of {INTERPOLATIONS}, got {interpolation!r}")
        self.interpolation = interpolation
        self.ts = ts
        self._carry: tuple[int, float, float] | None = None  # (move, s, increment) of last sample

    def samples(self, seg: Segment, k0: int, k1: int) -> SampleChunk:
        ts = self.ts
        t = np.arange(k0, k1, dtype=float) * ts
        n = len(seg.table)
        m = np.searchsorted(seg.t0, t, side="right") - 1
        np.clip(m, 0, n - 1, out=m)
        tau = t - seg.t0[m]
        if self.interpolation == "taylor":
            s_ex, v, a, _ = seg.profiles.evaluate(m, tau)
            s = self._taylor(seg, m, s_ex, v, a)
        else:
            s = seg.profiles.evaluate_s(m, tau)
        q = seg.table.positions(m, s)
        return SampleChunk(t, q, seg.s0[m] + s, seg.table.line[m], seg.table.index[m].astype(np.int32))

    def _taylor(self, seg: Segment, m, s_ex, v, a) -> np.ndarray:
        ts = self.ts
        gm = seg.table.index[m]
        inc = v * ts + (0.5 * ts * ts) * a  # Eq. 16 for |R'| constant
        n = gm.shape[0]
        if n == 0:
            return s_ex
        new = np.empty(n, dtype=bool)
        new[1:] = gm[1:] != gm[:-1]
        carry = self._carry
        new[0] = carry is None or carry[0] != gm[0]
        base = s_ex.copy()
        if not new[0]:
            base[0] = carry[1] + carry[2]
        flag = new.copy()
        flag[0] = True
        starts = np.flatnonzero(flag)
        seg_id = np.cumsum(flag) - 1
        prefix = np.empty(n)
        prefix[0] = 0.0
        np.cumsum(inc[:-1], out=prefix[1:])
        s = base[starts][seg_id] + (prefix - prefix[starts][seg_id])
        np.clip(s, 0.0, seg.table.length[m], out=s)
        self._carry = (int(gm[-1]), float(s[-1]), float(inc[-1]))
        return s
