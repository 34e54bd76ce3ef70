"""From a Program to time-stamped set-points: ``plan_program`` and ``stream_program``.

``plan_program`` plans the whole program (joint speeds, profiles, timeline) and returns a
:class:`Plan`; ``Plan.iter_chunks`` interpolates it lazily in chunks of bounded size.
``stream_program`` yields the very same samples while planning window by window, so the
first set-point is out within milliseconds whatever the program length.

``Plan.limit_report()`` checks what issue 4 section 4 demands, from the closed-form
profiles and from finite differences of the samples: tangential v/a/j, per-axis v/a/j
(jerk inside moves; at joints - tangent breaks and curvature jumps - it is reported
separately), contour error, end points, NaN, monotonic time.
"""

from __future__ import annotations

import time
from collections.abc import Iterator
from dataclasses import dataclass, field

import numpy as np

from planner.errors import PlannerError
from planner.interpolate import (
    INTERPOLATIONS,
    Interpolator,
    SampleChunk,
    Segment,
    first_sample_at,
    make_segment,
)
from planner.lookahead import MODES, LimitSet, PlannedBlock, plan_blocks, stop_and_dwell
from planner.machine import MachineSpec
from planner.movetable import contour_error
from planner.program import MoveKind, Program

__all__ = ["LimitReport", "Plan", "SampleChunk", "plan_program", "stream_program"]

DEFAULT_CHUNK = 65536
DEFAULT_WINDOW = 256


def _settings(machine: MachineSpec, mode: str | None, interpolation: str | None) -> tuple[str, str]:
    mode = machine.planner.mode if mode is None else mode
    interpolation = machine.planner.interpolation if interpolation is None else interpolation
    if mode not in MODES:
        raise PlannerError(f"planner mode must be one of {MODES}, got {mode!r}")
    if interpolation not in INTERPOLATIONS:
        raise PlannerError(f"interpolation must be one of {INTERPOLATIONS}, got {interpolation!r}")
    return mode, interpolation


def _check_axes(program: Program, machine: MachineSpec) -> None:
    if tuple(program.axes) != tuple(machine.axis_names):
        raise PlannerError(f"program axes {program.axes} do not match the machine's {machine.axis_names}")


def _samples_of_segment(interp: Interpolator, seg: Segment, k_lo: int, last: bool,
                        chunk: int) -> Iterator[SampleChunk]:
    ts = interp.ts
    k_hi = first_sample_at(seg.t_end, ts)
    if last:
        k_hi += 1  # the final sample, at or after the end: the program's end point
    for k in range(k_lo, k_hi, chunk):
        yield interp.samples(seg, k, min(k + chunk, k_hi))


def stream_program(program: Program, machine: MachineSpec, mode: str | None = None,
                   interpolation: str | None = None, chunk_samples: int = DEFAULT_CHUNK,
                   window: int = DEFAULT_WINDOW) -> Iterator[SampleChunk]:
    """Plan and interpolate window by window; the samples equal ``plan_program(...).collect()``."""
    _check_axes(program, machine)
    mode, interpolation = _settings(machine, mode, interpolation)
    ts = machine.planner.ts_s
    lim = LimitSet.from_machine(machine)
    interp = Interpolator(interpolation, ts)
    if not program.moves:
        yield _still(program, 0.0)
        return
    _, _, t_start = stop_and_dwell(program)
    s_start = 0.0
    k_lo = 0
    pending: list[PlannedBlock] = []
    pending_moves = 0
    first = True
    n = len(program.moves)
    for block in plan_blocks(program, lim, mode, window, first_window=min(window, 32)):
        pending.append(block)
        pending_moves += len(block.table)
        last = block.first + len(block.table) == n
        # Emit at once the first time (latency), then in batches of about a chunk of samples.
        if not (first or last or pending_moves * 50 >= chunk_samples):
            continue
        seg = make_segment(pending, interpolation, ts, t_start, s_start)
        yield from _samples_of_segment(interp, seg, k_lo, last, chunk_samples)
        k_lo = first_sample_at(seg.t_end, ts)
        t_start, s_start = seg.t_end, seg.s_end
        pending, pending_moves, first = [], 0, False


def _still(program: Program, t: float) -> SampleChunk:
    return SampleChunk(np.array([t]), np.asarray(program.start_position, float)[None, :].copy(),
                       np.zeros(1), np.zeros(1, np.int32), np.zeros(1, np.int32))


@dataclass(frozen=True)
class LimitReport:
    """Maxima and limit violations of a plan (JSON-able through ``to_dict``)."""

    tangential: dict[str, float]  # closed form: v, a, j
    tangential_samples: dict[str, float]  # finite differences of s(t_k)
    axes: dict[str, dict[str, float]]  # per axis: v, a, j (inside moves), j_joint
    contour_error_mm: float
    violations: dict[str, dict[str, float]]  # kind -> count, worst (value/limit), line
    joint_jerk: dict[str, float]  # per-axis jerk at joints over the limit: reported, not a violation
    end_error_mm: float  # last sample vs the program's end point
    nan: bool
    time_increasing: bool
    samples: int

    @property
    def ok(self) -> bool:
        return not self.violations and not self.nan and self.time_increasing

    def to_dict(self) -> dict:
        return {
            "tangential": self.tangential, "tangential_samples": self.tangential_samples,
            "axes": self.axes, "contour_error_mm": self.contour_error_mm,
            "violations": self.violations, "joint_jerk": self.joint_jerk,
            "end_error_mm": self.end_error_mm, "nan": self.nan,
            "time_increasing": self.time_increasing, "samples": self.samples,
        }


@dataclass(eq=False)
class Plan:
    """A planned program: per-move speeds and profiles on the global clock."""

    program: Program
    machine: MachineSpec
    mode: str
    interpolation: str
    segment: Segment
    plan_s: float = 0.0
    _n_samples: int = field(default=-1, repr=False)

    # -- per-move figures --------------------------------------------------------------------
    @property
    def cycle_time_s(self) -> float:
        return self.segment.t_end

    @property
    def ts_s(self) -> float:
        return self.machine.planner.ts_s

    @property
    def profiles(self):
        return self.segment.profiles

    @property
    def t0(self) -> np.ndarray:
        return self.segment.t0

    @property
    def t1(self) -> np.ndarray:
        return self.segment.t0 + self.segment.profiles.duration

    @property
    def vs(self) -> np.ndarray:
        return self.segment.profiles.vs

    @property
    def ve(self) -> np.ndarray:
        return self.segment.profiles.ve

    @property
    def vpeak(self) -> np.ndarray:
        return self.segment.profiles.vp

    @property
    def n_samples(self) -> int:
        if not self.program.moves:
            return 1
        return first_sample_at(self.segment.t_end, self.ts_s) + 1

    # -- samples -----------------------------------------------------------------------------
    def iter_chunks(self, chunk_samples: int = DEFAULT_CHUNK,
                    t_start_s: float = 0.0) -> Iterator[SampleChunk]:
        """Samples from t_start_s (rounded up to the grid) to the end, in chunks."""
        if not self.program.moves:
            yield _still(self.program, 0.0)
            return
        interp = Interpolator(self.interpolation, self.ts_s)
        k_lo = first_sample_at(max(t_start_s, 0.0), self.ts_s)
        if self.interpolation == "taylor" and k_lo > 0:
            # Taylor's state when starting late: the exact path length at that sample.
            row = int(np.clip(np.searchsorted(self.segment.t0, k_lo * self.ts_s, "right") - 1, 0, None))
            tau = np.array([k_lo * self.ts_s - self.segment.t0[row]])
            interp._carry = float(self.segment.s0[row] + self.profiles.evaluate_s(np.array([row]), tau)[0])
        yield from _samples_of_segment(interp, self.segment, k_lo, True, chunk_samples)

    def collect(self) -> SampleChunk:
        return SampleChunk.concat(list(self.iter_chunks()), len(self.program.axes))

    def moves_summary(self) -> list[dict]:
        tab = self.segment.table
        kinds = {int(k): k.name.lower() for k in MoveKind}
        t0, t1 = self.t0, self.t1
        return [
            {"line": int(tab.line[i]), "kind": kinds[int(tab.kind[i])], "length": float(tab.length[i]),
             "vs": float(self.vs[i]), "ve": float(self.ve[i]), "vpeak": float(self.vpeak[i]),
             "t0": float(t0[i]), "t1": float(t1[i])}
            for i in range(len(tab))
        ]

    # -- checks ------------------------------------------------------------------------------
    def limit_report(self, chunk_samples: int = DEFAULT_CHUNK, rel_tol: float = 1e-6) -> LimitReport:
        return _report(self, chunk_samples, rel_tol)


def plan_program(program: Program, machine: MachineSpec, mode: str | None = None,
                 interpolation: str | None = None, window: int = DEFAULT_WINDOW) -> Plan:
    """Plan the whole program (speeds at every joint, profiles, timeline)."""
    started = time.perf_counter()
    _check_axes(program, machine)
    mode, interpolation = _settings(machine, mode, interpolation)
    lim = LimitSet.from_machine(machine)
    blocks = list(plan_blocks(program, lim, mode, window))
    _, _, t_start = stop_and_dwell(program)
    if blocks:
        seg = make_segment(blocks, interpolation, machine.planner.ts_s, t_start, 0.0)
    else:
        from planner.movetable import MoveTable
        from planner.profile import build_profiles

        empty = MoveTable.from_moves((), len(program.axes))
        z = np.zeros(0)
        seg = Segment(empty, build_profiles(z, z, z, z, z, z), z, z, z, z, 0.0, z, 0.0, z, z, z, z, z, z, z)
    return Plan(program, machine, mode, interpolation, seg, time.perf_counter() - started)


# -- the limit report -------------------------------------------------------------------------
class _Worst:
    __slots__ = ("count", "ratio", "value", "line")

    def __init__(self):
        self.count = 0
        self.ratio = 0.0
        self.value = 0.0
        self.line = 0

    def update(self, value: np.ndarray, limit, lines: np.ndarray, tol: float, abs_tol: float) -> None:
        over = value > limit * (1.0 + tol) + abs_tol
        if over.any():
            self.count += int(over.sum())
            ratio = value / limit
            ratio = np.broadcast_to(ratio, value.shape)
            i = int(np.argmax(np.where(over, ratio, -np.inf)))
            if ratio.flat[i] > self.ratio:
                self.ratio = float(ratio.flat[i])
                self.value = float(value.flat[i])
                self.line = int(np.broadcast_to(lines, value.shape).flat[i])

    def as_dict(self) -> dict[str, float]:
        return {"count": self.count, "worst": self.value, "worst_ratio": self.ratio, "line": self.line}


def _report(plan: Plan, chunk_samples: int, rel_tol: float) -> LimitReport:
    seg = plan.segment
    prof = seg.profiles
    machine = plan.machine
    lim = LimitSet.from_machine(machine)
    ts = plan.ts_s
    names = machine.axis_names
    d = len(names)
    worst = {k: _Worst() for k in ("tangential_v", "tangential_a", "tangential_j",
                                   "axis_v", "axis_a", "axis_j")}
    joint = _Worst()
    # Closed form: the profile never exceeds its own caps; compare with the programmed limits.
    lines = seg.table.line
    n_moves = len(seg.table)
    tangential = {"v": 0.0, "a": 0.0, "j": 0.0}
    if n_moves and plan.interpolation != "classic":
        vmax = np.maximum(prof.vp, np.maximum(prof.vs, prof.ve))
        tangential = {"v": float(vmax.max()), "a": float(prof.accel_peak.max()),
                      "j": float(prof.jerk_peak.max())}
        worst["tangential_v"].update(vmax, seg.v_prog, lines, rel_tol, 1e-12)
        worst["tangential_a"].update(prof.accel_peak, lim.a_path, lines, rel_tol, 1e-9)
        worst["tangential_j"].update(prof.jerk_peak, lim.j_path, lines, rel_tol, 1e-9)
    tan_s = {"v": 0.0, "a": 0.0, "j": 0.0}
    ax = {n: {"v": 0.0, "a": 0.0, "j": 0.0, "j_joint": 0.0} for n in names}
    contour = 0.0
    nan = False
    increasing = True
    total = 0
    tail: SampleChunk | None = None
    last_q = None
    # Finite differences carry a rounding noise of about |q| eps / Ts^k: a small absolute allowance.
    scale = max(1.0, float(np.max(np.abs(seg.table.end))) if n_moves else 1.0)
    eps = np.finfo(float).eps * scale * 16
    tol_v, tol_a, tol_j = eps / ts, 4 * eps / ts**2, 8 * eps / ts**3
    interp_chunks = plan.iter_chunks(chunk_samples)
    for chunk in interp_chunks:
        total += len(chunk)
        nan |= bool(np.isnan(chunk.q).any() or np.isnan(chunk.s).any())
        if n_moves:
            row = chunk.move_index - int(seg.table.index[0])
            u = chunk.s - seg.s0[row]
            contour = max(contour, float(contour_error(seg.table, row, chunk.q, u).max()))
        if tail is not None:
            buf = SampleChunk.concat([tail, chunk], d)
            new_from = len(tail)
        else:
            buf, new_from = chunk, 0
        increasing &= bool(np.all(np.diff(buf.t) > 0))
        q, s, mi, ln = buf.q, buf.s, buf.move_index, buf.line
        vq = np.abs(np.diff(q, axis=0)) / ts
        vs_ = np.abs(np.diff(s)) / ts
        aq = np.abs(np.diff(q, 2, axis=0)) / ts**2
        as_ = np.abs(np.diff(s, 2)) / ts**2
        jq = np.abs(np.diff(q, 3, axis=0)) / ts**3
        js_ = np.abs(np.diff(s, 3)) / ts**3
        # Only stencils that end in the new chunk (the tail's were counted before).
        lo1, lo2, lo3 = max(new_from - 1, 0), max(new_from - 2, 0), max(new_from - 3, 0)
        vq, vs_, aq, as_, jq, js_ = vq[lo1:], vs_[lo1:], aq[lo2:], as_[lo2:], jq[lo3:], js_[lo3:]
        same4 = ((mi[3:] == mi[:-3]) & (mi[1:-2] == mi[3:]))[lo3:]
        if n_moves:
            row = mi - int(seg.table.index[0])
            vlim = np.maximum(seg.v_prog[row[1:]], seg.v_prog[row[:-1]])[lo1:]
            worst["tangential_v"].update(vs_, vlim, ln[1:][lo1:], rel_tol, tol_v)
        if plan.interpolation != "classic":
            worst["tangential_a"].update(as_, lim.a_path, ln[1:-1][lo2:], 1e-5, tol_a)
            worst["tangential_j"].update(js_[same4], lim.j_path, ln[1:-2][lo3:][same4], 1e-4, tol_j)
        if vs_.size:
            tan_s["v"] = max(tan_s["v"], float(vs_.max()))
        if as_.size:
            tan_s["a"] = max(tan_s["a"], float(as_.max()))
        if js_.size and same4.any():
            tan_s["j"] = max(tan_s["j"], float(js_[same4].max()))
        for k, name in enumerate(names):
            if vq.size:
                ax[name]["v"] = max(ax[name]["v"], float(vq[:, k].max()))
                worst["axis_v"].update(vq[:, k], lim.v_axis[k], ln[1:][lo1:], 1e-6, tol_v)
            if aq.size:
                ax[name]["a"] = max(ax[name]["a"], float(aq[:, k].max()))
                worst["axis_a"].update(aq[:, k], lim.a_axis[k], ln[1:-1][lo2:], 1e-5, tol_a)
            if jq.size:
                jin = jq[:, k][same4]
                jout = jq[:, k][~same4]
                lj = ln[1:-2][lo3:]
                if jin.size:
                    ax[name]["j"] = max(ax[name]["j"], float(jin.max()))
                    worst["axis_j"].update(jin, lim.j_axis[k], lj[same4], 1e-4, tol_j)
                if jout.size:
                    ax[name]["j_joint"] = max(ax[name]["j_joint"], float(jout.max()))
                    joint.update(jout, lim.j_axis[k], lj[~same4], 1e-4, tol_j)
        tail = SampleChunk(*(getattr(buf, f)[-3:] for f in SampleChunk.__slots__))
        last_q = chunk.q[-1]
    end_err = float(np.max(np.abs(last_q - plan.program.end_position))) if last_q is not None else 0.0
    violations = {k: w.as_dict() for k, w in worst.items() if w.count}
    return LimitReport(tangential, tan_s, ax, contour, violations, joint.as_dict(), end_err, nan,
                       increasing, total)
