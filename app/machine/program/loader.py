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

A program of more than ``WINDOWED_RUN_MOVES`` moves (``app.machine.motion.plans``) is planned
through once here, segment by segment (``check_pass``: its time, length and pause points), and
its plan is not kept: cycle start plans it again as the run reaches it (``planner.motion.window``).

Cycle start runs the plan made here (``ProgramInfo.plan``) as long as it is valid: same
configuration (limits, budget, planner mode) and work offsets, and the machine where the program
was interpreted from (``program_stale``). Otherwise the program is checked again by this same
path (``recheck_program``: in the worker thread, or synchronously with ``wait``), as is done at
once after ``update_config``; with single block on, its plan (exact stop at every block end) is
made in a worker thread too (``start_run_plan``). Cycle start is refused meanwhile
(``refusal``; ``loading`` is True).

The work is pure Python and NumPy: the thread shares the GIL with the GUI thread, which gets
it back at every switch interval (5 ms) and between the stages, so the panel keeps drawing
(figures: ``python -m bench.bench_load``). The heavy part itself: ``app.machine.program.checks``.
"""

from __future__ import annotations

import os
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from PySide6.QtCore import QObject

from app.background import Background
from app.machine.config import MachineConfig
from app.machine.infra.events import MachineEvents, PanelChannels
from app.machine.model import CommandResult, ProgramInfo, ProgramIssue
from app.machine.motion.making import JobMaker
from app.machine.motion.plans import single_block_program
from app.machine.ports import (
    CoordinatesView,
    MotionState,
    PositionsView,
    RunModes,
    Settings,
    SpindleView,
    ToolView,
)
from app.machine.program.checks import Cancelled, LoadRequest, check_text
from app.machine.state.gate import Action, guarded
from app.machine.state.states import StateMachine
from planner.core.errors import PlannerError
from planner.core.gcpause import gc_paused
from planner.core.heap import trim_heap
from planner.core.program import Program
from planner.core.tools import ToolTable
from planner.motion.plan import Plan
from planner.motion.window import PlanWindow

__all__ = ["ProgramLoader", "RunPlanRequest"]


@dataclass(eq=False)
class RunPlanRequest:
    """A run plan being made in a worker thread (single block: the program with an exact stop
    at every block end), for the loaded ``info`` under the configuration ``cfg``."""

    info: ProgramInfo
    cfg: MachineConfig
    program: Program  # the variant to plan
    single_block: bool
    cancel: threading.Event = field(default_factory=threading.Event)
    done: threading.Event = field(default_factory=threading.Event)
    plan: Plan | None = None  # when done
    error: str = ""
    finished: bool = False


class ProgramLoader:
    """Asynchronous program loading: the load and the single-block plan in flight, each run
    off the controller's thread (``app.background``), announced by ``loadingChanged``
    (``controller.loader``)."""

    def __init__(self, settings: Settings, states: StateMachine, positions: PositionsView,
                 coordinates: CoordinatesView, tools: ToolView, spindle: SpindleView, motion: MotionState,
                 jobs: JobMaker, switches: RunModes, out: PanelChannels, events: MachineEvents,
                 qt_parent: QObject) -> None:
        self._settings = settings
        self._states = states
        self._positions = positions
        self._coordinates = coordinates
        self._tools = tools
        self._spindle = spindle
        self._motion = motion
        self._jobs = jobs
        self._out = out
        self._events = events
        self._modes = switches      # block delete and single block, as a check reads them
        self.program_info: ProgramInfo | None = None
        self._program_text = ""
        self._program_path = ""
        self.load_request: LoadRequest | None = None  # the load in flight
        self._load_generation = 0
        self._load_reason = ""  # why the last load was refused
        self._let_go_of = False  # a program was let go by the load starting (its pages not yet trimmed)
        # the configuration, offsets, parameters, tools and switches the program was checked with
        self._program_cfg: MachineConfig | None = None
        self._program_offsets: dict[str, tuple[float, ...]] = {}
        self._program_block_delete = False
        self._program_parameters: dict[int, float] = {}
        self._program_tool_offset: tuple[int, tuple[float, ...]] | None = None
        self._program_tools: tuple[ToolTable, int] | None = None
        self.run_plan_request: RunPlanRequest | None = None  # single-block plan in flight
        self._run_plan_ready: RunPlanRequest | None = None  # ... and the one made
        # checks and plans run off the controller's thread; results come back to it (children of
        # the controller's object: nothing is delivered once the controller is gone)
        self._loads = Background("program-load", self._on_load_done, qt_parent)
        self._run_plans = Background("program-run-plan", self._on_run_plan_done, qt_parent)
        events.config_applied.connect(self._config_applied)

    @property
    def gate(self) -> StateMachine:
        return self._states

    @property
    def _block_delete(self) -> bool:
        return self._modes.block_delete

    @property
    def program(self) -> Program | None:
        """The loaded, checked program (None if none)."""
        return self.program_info.program if self.program_info is not None else None

    @property
    def plan(self) -> Plan | None:
        """The plan of the loaded program (planned with the override budget; None for a long
        program, planned as it runs)."""
        return self.program_info.plan if self.program_info is not None else None

    @property
    def checking_name(self) -> str:
        """The program being checked ("" when none)."""
        req = self.load_request
        return req.name if req is not None else ""

    @property
    def planning_name(self) -> str:
        """The program being planned for single block ("" when none)."""
        req = self.run_plan_request
        return req.info.name if req is not None else ""

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

    @guarded(Action.LOAD_PROGRAM)
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
        self._events.load_requested.emit()  # a new program is not the one a waiting start meant
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
                    self._out.loadingChanged.emit(False, old)
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
        return self._states.ok(Action.LOAD_PROGRAM)

    def wait_loaded(self, timeout_s: float | None = 60.0) -> CommandResult:
        """Block (in the controller's thread) until the load in flight is finished and applied
        (``programLoaded`` / ``programErrors`` emitted); without one, the state of the last
        load. Falsy with the reason when the program was refused or the wait timed out."""
        deadline = None if timeout_s is None else time.monotonic() + timeout_s
        while (req := self.load_request) is not None:  # a restart after a config change: again
            left = None if deadline is None else max(deadline - time.monotonic(), 0.0)
            if not req.done.wait(left):
                return CommandResult(False, Action.LOAD_PROGRAM,
                                     f"still checking {req.name} after {timeout_s} s")
            self._apply_load(req)
        if self.program_info is None:
            return CommandResult(False, "load_program", self._load_reason or "no program loaded")
        return self._states.ok(Action.LOAD_PROGRAM)

    # --- internals -----------------------------------------------------------------------
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
        self._events.program_let_go.emit()

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
            start_position=self._positions.machine_pos().copy(),
            cfg=self._settings.config,
            offsets=dict(self._coordinates.offsets),
            tools=self._tools.table,
            tool_in_spindle=self._tools.in_spindle,
            parameters=dict(self._coordinates.parameters),
            tool_offset=self._coordinates.start_offset(),
            spindle=self._spindle.spindle,
            spin_up_s=float(self._settings.config.controller.spindle_spinup_s),
            block_delete=self._block_delete,
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
        machine, plan_fn = self._coordinates.machine(), self._jobs.planner()
        self.load_request = req
        self._out.loadingChanged.emit(True, name)
        self._given_back()

        def work() -> LoadRequest:
            try:
                with gc_paused(freeze=True):
                    req.outcome = check_text(req, machine, plan_fn)
            except Cancelled:
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
            req.cfg is not self._settings.config or req.offsets != self._coordinates.offsets
        ):  # configuration changed meanwhile
            self.start_load(req.text, req.name, req.path, read_file=req.read_file)
            return
        outcome = req.outcome
        self._out.loadingChanged.emit(False, req.name)
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
            self._out.loadingChanged.emit(False, name)
        self._given_back()
        try:
            outcome = check_text(req, self._coordinates.machine(), self._jobs.planner())
        except Cancelled:  # pragma: no cover - nobody cancels a synchronous load
            return CommandResult(False, Action.LOAD_PROGRAM, "cancelled")
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
        self._program_tool_offset = req.tool_offset
        self._program_tools = (req.tools, req.tool_in_spindle)
        self._program_text = info.text
        self._program_path = info.path
        self._load_reason = ""
        self._out.programLoaded.emit(info)
        if self._modes.single_block and not self._motion.busy:
            self.start_run_plan(True)  # ready by the time cycle start is pressed
        self._events.program_loaded.emit(info)    # a cycle start waiting for it starts it
        return self._states.ok(Action.LOAD_PROGRAM)

    def _load_failed(self, issues: tuple[ProgramIssue, ...], reason: str) -> CommandResult:
        """A failed load unloads the previous program (as LinuxCNC drops the file on a failed
        open): cycle start is then refused with "no program loaded" instead of running the old
        program while the operator looks at the new one's errors."""
        self._supersede_run_plan()
        self.program_info = None
        self._program_text = ""
        self._program_path = ""
        self._events.program_refused.emit()
        self._load_reason = reason
        self._out.programErrors.emit(issues)
        return self._states.refuse(Action.LOAD_PROGRAM, reason)

    # --- run plans (single block) ------------------------------------------------------------
    def program_stale(self) -> str:
        """Why the loaded program (and its load-time plan) no longer fits the machine: the
        configuration or the work offsets changed, or the machine is not where the program
        was interpreted from; "" when it is still valid (or none is loaded)."""
        info = self.program_info
        if info is None:
            return ""
        if self._program_cfg is not self._settings.config:
            return "the machine configuration changed since it was loaded"
        if self._program_offsets != self._coordinates.offsets:
            return "the work offsets changed since it was loaded"
        if self._program_parameters != self._coordinates.parameters:
            return "G92, G28/G30 or other G-code parameters changed since it was loaded"
        if self._program_tools is None or self._program_tools[0] is not self._tools.table:
            return "the tool table changed since it was loaded"
        if self._program_tools[1] != self._tools.in_spindle:
            return "another tool is in the spindle since it was loaded"
        if self._program_tool_offset != self._coordinates.start_offset():
            return "the tool length offset in force changed since it was loaded"
        if self._program_block_delete != self._block_delete:
            return "block delete was switched since it was loaded"
        start = np.asarray(info.program.start_position)
        if np.max(np.abs(start - self._positions.machine_pos()), initial=0.0) > 1e-6:
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
        return self._states.ok(Action.LOAD_PROGRAM)

    def run_plan(self, single_block: bool) -> Plan | PlanWindow | None:
        """The ready plan for a cycle start of the loaded, still valid program: the load-time
        plan, or the single-block plan made for it; None when it is still to be made."""
        info = self.program_info
        if info is None:
            return None
        if info.plan is None:
            # a long program: planned as it runs, from its start (no plan to wait for)
            planner = self._jobs.planner()
            if single_block:
                return planner.window(single_block_program(info.program))
            return planner.window(info.program, info.plan_end_s)
        if not single_block:
            return info.plan
        ready = self._run_plan_ready
        if ready is not None and ready.info is info and ready.cfg is self._settings.config:
            return ready.plan
        return None

    def start_run_plan(self, single_block: bool = True) -> RunPlanRequest | None:
        """Plan the loaded program's single-block variant in a worker thread (unless ready or
        under way); cycle start is refused meanwhile (``refusal``)."""
        info = self.program_info
        if info is None or self.run_plan(single_block) is not None:
            return None
        cur = self.run_plan_request
        if (
            cur is not None
            and cur.info is info
            and cur.cfg is self._settings.config
            and cur.single_block == single_block
        ):
            return cur
        self._supersede_run_plan()
        prog: Program = info.program
        req = RunPlanRequest(info=info, cfg=self._settings.config, program=prog, single_block=single_block)
        plan_fn = self._jobs.planner()
        self.run_plan_request = req
        self._out.loadingChanged.emit(True, info.name)

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
            self._out.loadingChanged.emit(False, req.info.name)

    def _apply_run_plan(self, req: RunPlanRequest) -> None:
        """In the controller's thread: keep the finished run plan (if still wanted)."""
        if req.finished or req is not self.run_plan_request:
            return
        req.finished = True
        self.run_plan_request = None
        ok = True
        if req.plan is not None and req.info is self.program_info and req.cfg is self._settings.config:
            self._run_plan_ready = req
        elif req.error:
            self._out.message.emit(f"{req.info.name}: {req.error}")
            ok = False
        self._out.loadingChanged.emit(False, req.info.name)
        self._events.run_plan_done.emit(ok)     # a cycle start waiting for it starts, or not

    def wait_run_plan(self, timeout_s: float | None = 60.0) -> bool:
        """Block until the run plan under way (single block) is done; True when one is ready."""
        req = self.run_plan_request
        if req is not None:
            if not req.done.wait(timeout_s):
                return False
            self._apply_run_plan(req)
        return self._run_plan_ready is not None

    def _config_applied(self, wait: bool) -> None:
        """A new configuration: a load in flight restarts with it; a loaded program is checked
        again against it (before returning with ``wait``)."""
        req = self.load_request
        if req is not None:
            if wait:
                self.load_text(req.text, req.name, req.path)
            else:
                self.start_load(req.text, req.name, req.path)
        elif self.program_info is not None:
            self.recheck_program(wait)
