"""The load's heavy part, run off the controller's thread: read, parse, refuse what this machine
cannot run (``app.machine.motion.refusals``), blend, check the soft limits of the whole path,
plan, and make the tables the pages show. Every refusal names the line (and the column where
the code stands) and says why.
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
from app.machine.motion.refusals import analog_refusal, probe_refusal, synchronised_refusal, violation_issues
from app.machine.motion.spinup import spin_up_waits
from app.machine.motion.timescale import PauseFeed, PausePoint, pause_points
from app.program_lines import LineIndex
from app.toolpath import build_toolpath
from planner.blend import blend_program, blend_report
from planner.errors import PlannerError, ProgramError
from planner.heap import trim_heap
from planner.interpreter import parse_program, read_program
from planner.machine import MachineSpec
from planner.program import ProbeResult, Program
from planner.softlimits import check_and_bound
from planner.tools import ToolTable
from planner.window import PlanWindow

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
            text = read_program(req.path)
        except PlannerError as exc:
            why = str(exc).split(": ", 1)[1] if ": " in str(exc) else str(exc)
            return (ProgramIssue(0, 0, why),), str(exc)
        req.read_file = False
    assert text is not None
    req.text = text
    name = req.name

    def reread(probes: tuple[ProbeResult | None, ...], waits: tuple[float | None, ...]) -> Program:
        """The same program from the same start, read with the probe results (G38.x) and the
        values of the inputs (M66)."""
        again = parse_program(text, name, machine=machine, start_position=req.start_position,
                              tools=req.tools, tool_in_spindle=req.tool_in_spindle,
                              parameters=req.parameters, probe_results=probes, input_results=waits,
                              block_delete=req.block_delete)
        return blend_program(again, machine) if machine.planner.mode == "lookahead" else again

    try:
        program = parse_program(text, name, machine=machine, start_position=req.start_position,
                                tools=req.tools, tool_in_spindle=req.tool_in_spindle,
                                parameters=req.parameters, progress=stage_progress(0.0, LOAD_SHARES[0]),
                                block_delete=req.block_delete)
    except ProgramError as exc:
        issues = tuple(ProgramIssue(e.line, e.col, e.message) for e in exc.errors)
        return issues, f"{len(issues)} error(s) in the program; first: {issues[0]}"
    except PlannerError as exc:
        return (ProgramIssue(0, 0, str(exc)),), str(exc)
    finally:
        trim_heap()   # the reading's freed temporaries back to the system
    probe_cfg = req.cfg.probe
    refusals: list[tuple[int, str, str]] = []
    if program.probes:
        refusals.append((*probe_refusal(program, probe_cfg.drive, probe_cfg.max_feed_mm_min), "G38"))
    if program.synchronised:
        refusals.append((*synchronised_refusal(program), program.synchronised[0].code))
    if program.analog_outputs:
        refusals.append((*analog_refusal(program), program.analog_outputs[0].code))
    for at, why, code in refusals:
        if why:
            line = text.split("\n", at)[at - 1].upper() if at > 0 else ""
            col = line.find(code) + 1 or 1
            return (ProgramIssue(at, col, why),), f"line {at}: {why}"
    if machine.planner.mode == "lookahead":
        # G64 P: the program of record is the blended one (preview, progress, resume and the
        # plan all count its moves)
        program = blend_program(program, machine)
    if not program.moves:
        why = ("the program moves no axis: nothing to run (spindle, tool and coolant codes alone "
               "are given in MDI, M61 Q for the tool in the spindle)")
        return (ProgramIssue(0, 0, why),), why
    stage()
    blended = blend_report(program)
    # every move's extremes, arcs exact, a piece of the program at a time: limits and bounds
    violations, lo, hi = check_and_bound(program, machine)
    beyond = violation_issues(violations)
    if beyond:
        return beyond, f"soft limit: {beyond[0]}"
    stage()
    req.progress = LOAD_SHARES[0] + LOAD_SHARES[1]
    progress = stage_progress(req.progress, LOAD_SHARES[2])
    plan = None
    try:
        if len(program.moves) > plans.WINDOWED_RUN_MOVES:
            # planned through once, segment by segment as the run will plan it, keeping the
            # time, the length and the pause points: the run plans it again as it goes
            plan_end_s, length_mm, stops = check_pass(program, plan_fn.window(program), progress)
        else:
            plan = plan_fn(program, progress=progress)
            plan_end_s = float(plan.cycle_time_s)
            length_mm = float(np.sum(plan.segment.table.length))
            stops = tuple(pause_points(plan, False, True))
    except PlannerError as exc:
        return (ProgramIssue(0, 0, f"planner: {exc}"),), f"planner: {exc}"
    stage()
    req.progress = sum(LOAD_SHARES)
    toolpath = build_toolpath(program)
    starts = LineIndex(text)
    trim_heap()  # the check's freed temporaries back to the system (planner.heap)
    return ProgramInfo(
        name=name,
        path=req.path,
        text=text,
        line_count=program.line_count or text.count("\n") + 1,
        move_count=len(program.moves),
        cycle_time_s=plan_end_s + sum(wait for _tau, wait in spin_up_waits(stops, req.spindle,
                                                                           req.spin_up_s)),
        length_mm=length_mm,
        bounds_min=tuple(float(x) for x in lo),
        bounds_max=tuple(float(x) for x in hi),
        program=program,
        plan=plan,
        plan_end_s=plan_end_s,
        stops=stops,
        toolpath=toolpath,
        line_starts=starts,
        blends=blended.blends,
        path_deviation_mm=blended.max_corner_deviation_mm,
        reread=reread if program.probes or program.inputs else None,
    )


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


