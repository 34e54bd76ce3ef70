"""The load's heavy part, run off the controller's thread: the planner's one load pipeline
(``planner.pipeline.load``: read, refuse what this machine cannot run, blend, the soft limits of
the path that will run, plan) with this machine's abilities and its run planner, then the tables
the pages show. Every refusal names the line (and the column where the code stands) and says
why.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from app.machine.config import MachineConfig
from app.machine.model import ProgramInfo, ProgramIssue, SpindleState
from app.machine.motion import plans
from app.machine.motion.plans import RunPlanner
from app.machine.motion.refusals import machine_abilities, violation_issues
from app.machine.motion.spinup import spin_up_waits
from app.machine.motion.timescale import PauseFeed, PausePoint, pause_points
from app.program_lines import LineIndex
from app.toolpath import build_toolpath
from planner.core.errors import PlannerError, ProgramError
from planner.core.heap import trim_heap
from planner.core.machine import MachineSpec
from planner.core.program import EventKind, MoveKind, Program, SpindleSpeed
from planner.core.tools import ToolTable
from planner.gcode.interpreter import read_program
from planner.gcode.source import count_lines
from planner.motion.plan import Plan
from planner.motion.window import PlanWindow
from planner.pipeline import Refused, SoftLimitError, load

__all__ = ["LOAD_SHARES", "Cancelled", "LoadRequest", "check_pass", "check_text"]


class Cancelled(Exception):
    """A load superseded by a newer one stops between its stages."""


@dataclass(eq=False)
class LoadRequest:
    """One load in flight (owned by the controller's thread; the worker fills ``outcome``)."""

    generation: int
    text: str
    name: str
    path: str
    start_position: np.ndarray
    cfg: MachineConfig  # what it is checked against (identity: stale after update_config)
    offsets: dict[str, tuple[float, ...]]
    tools: ToolTable = field(default_factory=ToolTable)   # the table G43 reads (identity: stale)
    tool_in_spindle: int = 0
    parameters: dict[int, float] = field(default_factory=dict)   # G92, G28/G30 ... (var file)
    # the tool length offset in force at the start (G43 / G43.1 / G49 code, values per axis)
    tool_offset: tuple[int, tuple[float, ...]] | None = None
    cancel: threading.Event = field(default_factory=threading.Event)
    done: threading.Event = field(default_factory=threading.Event)
    progress: float = 0.0  # 0..1, written by the worker as it reads, checks and plans
    # the text is read from ``path`` by the worker (``text`` is "" until then): a file of
    # 250 MB takes half a second to read and decode, which the GUI thread must not wait for
    read_file: bool = False
    # the spindle when the program starts and its spin-up time: the cycle time counts the waits
    spindle: SpindleState = field(default_factory=SpindleState)
    spin_up_s: float = 0.0
    block_delete: bool = False   # the operator's switch: lines starting with '/' skipped
    # ProgramInfo, or (issues, reason) for a refused program; None while running / cancelled
    outcome: ProgramInfo | tuple[tuple[ProgramIssue, ...], str] | None = None
    finished: bool = False  # applied in the controller's thread (or dropped)


# the parts of a load's time (read, soft limits, plan; the tool path the rest), as measured
# on a 2,000,000-line raster: the progress shown moves evenly
LOAD_SHARES = (0.25, 0.05, 0.55)


def check_text(
    req: LoadRequest, machine: MachineSpec, plan_fn: RunPlanner
) -> ProgramInfo | tuple[tuple[ProgramIssue, ...], str]:
    """The heavy part of a load (any thread): parse, soft limits, plan, tables.

    Raises ``Cancelled`` between stages once ``req.cancel`` is set."""

    def stage() -> None:
        if req.cancel.is_set():
            raise Cancelled
        time.sleep(0)  # hand the GIL to the GUI thread between stages

    def stage_progress(first: float, share: float) -> Callable[[int, int], None]:
        """A progress callback for one stage: its part of the load, ``first`` .. + ``share``."""
        def report(done: int, total: int) -> None:
            req.progress = first + share * min(1.0, done / max(total, 1))
        return report

    text: str | None = req.text
    if req.read_file:
        try:
            # the text first, decoded a piece at a time, before any move is made: the reader
            # then goes through it a piece at a time too (text, bytes and the moves of
            # 10,000,000 lines were once held at once: 250 MB each and 460 MB)
            text = read_program(req.path, machine.planner.max_program_bytes)
        except PlannerError as exc:
            why = str(exc).split(": ", 1)[1] if ": " in str(exc) else str(exc)
            return (ProgramIssue(0, 0, why),), str(exc)
        req.read_file = False
    assert text is not None
    req.text = text
    name = req.name

    def plan(program: Program) -> tuple[Plan | None, float, float, tuple[PausePoint, ...]]:
        """The last stage: the run's plan; a planner error here is the planner's."""
        req.progress = LOAD_SHARES[0] + LOAD_SHARES[1]
        progress = stage_progress(req.progress, LOAD_SHARES[2])
        try:
            if len(program.moves) > plans.WINDOWED_RUN_MOVES:
                # planned through once, segment by segment as the run will plan it, keeping the
                # time, the length and the pause points: the run plans it again as it goes
                return (None, *check_pass(program, plan_fn.window(program), progress))
            whole = plan_fn(program, progress=progress)
        except PlannerError as exc:
            raise PlannerError(f"planner: {exc}") from None
        return (whole, float(whole.cycle_time_s), float(np.sum(whole.segment.table.length)),
                tuple(pause_points(whole, False, True)))

    try:
        loaded = load(text, name, machine, plan, start_position=req.start_position, tools=req.tools,
                      tool_in_spindle=req.tool_in_spindle, parameters=req.parameters,
                      block_delete=req.block_delete, tool_offset=req.tool_offset,
                      abilities=machine_abilities(req.cfg),
                      progress=stage_progress(0.0, LOAD_SHARES[0]), between=stage)
    except Refused as exc:
        e = exc.errors[0]
        issue = ProgramIssue(e.line, e.col, e.message)
        return (issue,), (f"line {e.line}: {e.message}" if e.line > 0 else e.message)
    except ProgramError as exc:
        issues = tuple(ProgramIssue(e.line, e.col, e.message) for e in exc.errors)
        return issues, f"{len(issues)} error(s) in the program; first: {issues[0]}"
    except SoftLimitError as exc:
        beyond = violation_issues(list(exc.violations))
        return beyond, f"soft limit: {beyond[0]}"
    except PlannerError as exc:
        return (ProgramIssue(0, 0, str(exc)),), str(exc)
    program = loaded.program
    plan_made, plan_end_s, length_mm, stops = loaded.plan
    assert loaded.bounds is not None
    lo, hi = loaded.bounds
    blended = loaded.blends
    stage()
    req.progress = sum(LOAD_SHARES)
    toolpath = build_toolpath(program)
    starts = LineIndex(text)
    trim_heap()  # the check's freed temporaries back to the system (planner.core.heap)
    return ProgramInfo(
        name=name,
        path=req.path,
        text=text,
        line_count=program.line_count or count_lines(text),
        move_count=len(program.moves),
        cycle_time_s=plan_end_s + sum(wait for _tau, wait in spin_up_waits(stops, req.spindle,
                                                                           req.spin_up_s)),
        length_mm=length_mm,
        bounds_min=tuple(float(x) for x in lo),
        bounds_max=tuple(float(x) for x in hi),
        program=program,
        plan=plan_made,
        plan_end_s=plan_end_s,
        stops=stops,
        toolpath=toolpath,
        line_starts=starts,
        blends=blended.blends,
        path_deviation_mm=blended.max_corner_deviation_mm,
        reread=loaded.reread if program.probes or program.inputs else None,
        warnings=spindle_stopped_cuts(program, req.spindle),
    )


def spindle_stopped_cuts(program: Program, start: SpindleState) -> tuple[ProgramIssue, ...]:
    """Feed moves the program makes with the spindle stopped after an M6 (LinuxCNC's M6 stops it
    until the program's own M3/M4): the first of each such stretch, naming the M6, for the
    operator to confirm before the run (a program that forgot its M3 would cut with a still
    tool). The moves are columns: a stretch is found by its first feed move, not one by one."""
    changes = [e for e in program.events if e.kind in (EventKind.TOOL_CHANGE, EventKind.SPINDLE)]
    if not any(e.kind is EventKind.TOOL_CHANGE for e in changes):
        return ()
    n = len(program.moves)
    cols = program.moves.columns()
    kinds, lines = cols.kind, cols.line
    feed = np.flatnonzero(kinds != int(MoveKind.RAPID))
    # a probe move is made with the spindle stopped on purpose (the tool measured on the setter
    # after the M6, a probe's search): no cut to ask about
    probing = np.fromiter((e.after_move for e in program.events if e.kind is EventKind.PROBE), np.int64)
    feed = np.setdiff1d(feed, probing)
    found: list[ProgramIssue] = []
    on = start.on
    stopped_by = 0
    bounds = [*changes, None]
    for k, e in enumerate(changes):
        if e.kind is EventKind.TOOL_CHANGE:
            on, stopped_by = False, e.line
        else:
            on = e.payload_as(SpindleSpeed).signed_rpm != 0.0
        if on or not stopped_by:
            continue
        nxt = bounds[k + 1]
        lo, hi = e.after_move + 1, (nxt.after_move + 1 if nxt is not None else n)
        i = int(np.searchsorted(feed, lo))
        if i < len(feed) and feed[i] < hi:
            found.append(ProgramIssue(int(lines[feed[i]]), 0,
                                      f"feed move with the spindle stopped: the M6 at line {stopped_by} "
                                      "stopped it and no M3/M4 started it again"))
    return tuple(found)


def check_pass(program: Program, window: PlanWindow,
               progress: Callable[[int, int], None]) -> tuple[float, float, tuple[PausePoint, ...]]:
    """The whole plan of ``window``'s program made once, segment by segment, each let go once
    seen: its end (planned time), its length and its pause points."""
    feed = PauseFeed(program, False, True)
    stops: list[PausePoint] = []
    length = 0.0
    n = len(program.moves)
    while not window.done:
        for seg in window.ensure(window.covered_until + 1e-9):
            stops.extend(feed.points_in(seg))
            length += float(np.sum(seg.table.length))
            progress(int(seg.table.index[-1]) + 1, n)
        window.release(window.covered_until)
    return window.t_end, length, tuple(stops)


