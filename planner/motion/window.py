"""A plan made as the run reaches it: ``PlanWindow``.

A program of millions of moves planned whole holds about 150 bytes a move (profiles, joint
speeds, timeline): 1.5 GB at 10,000,000 moves. The run needs the plan only around the point
it executes: where it may be rewound to (a few set-points queued in the drives' worker are
replaced when the operator holds or turns a knob) and ahead as far as it looks to brake (a
second or so). ``PlanWindow`` plans the program segment by segment (``plan_segments``: the
same look-ahead, window by window) as the run asks for later times, joins the segments it
holds into one ``Segment`` (local rows, the program's move numbers in ``table.index``) and
lets go of those the run has left behind.

It offers what the executor reads of a ``Plan`` (``program``, ``machine``, ``interpolation``,
``ts_s``, ``segment``, ``iter_chunks``, ``cycle_time_s``), so a whole ``Plan`` is one of
its kind (``PlanWindow.of_plan``: one segment, done from the start). Until the last segment
is made the end of the plan is not known: ``t_end`` is infinite and ``cycle_time_s`` the
estimate it was given (the load's check pass planned the same program the same way).
"""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Callable, Iterator

import numpy as np

from planner.core.errors import PlannerError
from planner.core.machine import MachineSpec
from planner.core.program import Program
from planner.motion.interpolate import Interpolator, SampleChunk, Segment, SegmentJoin, first_sample_at
from planner.motion.plan import DEFAULT_CHUNK, DEFAULT_WINDOW, Plan, plan_segments, resolve_settings

__all__ = ["PlanWindow", "WINDOW_SEGMENT_MOVES"]

#: moves a segment of a window holds: planned in a few milliseconds (the run plans the next
#: one while the drives' worker plays the set-points queued ahead), a few seconds of motion
#: even on a raster of 0.015 mm moves
WINDOW_SEGMENT_MOVES = 4096


class PlanWindow:
    """The plan of ``program`` for the times around the run: see the module docstring."""

    def __init__(self, program: Program, machine: MachineSpec, mode: str | None = None,
                 interpolation: str | None = None, *, segment_moves: int | None = None,
                 window: int | None = None, estimate_s: float = math.nan, quick_start: bool = True) -> None:
        segment_moves = WINDOW_SEGMENT_MOVES if segment_moves is None else segment_moves
        if segment_moves < 1:
            raise PlannerError(f"a window's segments hold at least one move, got {segment_moves}")
        mode, interpolation = resolve_settings(machine, mode, interpolation)
        self.program = program
        self.machine = machine
        self.mode = mode
        self.interpolation = interpolation
        self.n_moves = len(program.moves)
        # the look-ahead plans ``window`` moves at once (the plan is the same whatever its size)
        # and a segment holds whole windows: no larger than a segment
        window = min(DEFAULT_WINDOW, segment_moves) if window is None else window
        self._source: Iterator[Segment] | None = (
            plan_segments(program, machine, mode, interpolation, window, segment_moves=segment_moves,
                          quick_start=quick_start) if self.n_moves else None)
        self._held: deque[Segment] = deque()
        self._joined: Segment | None = None
        self.done = self._source is None
        self.t_end = 0.0 if self.done else math.inf
        self._estimate_s = float(estimate_s)
        self.segments_made = 0
        # told of each segment as it is made (the run's pause points come from them)
        self.on_segment: Callable[[Segment], None] | None = None

    @classmethod
    def of_plan(cls, plan: Plan) -> PlanWindow:
        """A whole plan as a window: its one segment, done."""
        win = cls.__new__(cls)
        win.program = plan.program
        win.machine = plan.machine
        win.mode = plan.mode
        win.interpolation = plan.interpolation
        win.n_moves = len(plan.program.moves)
        win._source = None
        win._held = deque([plan.segment]) if len(plan.segment.table) else deque()
        win._joined = plan.segment if len(plan.segment.table) else None
        win.done = True
        win.t_end = float(plan.segment.t_end) if len(plan.segment.table) else 0.0
        win._estimate_s = win.t_end
        win.segments_made = 1
        win.on_segment = None
        return win

    # -- what a Plan offers ---------------------------------------------------------------
    @property
    def ts_s(self) -> float:
        return self.machine.planner.ts_s

    @property
    def cycle_time_s(self) -> float:
        """The plan's end: exact once the last segment is made, else the estimate given, else
        as far as it is planned."""
        if self.done:
            return self.t_end
        return self._estimate_s if math.isfinite(self._estimate_s) else self.covered_until

    @property
    def segment(self) -> Segment:
        """The held segments as one (rows local to it; ``table.index``: the program's moves)."""
        if self._joined is None:
            self.ensure(0.0)
            if self._joined is None:
                raise PlannerError("the plan has no moves")
        return self._joined

    @property
    def covered_until(self) -> float:
        """The planned time the held segments reach (the plan's end once done)."""
        return float(self._held[-1].t_end) if self._held else 0.0

    @property
    def first_move(self) -> int:
        """The program's move number of the first held row."""
        return int(self._held[0].table.index[0]) if self._held else 0

    # -- moving the window ----------------------------------------------------------------
    def ensure(self, tau_s: float) -> list[Segment]:
        """Plan until the held segments reach planned time ``tau_s`` (or the end); the
        segments made now, in order."""
        made: list[Segment] = []
        while not self.done and (not self._held or self._held[-1].t_end < tau_s):
            assert self._source is not None
            seg = next(self._source, None)
            if seg is None:       # no segment after the last: the end was the one before
                self._finish()
                break
            self._held.append(seg)
            self.segments_made += 1
            made.append(seg)
            if self.on_segment is not None:
                self.on_segment(seg)
            if int(seg.table.index[-1]) + 1 >= self.n_moves:
                self._finish()
        if made:
            self._join()
        return made

    def release(self, tau_s: float) -> None:
        """Let go of the segments that end before planned time ``tau_s`` (the one holding it
        and those after stay)."""
        dropped = False
        while len(self._held) > 1 and self._held[0].t_end < tau_s:
            self._held.popleft()
            dropped = True
        if dropped:
            self._join()

    def _finish(self) -> None:
        self.done = True
        self._source = None
        self.t_end = self.covered_until

    def _join(self) -> None:
        if len(self._held) == 1:
            self._joined = self._held[0]
            return
        join = SegmentJoin(sum(len(s.table) for s in self._held))
        for seg in self._held:
            join.add(seg)
        self._joined = join.result()

    # -- lookups by the program's move number ---------------------------------------------
    def move_start_s(self, move: int) -> float:
        """Cumulative path length at the start of the program's move ``move`` (held)."""
        seg = self.segment
        row = move - int(seg.table.index[0])
        if not 0 <= row < len(seg.table):
            raise PlannerError(f"move {move} is not in the planned window (moves {self.first_move}.."
                               f"{int(seg.table.index[-1])})")
        return float(seg.s0[row])

    # -- samples --------------------------------------------------------------------------
    def iter_chunks(self, chunk_samples: int = DEFAULT_CHUNK, let_go: bool = False) -> Iterator[SampleChunk]:
        """The plan's samples on the Ts grid from time 0 to the end, in chunks, planned as they
        are reached. ``let_go``: the segments behind each chunk are released (a pass over the
        plan that nothing else reads)."""
        if not self.n_moves:
            q = np.asarray(self.program.start_position, float)[None, :].copy()
            yield SampleChunk(np.zeros(1), q, np.zeros(1), np.zeros(1, np.int32), np.zeros(1, np.int32))
            return
        ts = self.ts_s
        interp = Interpolator(self.interpolation, ts)
        k = 0
        while True:
            k_hi = k + chunk_samples
            self.ensure(k_hi * ts)
            last = first_sample_at(self.covered_until, ts) + (1 if self.done else 0)
            k_hi = min(k_hi, last)
            if k_hi <= k:
                return
            if let_go:
                self.release(k * ts)
            yield interp.samples(self.segment, k, k_hi)
            k = k_hi
