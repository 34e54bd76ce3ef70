"""The one limit meter: velocity, acceleration and jerk of sampled motion, measured by finite
differences of the set-points and compared with the machine's limits.

Every place that asks "did this motion stay within its limits?" measures the same way here:
``Plan.limit_report`` (``cnc-plan --json``), the controller's checks of what it actually sent
to the drives (feed hold, override, path stops), and the diagnostics page's v/a/j plot.

Stencils. The k-th difference of samples n-k .. n divided by Ts^k. Finite differences over a
joint between two moves see the joint itself (a tangent break, a curvature jump), whose
figures the planner reports separately, so jerk stencils that span a joint never count
against the jerk limits; they are reported as joint jerk. Whether the tangential (path
length) velocity and acceleration stencils that span a joint count is the caller's choice
(``across_joints``): a plan's report counts them, the execution check does not (the path
length's second difference across a tangent break is not an acceleration of any axis).

Rounding. A k-th difference of positions of magnitude |q| carries a rounding noise of about
|q| eps / Ts^k; that much is allowed on top of each limit (``noise``), with |q| bounded by the
machine's travel (or a scale the caller gives), so the allowance never depends on how the
samples were cut into chunks. Violations are judged with a small relative tolerance per order
(``REL_TOL``).

The meter streams: ``add`` takes consecutive chunks and keeps the last three samples, so
stencils across chunk borders are measured once and memory is bounded by the chunk.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from planner.core.machine import MachineSpec

try:  # the stencils in C (planner/motion/_meter.c), built by `pip install -e .`
    import planner.motion._meter as _meter
except ImportError:  # no compiler where it was installed: the NumPy form, the reference
    _meter = None  # type: ignore[assignment]

__all__ = ["KINDS", "REL_TOL", "LimitMeter", "PathSpeedLimits", "Worst", "check_limits", "path_vaj"]

#: the limit kinds measured, each the worst over time (and over axes for ``axis_*``)
KINDS = ("tangential_v", "tangential_a", "tangential_j", "axis_v", "axis_a", "axis_j")
#: relative tolerance of a violation by derivative order (v, a, j)
REL_TOL = {"v": 1e-6, "a": 1e-5, "j": 1e-4}


def path_vaj(s_mm: np.ndarray, ts_s: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Path speed, acceleration and jerk along the samples of the path length s(t_k)
    (central differences, same length as s; zeros when there are fewer than two samples)."""
    s = np.asarray(s_mm, dtype=float)
    if s.size < 2:
        z = np.zeros_like(s)
        return z, z, z
    v = np.gradient(s, ts_s)
    a = np.gradient(v, ts_s)
    j = np.gradient(a, ts_s)
    return v, a, j


@dataclass
class Worst:
    """Samples over a limit: how many, the worst ratio value/limit, its value and line."""

    count: int = 0
    ratio: float = 0.0
    value: float = 0.0
    line: int = 0

    def update(self, value: np.ndarray, limit: np.ndarray | float, lines: np.ndarray, rel_tol: float,
               noise: float) -> None:
        over = value > np.asarray(limit) * (1.0 + rel_tol) + noise
        if not over.any():
            return
        self.count += int(over.sum())
        ratio = np.broadcast_to(value / limit, value.shape)
        i = int(np.argmax(np.where(over, ratio, -np.inf)))
        if ratio.flat[i] > self.ratio:
            self.ratio = float(ratio.flat[i])
            self.value = float(value.flat[i])
            self.line = int(np.broadcast_to(lines, value.shape).flat[i])

    def merge(self, row: np.ndarray) -> None:
        """``update`` from a summary the compiled meter made of one call's stencils: (largest
        value, how many over, the worst ratio over, its value, its line, ...)."""
        if row[1] <= 0:
            return
        self.count += int(row[1])
        if row[2] > self.ratio:
            self.ratio, self.value, self.line = float(row[2]), float(row[3]), int(row[4])

    def as_dict(self) -> dict[str, float]:
        return {"count": self.count, "worst": self.value, "worst_ratio": self.ratio, "line": self.line}


class PathSpeedLimits:
    """Per move, the path speed limit: rapids to the rapid limit, every other move to the feed
    limit (moves of rotary axes alone: the angular ones, ``rotary_only``), looked up for the
    moves asked (an array of them for 10,000,000 moves is 80 MB, and making it held cycle start
    0.17 s)."""

    def __init__(self, rapid_moves: np.ndarray, v_rapid_mm_s: float, v_feed_mm_s: float,
                 rotary_only: np.ndarray | None = None, v_rapid_deg_s: float = math.inf,
                 v_feed_deg_s: float = math.inf) -> None:
        self.rapid = rapid_moves
        self.v_rapid = float(v_rapid_mm_s)
        self.v_feed = float(v_feed_mm_s)
        self.rotary_only = rotary_only if rotary_only is not None and rotary_only.any() else None
        self.v_rapid_rot, self.v_feed_rot = float(v_rapid_deg_s), float(v_feed_deg_s)

    def __len__(self) -> int:
        return len(self.rapid)

    def __getitem__(self, rows: np.ndarray) -> np.ndarray:
        rapid = self.rapid[rows]
        v = np.where(rapid, self.v_rapid, self.v_feed)
        if self.rotary_only is not None:
            v = np.where(self.rotary_only[rows], np.where(rapid, self.v_rapid_rot, self.v_feed_rot), v)
        return v


class LimitMeter:
    """Streams samples (q, s, move, line) and measures them against the machine's limits.

    ``v_path_per_move``: the path speed limit of each move (indexed by ``move - move_base``):
    its programmed feed for a plan's report, the machine's feed or rapid limit for what was
    executed. A stencil spanning two moves takes the larger of the two.
    ``position_scale``: the largest |position| for the rounding allowance (default: the travel).
    ``tangential_accel``: judge tangential acceleration and jerk against the path limits (off
    for the paper's classic interpolation, whose steps from one cruise speed to the next are
    not limited by design; their size is still measured).
    """

    def __init__(self, machine: MachineSpec, ts_s: float, v_path_per_move: np.ndarray | PathSpeedLimits, *,
                 move_base: int = 0, across_joints: bool = False, tangential_accel: bool = True,
                 position_scale: float | None = None) -> None:
        self.ts = float(ts_s)
        self.names = machine.axis_names
        self.v_axis = np.array([a.v_motion for a in machine.axes], dtype=float)
        self.a_axis = np.array([a.a_motion for a in machine.axes], dtype=float)
        self.j_axis = np.array([a.j_motion for a in machine.axes], dtype=float)
        self.a_path = machine.limits.a_max_mm_s2
        self.j_path = machine.limits.j_max_mm_s3
        # a stencil where no linear axis moves is along the rotary distance (deg): the angular
        # path limits (infinite: the rotary axes' own limits, measured per axis, govern)
        self.linear = ~np.array([a.rotary for a in machine.axes], dtype=bool)
        self.a_path_rot = machine.limits.a_max_deg_s2
        self.j_path_rot = machine.limits.j_max_deg_s3
        self.v_path: np.ndarray | PathSpeedLimits = (
            v_path_per_move if isinstance(v_path_per_move, PathSpeedLimits)
            else np.asarray(v_path_per_move, dtype=float))
        self.move_base = int(move_base)
        self.across_joints = across_joints
        self.tangential_accel = tangential_accel
        #: worst measured ratio per kind, rounding noise removed (<= 1 means within the limit)
        self.ratios = dict.fromkeys(KINDS, 0.0)
        #: samples over a limit per kind
        self.worst = {k: Worst() for k in KINDS}
        #: jerk of stencils spanning a joint, over the axis jerk limit (reported, not a violation)
        self.joint = Worst()
        #: largest measured tangential v/a/j and per-axis v/a/j/j_joint
        self.tangential = {"v": 0.0, "a": 0.0, "j": 0.0}
        self.axes = {n: {"v": 0.0, "a": 0.0, "j": 0.0, "j_joint": 0.0} for n in self.names}
        self.samples = 0
        travel = max((max(abs(a.min_pos), abs(a.max_pos)) for a in machine.axes), default=1.0)
        scale = travel if position_scale is None else position_scale
        self._scale = max(1.0, float(scale)) if np.isfinite(scale) else 1.0
        self._tail: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray] | None = None

    def _v_limit(self, move: np.ndarray) -> np.ndarray:
        if not len(self.v_path):
            return np.full(len(move) - 1, np.inf)
        row = np.clip(move - self.move_base, 0, len(self.v_path) - 1)
        return np.maximum(self.v_path[row[1:]], self.v_path[row[:-1]])

    def next_moves(self, v_path_per_move: np.ndarray, move_base: int) -> None:
        """The path speed limits of the next moves, from ``move_base`` on (a plan measured
        segment by segment). The limits of the moves of the samples kept from before stay, so
        that a pair across the joint is held to the faster of its two moves, as in one piece."""
        new = np.asarray(v_path_per_move, dtype=float)
        if isinstance(self.v_path, PathSpeedLimits):
            raise TypeError("a meter of the rapid and feed limits measures one program: no next moves")
        if self._tail is not None and len(self.v_path):
            lo = max(0, int(self._tail[2].min()) - self.move_base)
            hi = min(len(self.v_path), max(lo, move_base - self.move_base))
            new = np.concatenate([self.v_path[lo:hi], new])
            move_base -= hi - lo
        self.v_path = new
        self.move_base = int(move_base)

    def add(self, q: np.ndarray, s_mm: np.ndarray, move: np.ndarray, line: np.ndarray | None = None) -> None:
        """Measure the next consecutive samples (axis positions (N, n_axes), path length (N,),
        move index (N,), source line (N,))."""
        q = np.asarray(q, dtype=float)
        move = np.asarray(move)
        line = np.zeros(len(q), np.int64) if line is None else np.asarray(line)
        self.samples += len(q)
        if self._tail is not None:
            tq, ts_, tm, tl = self._tail
            new_from = len(tq)
            q = np.concatenate([tq, q])
            s_mm = np.concatenate([ts_, s_mm])
            move = np.concatenate([tm, move])
            line = np.concatenate([tl, line])
        else:
            new_from = 0
        self._measure(q, np.asarray(s_mm, dtype=float), move, line, new_from)
        self._tail = (q[-3:].copy(), np.asarray(s_mm[-3:], dtype=float).copy(), move[-3:].copy(),
                      line[-3:].copy())

    def _noise(self) -> tuple[float, dict[str, float]]:
        """The rounding allowance: (eps of a position, the noise of a k-th difference per order)."""
        ts = self.ts
        eps = np.finfo(float).eps * self._scale * 16
        return eps, {"v": eps / ts, "a": 4 * eps / ts**2, "j": 8 * eps / ts**3}

    def _measure(self, q: np.ndarray, s: np.ndarray, move: np.ndarray, line: np.ndarray,
                 new_from: int) -> None:
        """Measure the stencils that end in the new samples: in C where it is built, the same
        figures as ``_measure_numpy``, which measures where it is not (and samples with NaN)."""
        if _meter is None:
            self._measure_numpy(q, s, move, line, new_from)
            return
        d = len(self.names)
        ts = self.ts
        eps, noise = self._noise()
        keys = ("v", "a", "j")
        params = np.array([new_from, ts, ts**2, ts**3, eps, noise["v"], noise["a"], noise["j"],
                           REL_TOL["v"], REL_TOL["a"], REL_TOL["j"], float(self.across_joints)])
        out = np.empty((3, 2 * d + 1, 7))
        paths = np.array([self.a_path, self.a_path_rot, self.j_path, self.j_path_rot], dtype=float)
        done = _meter.measure(np.ascontiguousarray(q, dtype=float), np.ascontiguousarray(s, dtype=float),
                              np.ascontiguousarray(move, dtype=np.int64),
                              np.ascontiguousarray(line, dtype=np.int64),
                              np.ascontiguousarray(self._v_limit(move), dtype=float), self.linear,
                              np.stack([self.v_axis, self.a_axis, self.j_axis]), paths, params, out)
        if not done:
            self._measure_numpy(q, s, move, line, new_from)
            return
        # the figures in the order the NumPy form updates them
        for k, key in enumerate(keys):
            block, limit = out[k], (self.v_axis, self.a_axis, self.j_axis)[k]
            for i, name in enumerate(self.names):
                joint, inside = block[d + i], block[i]
                if joint[5]:
                    self.axes[name]["j_joint"] = max(self.axes[name]["j_joint"], float(joint[0]))
                    self.joint.merge(joint)
                if inside[5]:
                    self.axes[name][key] = max(self.axes[name][key], float(inside[0]))
                    self.ratios["axis_" + key] = max(self.ratios["axis_" + key],
                                                     (float(inside[0]) - noise[key]) / float(limit[i]))
                    self.worst["axis_" + key].merge(inside)
            path = block[2 * d]
            if not path[5]:
                continue
            self.tangential[key] = max(self.tangential[key], float(path[0]))
            if k > 0 and not self.tangential_accel:
                continue
            self.ratios["tangential_" + key] = max(self.ratios["tangential_" + key], float(path[6]))
            self.worst["tangential_" + key].merge(path)

    def _measure_numpy(self, q: np.ndarray, s: np.ndarray, move: np.ndarray, line: np.ndarray,
                       new_from: int) -> None:
        ts = self.ts
        eps, noise = self._noise()
        same1 = move[1:] == move[:-1]
        same = {1: same1, 2: same1[1:] & same1[:-1], 3: same1[2:] & same1[1:-1] & same1[:-2]}
        dq, ds = q, s
        # per sample pair: whether a linear axis moves (then the path is along X Y Z)
        lin_step = (np.abs(np.diff(q[:, self.linear], axis=0)) > eps).any(axis=1) if self.linear.any() \
            else np.zeros(max(len(q) - 1, 0), dtype=bool)
        for k, key in ((1, "v"), (2, "a"), (3, "j")):
            if len(q) <= k:
                break
            dq, ds = np.diff(dq, axis=0), np.diff(ds)      # k-th differences, from the (k-1)-th
            lo = max(new_from - k, 0)                        # only stencils that end in the new samples
            aq = np.abs(dq[lo:]) / ts**k
            as_ = np.abs(ds[lo:]) / ts**k
            inside = same[k][lo:]
            # a stencil is attributed to the line of its second sample, as the planner reports it
            lines = line[1:len(line) - k + 1][lo:]
            axis_lim = (self.v_axis, self.a_axis, self.j_axis)[k - 1]
            # axes: velocity and acceleration everywhere, jerk inside moves (joints reported)
            self._axes(key, aq, None if k < 3 else inside, axis_lim, lines, noise[key])
            # along the path
            # a k-th difference spans k sample pairs: along the rotary distance when none of
            # them moves a linear axis
            moving = np.convolve(lin_step.astype(np.int64), np.ones(k, dtype=np.int64), "valid")[lo:] > 0
            path_limit = (np.where(moving, self.a_path, self.a_path_rot) if k == 2
                          else np.where(moving, self.j_path, self.j_path_rot))
            if k == 3 or not self.across_joints:
                if not inside.any():
                    continue
                val, vlines = as_[inside], lines[inside]
                limit: np.ndarray | float = self._v_limit(move)[lo:][inside] if k == 1 else path_limit[inside]
            else:
                val, vlines = as_, lines
                limit = self._v_limit(move)[lo:] if k == 1 else path_limit
            self.tangential[key] = max(self.tangential[key], float(val.max()))
            if k > 1 and not self.tangential_accel:
                continue
            self.ratios["tangential_" + key] = max(self.ratios["tangential_" + key],
                                                   float(np.max((val - noise[key]) / limit)))
            self.worst["tangential_" + key].update(val, limit, vlines, REL_TOL[key], noise[key])

    def _axes(self, key: str, val: np.ndarray, inside: np.ndarray | None, limit: np.ndarray,
              lines: np.ndarray, noise: float) -> None:
        """Per-axis maxima of one order's stencils (N, n_axes), column by column (a reduction
        along the first axis of an (N, 3) array is many times slower than three column ones);
        with ``inside``, the stencils within one move count against the limit and the others
        are joint jerk. A violation's details are looked up only when a column is over."""
        tol = REL_TOL[key]
        joint_lines = lines[~inside] if inside is not None else lines
        in_lines = lines[inside] if inside is not None else lines
        for i, name in enumerate(self.names):
            col = val[:, i]
            if inside is not None:
                out = col[~inside]
                col = col[inside]
                if out.size:
                    worst = float(out.max())
                    self.axes[name]["j_joint"] = max(self.axes[name]["j_joint"], worst)
                    if worst > limit[i] * (1.0 + tol) + noise:
                        self.joint.update(out, limit[i], joint_lines, tol, noise)
            if not col.size:
                continue
            worst = float(col.max())
            self.axes[name][key] = max(self.axes[name][key], worst)
            self.ratios["axis_" + key] = max(self.ratios["axis_" + key], (worst - noise) / float(limit[i]))
            if worst > limit[i] * (1.0 + tol) + noise:
                self.worst["axis_" + key].update(col, limit[i], in_lines, tol, noise)

    @property
    def violations(self) -> dict[str, dict[str, float]]:
        return {k: w.as_dict() for k, w in self.worst.items() if w.count}

    def ratio_report(self) -> dict[str, float]:
        """Worst ratios per kind and the largest tangential values (keys ``tangential_v_max``
        and so on), the form the controller's checks use."""
        out = dict(self.ratios)
        for key in ("v", "a", "j"):
            out[f"tangential_{key}_max"] = self.tangential[key]
        return out


def check_limits(q: np.ndarray, s_mm: np.ndarray, move: np.ndarray, machine: MachineSpec, ts_s: float,
                 rapid_move: np.ndarray | None = None,
                 rotary_only: np.ndarray | None = None) -> dict[str, float]:
    """Measured maxima of executed set-points as ratios to the machine's limits (<= 1 holds):
    the path speed against the machine's feed limit (rapid limit on rapid moves), joints
    excluded from the tangential figures. One call of the meter over one buffer."""
    lim = machine.limits
    if rapid_move is not None and len(rapid_move):
        v_path = PathSpeedLimits(rapid_move, lim.rapid_mm_s, lim.v_max_mm_s, rotary_only, lim.rapid_deg_s,
                                 lim.v_max_deg_s)[np.arange(len(rapid_move))]
    else:
        v_path = np.array([max(lim.v_max_mm_s, lim.rapid_mm_s)])
    meter = LimitMeter(machine, ts_s, v_path)
    if len(q) >= 4:
        meter.add(q, s_mm, move)
    return meter.ratio_report()
