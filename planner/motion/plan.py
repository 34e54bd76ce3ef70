"""From a Program to time-stamped set-points: ``plan_program`` and ``stream_program``.

``plan_program`` plans the whole program (joint speeds, profiles, timeline) and returns a
:class:`Plan`; ``Plan.iter_chunks`` interpolates it lazily in chunks of bounded size.
``stream_program`` yields the very same samples while planning window by window, so the
first set-point is out within milliseconds whatever the program length.

``Plan.limit_report()`` checks that no limit is exceeded, from the closed-form
profiles and from finite differences of the samples: tangential v/a/j, per-axis v/a/j
(jerk inside moves; at joints - tangent breaks and curvature jumps - it is reported
separately), contour error, end points, NaN, monotonic time.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass, field

import numpy as np

from planner.core.errors import PlannerError
from planner.core.machine import MachineSpec
from planner.core.program import MoveKind, Program
from planner.geometry.movetable import MoveTable, concat_tables, contour_error, take_rows
from planner.motion.interpolate import (
    INTERPOLATIONS,
    Interpolator,
    SampleChunk,
    Segment,
    SegmentJoin,
    first_sample_at,
    make_segment,
)
from planner.motion.lookahead import (
    MODES,
    LimitSet,
    PlannedBlock,
    corner_steps,
    plan_blocks,
    stops_and_dwells,
)
from planner.motion.meter import LimitMeter
from planner.motion.profile import build_profiles

__all__ = ["LimitReport", "Plan", "SampleChunk", "plan_program", "stream_program"]

DEFAULT_CHUNK = 65536
# moves planned at once: the look-ahead's NumPy work per window costs the same whatever its
# size up to a few thousand moves (on a 200,000-line raster 0.70 s at 256, 0.37 s at 4096);
# a stream's first window stays small (``first_window``) so that motion starts at once
DEFAULT_WINDOW = 4096


def resolve_settings(machine: MachineSpec, mode: str | None, interpolation: str | None) -> tuple[str, str]:
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


def plan_segments(program: Program, machine: MachineSpec, mode: str | None = None,
                  interpolation: str | None = None, window: int = DEFAULT_WINDOW,
                  segment_moves: int = 65_536, quick_start: bool = False) -> Iterator[Segment]:
    """Plan window by window and yield consecutive segments (profiles and timeline) of about
    ``segment_moves`` moves each: the whole plan's, piece by piece, in memory bounded by a
    segment. ``quick_start``: the first segment is the first final block, out at once."""
    _check_axes(program, machine)
    mode, interpolation = resolve_settings(machine, mode, interpolation)
    ts = machine.planner.ts_s
    lim = LimitSet.from_machine(machine)
    t_start = stops_and_dwells(program).before_s
    s_start = 0.0
    pending: list[PlannedBlock] = []
    pending_moves = 0
    first = quick_start
    n = len(program.moves)
    first_window = min(window, 32) if quick_start else window
    for block in plan_blocks(program, lim, mode, window, first_window=first_window):
        pending.append(block)
        pending_moves += len(block.table)
        last = block.first + len(block.table) == n
        if not (first or last or pending_moves >= segment_moves):
            continue
        seg = make_segment(pending, interpolation, ts, t_start, s_start)
        yield seg
        t_start, s_start = seg.t_end, seg.s_end
        pending, pending_moves, first = [], 0, False


def stream_program(program: Program, machine: MachineSpec, mode: str | None = None,
                   interpolation: str | None = None, chunk_samples: int = DEFAULT_CHUNK,
                   window: int = DEFAULT_WINDOW) -> Iterator[SampleChunk]:
    """Plan and interpolate window by window; the samples equal ``plan_program(...).collect()``."""
    _check_axes(program, machine)
    mode, interpolation = resolve_settings(machine, mode, interpolation)
    if not program.moves:
        yield _still(program, 0.0)
        return
    interp = Interpolator(interpolation, machine.planner.ts_s)
    k_lo = 0
    n = len(program.moves)
    # the first segment at once (latency), then about a chunk of samples each
    for seg in plan_segments(program, machine, mode, interpolation, window,
                             segment_moves=max(1, chunk_samples // 50), quick_start=True):
        last = int(seg.table.index[-1]) + 1 == n
        yield from _samples_of_segment(interp, seg, k_lo, last, chunk_samples)
        k_lo = first_sample_at(seg.t_end, interp.ts)


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
    # joints crossed with a velocity step beyond the jerk limit ([planner]
    # corner_velocity_step_mm_s): how many, the largest step (mm/s), the lines (the first 50)
    corner_steps: dict[str, object] = field(default_factory=lambda: {"count": 0, "largest_mm_s": 0.0,
                                                                     "lines": []})

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
            "corner_steps": self.corner_steps,
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
                 interpolation: str | None = None, window: int = DEFAULT_WINDOW,
                 progress: Callable[[int, int], None] | None = None) -> Plan:
    """Plan the whole program (speeds at every joint, profiles, timeline); ``progress(moves
    planned, moves in all)`` is called after each segment."""
    started = time.perf_counter()
    _check_axes(program, machine)
    mode, interpolation = resolve_settings(machine, mode, interpolation)
    # planned in segments and joined as they come: the same plan, with the temporaries of a
    # segment; segments of 16,384 moves: the progress moves often enough to be seen
    moves = program.moves
    cols = moves.columns()
    join = SegmentJoin(len(moves), moves.positions,
                       {name: getattr(cols, name) for name in SegmentJoin.PROGRAM_COLUMNS})
    for seg in plan_segments(program, machine, mode, interpolation, window, segment_moves=16_384):
        join.add(seg)
        if progress is not None:
            progress(int(seg.table.index[-1]) + 1, len(moves))
    if len(moves):
        seg = join.result()
    else:
        empty = MoveTable.from_moves((), len(program.axes))
        z = np.zeros(0)
        seg = Segment(empty, build_profiles(z, z, z, z, z, z), z, z, 0.0, z, 0.0)
    return Plan(program, machine, mode, interpolation, seg, time.perf_counter() - started)


# -- the limit report -------------------------------------------------------------------------
def _report(plan: Plan, chunk_samples: int, rel_tol: float) -> LimitReport:
    return report_segments(plan.program, plan.machine, plan.interpolation, [plan.segment], chunk_samples,
                           rel_tol)


def _extent(program: Program) -> float:
    """Largest |coordinate| the program's moves reach (end points)."""
    moves = program.moves
    if not len(moves):
        return 1.0
    return float(np.max(np.abs(moves.positions[1:])))


def report_segments(program: Program, machine: MachineSpec, interpolation: str, segments: Iterable[Segment],
                    chunk_samples: int = DEFAULT_CHUNK, rel_tol: float = 1e-6,
                    on_segment: Callable[[Segment], None] | None = None,
                    on_chunk: Callable[[SampleChunk], None] | None = None) -> LimitReport:
    """The limit report of a plan given as consecutive segments (``plan_segments``, or the
    whole plan's one): closed-form maxima of the profiles, and the samples measured by the one
    limit meter (``planner.motion.meter``) against the programmed feed of each move and the machine's
    limits. ``on_segment`` sees each segment once it is measured (a streamed summary),
    ``on_chunk`` each chunk of samples (files written as the samples are made)."""
    ts = machine.planner.ts_s
    lim = LimitSet.from_machine(machine)
    n_total = len(program.moves)
    classic = interpolation == "classic"
    # a plan is not held to the travel here (cnc-plan without soft limits): its own extent
    meter = LimitMeter(machine, ts, np.zeros(0), across_joints=True, tangential_accel=not classic,
                       position_scale=_extent(program))
    tangential = {"v": 0.0, "a": 0.0, "j": 0.0}
    closed = meter.worst            # one worst-case record per kind for closed form and samples
    contour = 0.0
    nan = False
    increasing = True
    last_t: float | None = None
    last_q = None
    if not n_total:
        still = _still(program, 0.0)
        meter.add(still.q, still.s, still.move_index, still.line)
        if on_chunk is not None:
            on_chunk(still)
        return LimitReport(tangential, dict(meter.tangential), meter.axes, 0.0, meter.violations,
                           meter.joint.as_dict(), 0.0, False, True, meter.samples)
    interp = Interpolator(interpolation, ts)
    k_lo = 0
    steps = _CornerSteps(lim)
    for seg in segments:
        prof = seg.profiles
        steps.add(seg)
        lines = seg.table.line
        first = int(seg.table.index[0])
        meter.next_moves(seg.v_prog, first)
        if not classic:
            # closed form: the profile never exceeds its own caps; compare with the programmed limits
            vmax = np.maximum(prof.vp, np.maximum(prof.vs, prof.ve))
            tangential = {"v": max(tangential["v"], float(vmax.max())),
                          "a": max(tangential["a"], float(prof.accel_peak.max())),
                          "j": max(tangential["j"], float(prof.jerk_peak.max()))}
            closed["tangential_v"].update(vmax, seg.v_prog, lines, rel_tol, 1e-12)
            _v, a_path, j_path, _r = lim.path(lim.rotary_only(seg.table.start, seg.table.end))
            closed["tangential_a"].update(prof.accel_peak, a_path, lines, rel_tol, 1e-9)
            closed["tangential_j"].update(prof.jerk_peak, j_path, lines, rel_tol, 1e-9)
        end = first + len(seg.table)
        for chunk in _samples_of_segment(interp, seg, k_lo, end == n_total, chunk_samples):
            nan |= bool(np.isnan(chunk.q).any() or np.isnan(chunk.s).any())
            row = chunk.move_index - first
            u = chunk.s - seg.s0[row]
            contour = max(contour, float(contour_error(seg.table, row, chunk.q, u).max()))
            t = chunk.t if last_t is None else np.concatenate([[last_t], chunk.t])
            increasing &= bool(np.all(np.diff(t) > 0))
            meter.add(chunk.q, chunk.s, chunk.move_index, chunk.line)
            if on_chunk is not None:
                on_chunk(chunk)
            if len(chunk):
                last_t = float(chunk.t[-1])
                last_q = chunk.q[-1]
        k_lo = first_sample_at(seg.t_end, ts)
        if on_segment is not None:
            on_segment(seg)
    end_err = float(np.max(np.abs(last_q - program.end_position))) if last_q is not None else 0.0
    return LimitReport(tangential, dict(meter.tangential), meter.axes, contour, meter.violations,
                       meter.joint.as_dict(), end_err, nan, increasing, meter.samples, steps.as_dict())


class _CornerSteps:
    """The joints of consecutive segments crossed with a velocity step beyond the jerk limit
    (``lookahead.corner_steps``), the joint between two segments included."""

    LINES_KEPT = 50

    def __init__(self, lim: LimitSet) -> None:
        self.lim = lim
        self.count = 0
        self.largest = 0.0
        self.lines: list[int] = []
        self._last: tuple[MoveTable, float, float] | None = None   # a segment's last move

    def add(self, seg: Segment) -> None:
        prof = seg.profiles
        table, v_joint, j_t = seg.table, prof.ve[:-1], prof.j_max
        if self._last is not None and len(table):
            last_table, last_ve, last_j = self._last
            table = concat_tables([last_table, table])
            v_joint = np.concatenate([[last_ve], v_joint])
            j_t = np.concatenate([[last_j], j_t])
        if len(seg.table):
            self._last = (take_rows(seg.table, slice(len(seg.table) - 1, None)), float(prof.ve[-1]),
                          float(prof.j_max[-1]))
        step = corner_steps(table, v_joint, j_t, self.lim)
        over = np.flatnonzero(step > 0.0)
        if not over.size:
            return
        self.count += int(over.size)
        self.largest = max(self.largest, float(step[over].max()))
        room = self.LINES_KEPT - len(self.lines)
        if room > 0:
            self.lines += [int(x) for x in table.line[over[:room] + 1]]

    def as_dict(self) -> dict[str, object]:
        return {"count": self.count, "largest_mm_s": self.largest, "lines": self.lines}
