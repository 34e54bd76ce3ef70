"""Program loading: read, parse, soft-limit check and plan a program off the GUI thread.

``load_program`` reads the file (or takes the text), then hands the heavy work (interpreter,
soft-limit check of the whole path, planning, the ``ProgramInfo`` tables) to a worker thread
and returns at once; the outcome arrives through a queued signal in the controller's thread,
which emits ``programLoaded`` or ``programErrors`` exactly as a synchronous load did. While a
load runs, ``loading`` is True (``loadingChanged``), cycle start and run from line are refused
with the reason, and a newer load (or a configuration change) supersedes it: the older one is
cancelled between its stages and its result dropped. The program loaded before is let go as
a load starts (``program_info`` is None until the outcome; a failed load leaves none), a check
again after a touch-off included. ``load_program(..., wait=True)`` and ``wait_loaded()`` give
the synchronous behaviour for headless use (``cnc-run``, tests).

A program of more than ``WINDOWED_RUN_MOVES`` moves (``app.machine.feeder``) is planned
through once here, segment by segment (``check_pass``: its time, length and pause points), and
its plan is not kept: cycle start plans it again as the run reaches it (``planner.window``).

Cycle start runs the plan made here (``ProgramInfo.plan``) as long as it is valid: same
configuration (limits, budget, planner mode) and work offsets, and the machine where the program
was interpreted from (``_program_stale``). Otherwise the program is checked again by this same
path (``_recheck_program``: in the worker thread, or synchronously with ``wait``), as is done at
once after ``update_config``; with single block on, its plan (exact stop at every block end) is
made in a worker thread too (``_start_run_plan``). Cycle start is refused meanwhile
(``refusal``; ``loading`` is True).

The work is pure Python and NumPy: the thread shares the GIL with the GUI thread, which gets
it back at every switch interval (5 ms) and between the stages, so the panel keeps drawing
(figures: ``python -m bench.bench_load``). A part of ``MachineController``.
"""

from __future__ import annotations

import os
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from app.background import Background
from app.machine.inputs import probe_refusal
from app.machine.model import CommandResult, ProgramInfo, ProgramIssue, SpindleState
from app.machine.outputs import analog_refusal
from app.machine.spindle import spin_up_waits, synchronised_refusal
from app.machine.timescale import PauseFeed, PausePoint, pause_points
from app.program_lines import LineIndex
from app.toolpath import build_toolpath
from planner.blend import blend_program, blend_report
from planner.errors import PlannerError, ProgramError
from planner.gcpause import gc_paused
from planner.heap import trim_heap
from planner.interpreter import parse_program, read_program
from planner.machine import MachineSpec
from planner.program import ProbeResult, Program
from planner.softlimits import LimitViolation, check_and_bound, check_program
from planner.tools import ToolTable
from planner.window import PlanWindow

if TYPE_CHECKING:
    from app.machine.controller import MachineController

__all__ = ["ProgramLoader", "LoadRequest", "RunPlanRequest"]


class _Cancelled(Exception):
    pass


@dataclass(eq=False)
class LoadRequest:
    """One load in flight (owned by the controller's thread; the worker fills ``outcome``)."""

    generation: int
    text: str
    name: str
    path: str
    start_position: np.ndarray
    cfg: object  # the MachineConfig it is checked against (identity: stale after update_config)
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


@dataclass(eq=False)
class RunPlanRequest:
    """A run plan being made in a worker thread (single block: the program with an exact stop
    at every block end), for the loaded ``info`` under the configuration ``cfg``."""

    info: ProgramInfo
    cfg: object
    program: Program  # the variant to plan
    single_block: bool
    cancel: threading.Event = field(default_factory=threading.Event)
    done: threading.Event = field(default_factory=threading.Event)
    plan: Any = None  # planner.plan.Plan when done
    error: str = ""
    finished: bool = False


def _issues(violations: list[LimitViolation]) -> tuple[ProgramIssue, ...]:
    return tuple(ProgramIssue(v.line, 1, str(v).split(": ", 1)[1], v.axis) for v in violations)


def _issues_from_limits(program: Program, machine: MachineSpec) -> tuple[ProgramIssue, ...]:
    return _issues(check_program(program, machine))


# the parts of a load's time (read, soft limits, plan; the tool path the rest), as measured
# on a 2,000,000-line raster: the progress shown moves evenly
LOAD_SHARES = (0.25, 0.05, 0.55)


def check_text(
    req: LoadRequest, machine: MachineSpec, plan_fn: Any
) -> ProgramInfo | tuple[tuple[ProgramIssue, ...], str]:
    """The heavy part of a load (any thread): parse, soft limits, plan, tables.

    Raises ``_Cancelled`` between stages once ``req.cancel`` is set."""

    def stage() -> None:
        if req.cancel.is_set():
            raise _Cancelled
        time.sleep(0)  # hand the GIL to the GUI thread between stages

    def stage_progress(first: float, share: float):
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
    probe_cfg = getattr(req.cfg, "probe", None)
    refusals = []
    if program.probes:
        refusals.append((*probe_refusal(program, getattr(probe_cfg, "drive", None),
                                        getattr(probe_cfg, "max_feed_mm_min", 0.0)), "G38"))
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
    limit_issues = _issues(violations)
    if limit_issues:
        return limit_issues, f"soft limit: {limit_issues[0]}"
    stage()
    req.progress = LOAD_SHARES[0] + LOAD_SHARES[1]
    progress = stage_progress(req.progress, LOAD_SHARES[2])
    plan = None
    try:
        from app.machine import feeder

        if len(program.moves) > feeder.WINDOWED_RUN_MOVES:
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


class ProgramLoader:
    """Asynchronous program loading: the load and the single-block plan in flight, each run
    off the controller's thread (``app.background``), announced by ``loadingChanged``. A part
    of ``MachineController`` (``controller.loader``)."""

    def __init__(self, m: MachineController) -> None:
        self.m = m
        self.program_info: ProgramInfo | None = None
        self._program_text = ""
        self._program_path = ""
        self.load_request: LoadRequest | None = None  # the load in flight
        self._load_generation = 0
        self._load_reason = ""  # why the last load was refused
        self._let_go_of = False  # a program was let go by the load starting (its pages not yet trimmed)
        self._program_cfg: object = None  # configuration and offsets the program was checked with
        self._program_offsets: dict[str, tuple[float, ...]] = {}
        self._program_block_delete = False
        self._program_parameters: dict[int, float] = {}
        self._program_tools: tuple[ToolTable, int] | None = None
        self.run_plan_request: RunPlanRequest | None = None  # single-block plan in flight
        self._run_plan_ready: RunPlanRequest | None = None  # ... and the one made
        # checks and plans run off the controller's thread; results come back to it
        self._loads = Background("program-load", self._on_load_done, m)
        self._run_plans = Background("program-run-plan", self._on_run_plan_done, m)

    # --- public --------------------------------------------------------------------------
    @property
    def loading(self) -> bool:
        """True while a program is being read, checked and planned, or checked again, or
        planned for single block (cycle start refused meanwhile)."""
        return self.load_request is not None or self.run_plan_request is not None

    @property
    def loading_progress(self) -> float:
        """How far the program being checked is, 0 .. 1 (0 when none)."""
        req = self.load_request
        return req.progress if req is not None else 0.0

    @property
    def loading_name(self) -> str:
        """Name of the program being checked ("" when none)."""
        req = self.load_request
        if req is not None:
            return req.name
        rp = self.run_plan_request
        return rp.info.name if rp is not None else ""

    def load_program(
        self,
        source: str | os.PathLike[str],
        name: str | None = None,
        *,
        wait: bool = False,
        timeout_s: float | None = None,
    ) -> CommandResult:
        """Load a program from a path (``os.PathLike`` or an existing file name) or G-code text.

        Parses, checks the whole path against the soft limits (arcs by their exact extremes)
        and plans it before anything moves, in a worker thread: returns at once (truthy:
        accepted and being checked), then emits ``programLoaded`` or ``programErrors`` (all
        errors, with lines and axes) from the controller's thread. ``wait=True`` does the work
        in the calling thread and returns the outcome (falsy with the reason when refused), as
        ``wait_loaded`` does for a load already started. A newer load supersedes one in flight.
        Refused while running. Programs start in the interpreter's reset state (G54) unless they
        select a work offset; the active offset (``select_work_offset``) applies to MDI blocks
        and to the work coordinates shown.
        """
        self.m.run.start_pending = False  # a new program is not the one a waiting start meant
        why = self.m.states.refusal("load_program")
        if why:
            return self.m.states.refuse("load_program", why)
        path = ""
        if isinstance(source, os.PathLike) or (
            "\n" not in source and len(source) < 4096 and Path(source).is_file()
        ):
            path = str(source)
            try:  # can it be read at all (the worker reads it): refused at once if not
                with open(path, "rb"):
                    pass
            except OSError as exc:
                if self.load_request is not None:  # superseded by this failed one
                    old = self.load_request.name
                    self._supersede_load()
                    self.m.loadingChanged.emit(False, old)
                return self._load_failed(
                    (ProgramIssue(0, 0, f"cannot read: {exc.strerror or exc}"),),
                    f"{path}: cannot read: {exc.strerror or exc}",
                )
            text = ""
            name = name or Path(path).name
        else:
            text = str(source)
            name = name or "<text>"
        if wait:
            return self.load_text(text, name, path, read_file=bool(path))
        self.start_load(text, name, path, read_file=bool(path))
        if timeout_s is not None:
            return self.wait_loaded(timeout_s)
        return self.m.states.ok("load_program")

    def wait_loaded(self, timeout_s: float | None = 60.0) -> CommandResult:
        """Block (in the controller's thread) until the load in flight is finished and applied
        (``programLoaded`` / ``programErrors`` emitted); without one, the state of the last
        load. Falsy with the reason when the program was refused or the wait timed out."""
        deadline = None if timeout_s is None else time.monotonic() + timeout_s
        while (req := self.load_request) is not None:  # a restart after a config change: again
            left = None if deadline is None else max(deadline - time.monotonic(), 0.0)
            if not req.done.wait(left):
                return CommandResult(False, "load_program", f"still checking {req.name} after {timeout_s} s")
            self._apply_load(req)
        if self.program_info is None:
            return CommandResult(False, "load_program", self._load_reason or "no program loaded")
        return self.m.states.ok("load_program")

    # --- internals -----------------------------------------------------------------------
    def check_program_limits(self, program: Program) -> list[ProgramIssue]:
        """Soft-limit issues of a program's whole path (also used by MDI and run from line)."""
        return list(_issues_from_limits(program, self.m.conn.machine))

    def _let_go(self) -> None:
        """A load replaces the loaded program whatever its outcome (a refused one unloads it,
        as LinuxCNC drops a file it failed to open), so the program is let go as the load
        starts: two programs are never held at once (a 10,000,000-line one is half a gigabyte,
        and checking it again after a touch-off held it twice). Nothing could use it meanwhile:
        cycle start and run from line wait for the load, and the stop point to resume from
        belongs to the program let go (every load forgot it at its end already)."""
        self._supersede_run_plan()
        self._let_go_of = self.program_info is not None
        self.program_info = None
        self._program_text = ""     # a check again has it in its request
        self.m.run.resume_point = None

    def _given_back(self) -> None:
        """Once the pages have let the program go too (``loadingChanged``): its freed pages back
        to the system. They lie in the heap of the thread that made them, which the load's
        worker does not take from: kept, they were counted twice."""
        if self._let_go_of:
            self._let_go_of = False
            trim_heap()

    def _new_request(self, text: str, name: str, path: str, read_file: bool = False) -> LoadRequest:
        self._supersede_load()
        self._let_go()
        self._load_generation += 1
        return LoadRequest(
            generation=self._load_generation,
            text=text,
            name=name,
            path=path,
            read_file=read_file,
            start_position=self.m.states.machine_pos().copy(),
            cfg=self.m.config,
            offsets=dict(self.m.pos.offsets),
            tools=self.m.tools.table,
            tool_in_spindle=self.m.tools.in_spindle,
            parameters=dict(self.m.pos.parameters),
            spindle=self.m.spindle_ctl.spindle,
            spin_up_s=float(self.m.config.controller.spindle_spinup_s),
            block_delete=self.m.run.block_delete,
        )

    def _supersede_load(self) -> None:
        """Cancel the load in flight (its result, if any, is dropped)."""
        req = self.load_request
        if req is not None:
            req.cancel.set()
            req.finished = True
            self.load_request = None

    def start_load(self, text: str, name: str, path: str, read_file: bool = False) -> LoadRequest:
        """Check ``text`` (or, ``read_file``, the file ``path``) in a worker thread."""
        req = self._new_request(text, name, path, read_file)
        machine, plan_fn = self.m.conn.machine, self.m.stream.planner()
        self.load_request = req
        self.m.loadingChanged.emit(True, name)
        self._given_back()

        def work() -> LoadRequest:
            try:
                with gc_paused(freeze=True):
                    req.outcome = check_text(req, machine, plan_fn)
            except _Cancelled:
                req.outcome = None
            except Exception as exc:  # noqa: BLE001 - a planner bug must not kill the panel
                req.outcome = (
                    (ProgramIssue(0, 0, f"internal error while checking: {exc!r}"),),
                    f"internal error while checking: {exc!r}",
                )
            finally:
                req.done.set()
            return req

        self._loads.submit(work)  # the result comes back in the controller's thread
        return req

    def _on_load_done(self, req: object) -> None:
        if isinstance(req, LoadRequest) and not req.cancel.is_set():
            self._apply_load(req)

    def _on_run_plan_done(self, req: object) -> None:
        if isinstance(req, RunPlanRequest) and not req.cancel.is_set():
            self._apply_run_plan(req)

    def _apply_load(self, req: LoadRequest) -> None:
        """In the controller's thread: publish the outcome of ``req`` unless it was superseded."""
        if req.finished or req is not self.load_request:
            return
        req.finished = True
        self.load_request = None
        if (
            req.cfg is not self.m.config or req.offsets != self.m.pos.offsets
        ):  # configuration changed meanwhile
            self.start_load(req.text, req.name, req.path, read_file=req.read_file)
            return
        outcome = req.outcome
        self.m.loadingChanged.emit(False, req.name)
        if isinstance(outcome, ProgramInfo):
            self._program_loaded(outcome, req)
        elif outcome is not None:
            self._load_failed(*outcome)

    def load_text(self, text: str, name: str, path: str, read_file: bool = False) -> CommandResult:
        """Synchronous load in the calling thread (``wait=True``, re-checks after a
        configuration change or a move since loading); supersedes a load in flight."""
        was_loading = self.load_request is not None
        req = self._new_request(text, name, path, read_file)
        if was_loading:
            self.m.loadingChanged.emit(False, name)
        self._given_back()
        try:
            outcome = check_text(req, self.m.conn.machine, self.m.stream.planner())
        except _Cancelled:  # pragma: no cover - nobody cancels a synchronous load
            return CommandResult(False, "load_program", "cancelled")
        if isinstance(outcome, ProgramInfo):
            return self._program_loaded(outcome, req)
        return self._load_failed(*outcome)

    def _program_loaded(self, info: ProgramInfo, req: LoadRequest) -> CommandResult:
        self._supersede_run_plan()
        self.program_info = info
        self._program_cfg = req.cfg  # what the program and its plan were made for
        self._program_offsets = dict(req.offsets)
        self._program_block_delete = req.block_delete
        self._program_parameters = dict(req.parameters)
        self._program_tools = (req.tools, req.tool_in_spindle)
        self._program_text = info.text
        self._program_path = info.path
        self.m.run.resume_point = None
        self._load_reason = ""
        self.m.programLoaded.emit(info)
        if self.m.run.single_block and self.m.stream.job is None:
            self.start_run_plan(True)  # ready by the time cycle start is pressed
        self.m.run.pending_start()
        return self.m.states.ok("load_program")

    def _load_failed(self, issues: tuple[ProgramIssue, ...], reason: str) -> CommandResult:
        """A failed load unloads the previous program (as LinuxCNC drops the file on a failed
        open): cycle start is then refused with "no program loaded" instead of running the old
        program while the operator looks at the new one's errors."""
        self._supersede_run_plan()
        self.m.run.start_pending = False
        self.program_info = None
        self._program_text = ""
        self._program_path = ""
        self.m.run.resume_point = None
        self._load_reason = reason
        self.m.programErrors.emit(issues)
        return self.m.states.refuse("load_program", reason)

    # --- run plans (single block) ------------------------------------------------------------
    def program_stale(self) -> str:
        """Why the loaded program (and its load-time plan) no longer fits the machine: the
        configuration or the work offsets changed, or the machine is not where the program
        was interpreted from; "" when it is still valid (or none is loaded)."""
        info = self.program_info
        if info is None:
            return ""
        if self._program_cfg is not self.m.config:
            return "the machine configuration changed since it was loaded"
        if self._program_offsets != self.m.pos.offsets:
            return "the work offsets changed since it was loaded"
        if self._program_parameters != self.m.pos.parameters:
            return "G92, G28/G30 or other G-code parameters changed since it was loaded"
        if self._program_tools is None or self._program_tools[0] is not self.m.tools.table:
            return "the tool table changed since it was loaded"
        if self._program_tools[1] != self.m.tools.in_spindle:
            return "another tool is in the spindle since it was loaded"
        if self._program_block_delete != self.m.run.block_delete:
            return "block delete was switched since it was loaded"
        start = np.asarray(info.program.start_position)  # type: ignore[attr-defined]
        if np.max(np.abs(start - self.m.states.machine_pos()), initial=0.0) > 1e-6:
            return "the machine moved since it was loaded"
        return ""

    def recheck_program(self, wait: bool) -> CommandResult:
        """Check the loaded program again (parse, soft limits, plan) with the current machine:
        synchronously (``wait``) or in the worker thread like a load (cycle start refused
        until it is done). Same outcome either way (``check_text``)."""
        info = self.program_info
        assert info is not None
        if wait:
            return self.load_text(self._program_text, info.name, self._program_path)
        self.start_load(self._program_text, info.name, self._program_path)
        return self.m.states.ok("load_program")

    def run_plan(self, single_block: bool) -> Any:
        """The ready plan for a cycle start of the loaded, still valid program: the load-time
        plan, or the single-block plan made for it; None when it is still to be made."""
        info = self.program_info
        if info is None:
            return None
        if info.plan is None:
            # a long program: planned as it runs, from its start (no plan to wait for)
            from app.machine.feeder import single_block_program

            planner = self.m.stream.planner()
            if single_block:
                return planner.window(single_block_program(info.program))  # type: ignore[arg-type]
            return planner.window(info.program, info.plan_end_s)  # type: ignore[arg-type]
        if not single_block:
            return info.plan
        ready = self._run_plan_ready
        if ready is not None and ready.info is info and ready.cfg is self.m.config:
            return ready.plan
        return None

    def start_run_plan(self, single_block: bool = True) -> RunPlanRequest | None:
        """Plan the loaded program's single-block variant in a worker thread (unless ready or
        under way); cycle start is refused meanwhile (``refusal``)."""
        from app.machine.feeder import single_block_program

        info = self.program_info
        if info is None or self.run_plan(single_block) is not None:
            return None
        cur = self.run_plan_request
        if (
            cur is not None
            and cur.info is info
            and cur.cfg is self.m.config
            and cur.single_block == single_block
        ):
            return cur
        self._supersede_run_plan()
        prog: Program = info.program  # type: ignore[assignment]
        req = RunPlanRequest(info=info, cfg=self.m.config, program=prog, single_block=single_block)
        plan_fn = self.m.stream.planner()
        self.run_plan_request = req
        self.m.loadingChanged.emit(True, info.name)

        def work() -> RunPlanRequest:
            try:
                with gc_paused(freeze=True):
                    variant = single_block_program(prog) if single_block else prog
                    if not req.cancel.is_set():
                        req.plan = plan_fn(variant)
            except PlannerError as exc:
                req.error = f"planner: {exc}"
            except Exception as exc:  # noqa: BLE001 - a planner bug must not kill the panel
                req.error = f"internal error while planning: {exc!r}"
            finally:
                req.done.set()
            return req

        self._run_plans.submit(work)
        return req

    def _supersede_run_plan(self) -> None:
        req = self.run_plan_request
        self._run_plan_ready = None
        if req is not None:
            req.cancel.set()
            req.finished = True
            self.run_plan_request = None
            self.m.loadingChanged.emit(False, req.info.name)

    def _apply_run_plan(self, req: RunPlanRequest) -> None:
        """In the controller's thread: keep the finished run plan (if still wanted)."""
        if req.finished or req is not self.run_plan_request:
            return
        req.finished = True
        self.run_plan_request = None
        if req.plan is not None and req.info is self.program_info and req.cfg is self.m.config:
            self._run_plan_ready = req
        elif req.error:
            self.m.message.emit(f"{req.info.name}: {req.error}")
            self.m.run.start_pending = False
        self.m.loadingChanged.emit(False, req.info.name)
        self.m.run.pending_start()

    def wait_run_plan(self, timeout_s: float | None = 60.0) -> bool:
        """Block until the run plan under way (single block) is done; True when one is ready."""
        req = self.run_plan_request
        if req is not None:
            if not req.done.wait(timeout_s):
                return False
            self._apply_run_plan(req)
        return self._run_plan_ready is not None
