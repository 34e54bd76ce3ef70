"""Interpolation at the sample period Ts (paper section 3.3, Eq. 16-17).

Sample k is at time t_k = k Ts on one global grid. Three methods (``planner.interpolation``):

* ``"exact"`` (default): s(t) of the move's closed-form profile, mapped through the exact
  geometry (for arcs and helices the angle parameter is s / |R'|, |R'| constant).
* ``"taylor"``: Eq. 16, step by step: S_{k+1} = S_k + V(t_k) Ts + A(t_k) Ts^2 / 2 with V, A
  of the profile at t_k; for our curves |R'| is constant and R'.R'' = 0, so stepping the
  path length is stepping the arc parameter. S runs over the whole program (a cumulative
  sum carried across chunks), so it drifts from the exact s(t) by the neglected jerk term
  (about J Ts^3 / 12 per phase switch, partly cancelling); the limit report shows it.
* ``"classic"``: Eq. 17, constant parameter increment: every move at its cruise speed
  min(F, Vmax), a whole number of samples per move, no soft start (Fig. 11's comparison).

Everything is vectorised over chunks of samples spanning many moves: one ``searchsorted``
finds each sample's move, then the profile and the geometry are evaluated for the whole
chunk. Memory is bounded by the chunk size.

The machine runs the same evaluator: ``Interpolator.at`` takes planned times that are not on
the grid (the controller's time scaling for feed hold and override advances planned time by
sigma Ts per sample) and applies the same method, so what the drives get is what
``cnc-plan --interp`` shows: exact and classic are the closed form at those times, Taylor
steps Eq. 16 over the actual increments of planned time.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from planner.core.errors import PlannerError
from planner.geometry.movetable import MoveTable, RowJoin, concat_tables
from planner.motion.lookahead import PlannedBlock
from planner.motion.profile import Profiles, build_profiles

__all__ = ["INTERPOLATIONS", "Interpolator", "SampleChunk", "Segment", "SegmentJoin", "first_sample_at",
           "make_segment"]

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
    profiles: Profiles  # their vs, ve: each move's start and end speed
    v_prog: np.ndarray
    t0: np.ndarray  # (n,) start time of each move
    t_end: float  # end of the segment's time span (after the last move's dwell)
    s0: np.ndarray  # (n,) cumulative path length at each move's start
    s_end: float
    # the boundary tables ``state`` made last, with the rows they are of (the machine asks for
    # a few set-points at a time, mostly within the same one or two moves); one item, read and
    # replaced whole, as threads may share a segment
    _tables_memo: list[tuple[int, int, tuple[np.ndarray, ...]]] = field(
        default_factory=lambda: [(-1, -1, ())], init=False, repr=False, compare=False)

    def state(self, t: np.ndarray, need_va: bool = False):
        """(row, s) or (row, s, v, a) at global times t (closed form, vectorised)."""
        prof = self.profiles
        if t.shape[0] > 0 and (t.shape[0] == 1 or (t[0] <= t[-1] and np.all(t[1:] >= t[:-1]))):
            # times in order (the usual case): the moves from the first time's to the last's
            r0, r1 = np.searchsorted(self.t0, t[[0, -1]], side="right") - 1
            lo, hi = max(int(r0), 0), max(int(r1), 0)
            uniq = np.arange(lo, hi + 1)
            lo_m, hi_m, tables = self._tables_memo[0]
            if lo_m != lo or hi_m != hi:
                tables = self._tables(prof, uniq)
                self._tables_memo[0] = (lo, hi, tables)
            t_b, s_b, v_b, a_b, ph = tables
        else:
            row = np.searchsorted(self.t0, t, side="right") - 1
            uniq = np.unique(np.clip(row, 0, None))
            t_b, s_b, v_b, a_b, ph = self._tables(prof, uniq)
        idx = np.searchsorted(ph, t, side="right") - 1
        np.clip(idx, 0, None, out=idx)
        local = idx // 7
        phase = idx - 7 * local
        row = uniq[local]
        flat = idx + local  # the same phase in the (u, 8) tables
        t_b = t_b.ravel()
        dt = np.clip(t - ph[idx], 0.0, t_b[flat + 1] - t_b[flat])
        a0 = a_b.ravel()[flat]
        j6 = prof.phase_jerk(row, phase) / 6.0
        v0 = v_b.ravel()[flat]
        s = s_b.ravel()[flat] + dt * (v0 + dt * (0.5 * a0 + dt * j6))
        length = self.table.length[row]
        s = np.where(t >= self.t0[row] + prof.duration[row], length, np.minimum(s, length))
        if not need_va:
            return row, s
        v = v0 + dt * (a0 + 3.0 * j6 * dt)
        a = a0 + 6.0 * j6 * dt
        return row, s, v, a

    def _tables(self, prof: Profiles, uniq: np.ndarray) -> tuple[np.ndarray, ...]:
        """The boundary tables of the moves ``uniq`` these times fall in, each made once, and
        the absolute start of each of their phases (in time order): one search finds move and
        phase, the last phase started by t."""
        t_b, s_b, v_b, a_b = prof.tables(uniq)
        ph = (self.t0[uniq][:, None] + t_b[:, :7]).ravel()
        return t_b, s_b, v_b, a_b, ph


def first_sample_at(t: float, ts: float) -> int:
    """Smallest k with k * ts >= t (exact in floating point). The quotient's rounding moves
    k by a step or two at the most; the corrections are bounded, so that a time beyond a
    float's resolution of whole samples (where k * ts no longer changes with k) still ends."""
    k = max(math.ceil(t / ts), 0)
    for _ in range(4):
        if k > 0 and (k - 1) * ts >= t:
            k -= 1
        elif k * ts < t:
            k += 1
        else:
            break
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
    t0 = bounds[:-1]
    prof = shared_speeds(prof, v_prog)
    return Segment(table, prof, v_prog, t0, float(bounds[-1]), s_bounds[:-1], float(s_bounds[-1]))


def shared_speeds(prof: Profiles, v_prog: np.ndarray) -> Profiles:
    """The same profiles holding each speed once: a move ends at the speed the next one starts
    with, so ``ve[:-1]`` and ``vs[1:]`` are the same numbers (one array of joint speeds, ``vs``
    and ``ve`` views of it), and the cruise cap is the programmed speed wherever the path
    does not lower it (``vc`` is then ``v_prog``). Shared only where equal to the bit: 16 of
    the 177 bytes a move of a plan of millions of moves."""
    vs, ve, vc = prof.vs, prof.ve, prof.vc
    changes: dict[str, np.ndarray] = {}
    if len(vs) > 1 and vs.strides[0] and ve.strides[0] and np.array_equal(ve[:-1], vs[1:]):
        joint = np.empty(len(vs) + 1)
        joint[:-1] = vs
        joint[-1] = ve[-1]
        changes["vs"], changes["ve"] = joint[:-1], joint[1:]
    if vc is not v_prog and vc.strides[0] and v_prog.strides[0] and np.array_equal(vc, v_prog):
        changes["vc"] = v_prog
    return replace(prof, **changes) if changes else prof


_OWN_COLUMNS = ("v_prog", "t0", "s0")


class SegmentJoin:
    """Consecutive segments (each starting where the one before ends) joined into one as they
    come, each let go once added: the same as ``make_segment`` of all their blocks at once,
    built in pieces (profiles of a few thousand moves need far smaller temporaries than those
    of millions), in the memory of the whole plan plus one segment.

    ``moves``: how many moves the segments hold in all. ``positions``: the program's
    (n + 1, d) joint positions, when the segments hold all its moves: the table's start and
    end are then views of them (48 bytes a move not copied). ``columns``: the program's own
    columns of the table's line, kind and exact stop: the table takes them as they are while
    every segment's rows are theirs (6 bytes a move not copied); a column a segment differs
    from is joined from the segments as the others. (Taking the program's feed and length too
    saved 16 bytes more but made the Taylor interpolation of the sphere finishing program 30 %
    slower, measured over three interleaved runs; the cause was not found.)"""

    PROGRAM_COLUMNS = ("line", "kind", "exact_stop")

    def __init__(self, moves: int, positions: np.ndarray | None = None,
                 columns: dict[str, np.ndarray] | None = None) -> None:
        self._shared = {} if positions is None else {"start": positions[:-1], "end": positions[1:]}
        self._program = {name: col for name, col in (columns or {}).items()
                         if name in self.PROGRAM_COLUMNS and len(col) == moves}
        self._moves = moves
        self._rows = 0  # the rows filled so far
        self._table = {name: RowJoin(moves) for name in MoveTable.__slots__
                       if name not in self._shared and name not in self._program}
        # a profile's length is its move's (build_profiles keeps the very array)
        self._prof = {name: RowJoin(moves) for name in Profiles.__slots__ if name != "length_mm"}
        self._own = {name: RowJoin(moves) for name in _OWN_COLUMNS}
        self._last: Segment | None = None
        self._count = 0

    def add(self, seg: Segment) -> None:
        # the first segment is copied only once a second one comes: a plan of one segment
        # (most programs) is that segment, not a copy of it
        if self._count == 1:
            assert self._last is not None
            self._fill(self._last)
        if self._count >= 1:
            self._fill(seg)
        self._last = seg
        self._count += 1

    def _fill(self, seg: Segment) -> None:
        lo, k = self._rows, len(seg.table)
        for name in list(self._program):
            if not np.array_equal(getattr(seg.table, name), self._program[name][lo:lo + k]):
                # the segment's rows differ: the column is joined from here on, its rows so
                # far taken from the program's (they were the same)
                join = RowJoin(self._moves)
                if lo:
                    join.add(self._program[name][:lo])
                self._table[name] = join
                del self._program[name]
        for name, col in self._table.items():
            col.add(getattr(seg.table, name))
        self._rows += k
        for name, col in self._prof.items():
            col.add(getattr(seg.profiles, name))
        for name, col in self._own.items():
            col.add(getattr(seg, name))

    def result(self) -> Segment:
        last = self._last
        if last is None:
            raise ValueError("no segment to join")
        if self._count == 1:
            return last
        given = {**self._shared, **self._program}
        table = MoveTable(**{name: given[name] if name in given else self._table[name].result()
                             for name in MoveTable.__slots__})
        profiles = Profiles(*(self._prof[name].result() if name != "length_mm" else table.length
                              for name in Profiles.__slots__))
        cols = {name: col.result() for name, col in self._own.items()}
        profiles = shared_speeds(profiles, cols["v_prog"])
        return Segment(table, profiles, cols["v_prog"], cols["t0"], last.t_end, cols["s0"], last.s_end)


class Interpolator:
    """Turns sample index ranges of segments into SampleChunks (keeps Taylor's state)."""

    def __init__(self, interpolation: str, ts: float):
        if interpolation not in INTERPOLATIONS:
            raise PlannerError(f"interpolation must be one of {INTERPOLATIONS}, got {interpolation!r}")
        self.interpolation = interpolation
        self.ts = ts
        self._carry: float | None = None  # Taylor: path length S of the next sample
        # Taylor at arbitrary times: (tau, S, V, A) of the last sample given to ``at``
        self.at_state: tuple[float, float, float, float] | None = None

    def samples(self, seg: Segment, k0: int, k1: int) -> SampleChunk:
        t = np.arange(k0, k1, dtype=float) * self.ts
        if self.interpolation == "taylor":
            _, _, v, a = seg.state(t, need_va=True)
            s_glob = self._taylor(seg, v, a)
            m = np.searchsorted(seg.s0, s_glob, side="right") - 1
            np.clip(m, 0, len(seg.table) - 1, out=m)
            s = np.clip(s_glob - seg.s0[m], 0.0, seg.table.length[m])
        else:
            m, s = seg.state(t)
        q = seg.table.positions(m, s)
        return SampleChunk(t, q, seg.s0[m] + s, seg.table.line[m], seg.table.index[m].astype(np.int32))

    def at(self, seg: Segment, tau: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(q, row, s) at non-decreasing planned times ``tau`` (not necessarily on the grid):
        axis positions, the move's row in the segment and the path length within it.

        Taylor: S_{k+1} = S_k + V(tau_k) dtau_k + A(tau_k) dtau_k^2 / 2 with dtau_k the actual
        increment, carried across calls in ``at_state`` (the first call starts at the exact
        s(tau_0)); with tau_k = k Ts this is ``samples``' Eq. 16 step for step."""
        tau = np.asarray(tau, dtype=float)
        if self.interpolation != "taylor" or tau.shape[0] == 0:
            row, s = seg.state(tau)
            return seg.table.positions(row, s), row, s
        row_e, s_e, v, a = seg.state(tau, need_va=True)
        st = self.at_state
        if st is None:
            st = (float(tau[0]), float(seg.s0[row_e[0]] + s_e[0]), float(v[0]), float(a[0]))
        t_prev = np.concatenate([[st[0]], tau[:-1]])
        v_prev = np.concatenate([[st[2]], v[:-1]])
        a_prev = np.concatenate([[st[3]], a[:-1]])
        dt = tau - t_prev
        s_glob = st[1] + np.cumsum(v_prev * dt + 0.5 * a_prev * dt * dt)
        self.at_state = (float(tau[-1]), float(s_glob[-1]), float(v[-1]), float(a[-1]))
        row = np.searchsorted(seg.s0, s_glob, side="right") - 1
        np.clip(row, 0, len(seg.table) - 1, out=row)
        s = np.clip(s_glob - seg.s0[row], 0.0, seg.table.length[row])
        return seg.table.positions(row, s), row, s

    def _taylor(self, seg: Segment, v: np.ndarray, a: np.ndarray) -> np.ndarray:
        """Eq. 16 (|R'| constant, R'.R'' = 0): S_{k+1} = S_k + V(t_k) Ts + A(t_k) Ts^2 / 2 on the
        cumulative path length, carried across chunks and moves (no re-synchronisation)."""
        ts = self.ts
        inc = v * ts + (0.5 * ts * ts) * a
        if inc.shape[0] == 0:
            return inc
        start = seg.s0[0] if self._carry is None else self._carry
        s = np.empty_like(inc)
        s[0] = start
        np.cumsum(inc[:-1], out=s[1:])
        s[1:] += start
        self._carry = float(s[-1] + inc[-1])
        return s
