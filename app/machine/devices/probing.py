"""The probing wizards: a part set up by touch (a surface, an edge, a corner, a bore, a boss,
the angle of a face), as Probe Basic's and Sinumerik's "measure workpiece" do.

Each wizard is a G-code routine shipped with the control (``resources/subroutines/probe_*.ngc``,
O-word subroutines an integrator can read and replace from a folder of ``[planner]
subroutine_dirs``), called from a few blocks this module writes and run as MDI is: read,
checked against the soft limits and the machine's rules, drawn before the operator confirms,
and run with the probe read at every contact. Every positioning move of a routine is a G38.3
that stops on a contact ("probe touched during positioning"); a probe move that finds nothing
is an alarm (G38.2); a bore or boss whose diameter is not the one expected stops the routine
before it writes. The result goes into the chosen coordinate system by the routine's own G10
(L20 for a position, L2 R for an angle), or is only reported.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import Protocol

import numpy as np

from app.machine.config import ProbeSettings
from app.machine.model import WIZARD, CommandResult, MachineState, ProbingRequest, ProbingResult
from app.machine.motion.jobs import Job
from app.machine.ports import CoordinatesView, PositionsView, Settings, ToolsView
from app.machine.state.gate import Action
from app.machine.state.states import StateMachine
from planner.core.machine import WORK_OFFSET_NAMES
from planner.core.program import EventKind, Program

__all__ = ["Probing", "RoutineRunner", "probing_routine"]


_RESULT = re.compile(r"probe result:(.*)")
_POSITIONS = ("X", "Y", "Z")   # what the routines report as positions (the wizards probe in X, Y, Z)
_VALUE = re.compile(r"([A-Z])=(-?\d+(?:\.\d+)?)")


class RoutineRunner(Protocol):
    """Reads and runs a few blocks the controller wrote as MDI (``ManualMotion``): the
    probing wizards' and the tool setter's."""

    def check_routine(self, text: str, name: str, action: str) -> Program | CommandResult: ...

    def run_routine(self, text: str, name: str, action: str,
                    when_done: Callable[[Job], None] | None = None, reason: str = "",
                    steps: dict[int, str] | None = None) -> CommandResult: ...

    def show_message(self, text: str) -> None: ...


class Probing:
    """The probing wizards (``controller.probing``)."""

    def __init__(self, settings: Settings, states: StateMachine, tools: ToolsView, positions: PositionsView,
                 coordinates: CoordinatesView, manual: RoutineRunner,
                 finished: Callable[[ProbingResult], None]) -> None:
        self._settings = settings
        self._states = states
        self._tools = tools
        self._positions = positions
        self._coordinates = coordinates
        self._manual = manual
        self._finished = finished
        self.last: ProbingResult | None = None

    # ------------------------------------------------------------------ the routine
    def routine(self, req: ProbingRequest) -> str:
        """The blocks the wizard runs with the tool in the spindle (``probing_routine``)."""
        coordinates = self._coordinates
        active = coordinates.active_offset
        same_turn = not req.system or coordinates.rotation_of(req.system) == coordinates.rotation_of(active)
        return probing_routine(req, self._settings.config.probe, self._tools.in_spindle, active, same_turn)

    def refusal(self, req: ProbingRequest) -> str:
        """Why the wizard cannot run now ("" when it can)."""
        cfg = self._settings.config
        probe = cfg.probe
        if self._states.state is not MachineState.IDLE:
            return f"machine is {self._states.state.label.lower()}"
        if probe.drive is None:
            return "this machine has no probe input ([probe] drive in the machine configuration)"
        if not {"X", "Y", "Z"} <= set(cfg.axes):
            return "probing a part needs X, Y and Z axes"
        if not all(self._positions.homed):
            return "axes not homed: home them before probing"
        tool = self._tools.in_spindle
        why = probe.probe_refusal(tool)
        if why:
            return why
        spec = self._tools.table.get(tool)
        if tool == 0 or spec is None:
            return "no probe in the spindle: put it in and set it (In the spindle) first"
        if spec.diameter_mm <= 0.0:
            return (f"T{tool} has no tip diameter in the tool table: the edges found would be off by "
                    "the ball's radius")
        if req.system and req.system not in WORK_OFFSET_NAMES:
            return f"unknown work offset {req.system} (G54-G59.3)"
        if req.axis not in ("X", "Y") or req.x_dir not in (-1, 1) or req.y_dir not in (-1, 1):
            return "the direction is +X, -X, +Y or -Y"
        if not req.diameter_mm > 0.0:
            return "the diameter must be above 0 mm"
        if not req.along_mm > 0.0:
            return "the distance along the faces must be above 0 mm"
        if "depth" in WIZARD[req.wizard].inputs and not req.depth_mm > 0.0:
            return "the depth below the start must be above 0 mm"
        if not req.tolerance_mm > 0.0:
            return "the diameter's tolerance must be above 0 mm"
        fast = probe.fast_feed_mm_min if req.fast_feed_mm_min is None else req.fast_feed_mm_min
        slow = probe.slow_feed_mm_min if req.slow_feed_mm_min is None else req.slow_feed_mm_min
        if not slow < fast:
            # the edge is read at the slow probe, after the fast one found it: slower is what
            # makes it exact (the stylus' overtravel grows with the feed)
            return (f"the slow probe feed F{slow:g} must be below the fast one F{fast:g} mm/min: the edge "
                    "is read at the slow one")
        return ""

    # ------------------------------------------------------------------ commands
    def preview_probing(self, req: ProbingRequest) -> Program | CommandResult:
        """The wizard's moves as they would run without a contact (each probe to the end of its
        search), read and checked as they will run; why not otherwise (not told to the panel as
        a refusal: the panel asks at every change of the inputs and shows it itself)."""
        why = self.refusal(req)
        if why:
            return CommandResult(False, str(Action.PROBE), why)
        return self._manual.check_routine(self.routine(req), _name(req), Action.PROBE)

    def run_probing(self, req: ProbingRequest) -> CommandResult:
        """Run the wizard; ``finished`` (and ``last``) get what it found when it ends."""
        why = self.refusal(req)
        if why:
            return self._states.refuse(Action.PROBE, why)
        self.last = None

        def done(job: Job) -> None:
            result = self._result(req, job)
            if result is None:
                return
            self.last = result
            self._manual.show_message(result.text())
            self._finished(result)

        return self._manual.run_routine(self.routine(req), _name(req), Action.PROBE, done,
                                        reason=f"probing {_name(req)}")

    def _result(self, req: ProbingRequest, job: Job) -> ProbingResult | None:
        """What the routine reported, read from it with every contact the machine made."""
        if job.reread is None:
            return None
        full = job.reread(job.probe_results, job.wait_results).program
        reported = [e.message for e in full.events
                    if e.kind is EventKind.MESSAGE and _RESULT.search(e.message)]
        if not reported:
            return None
        found = _RESULT.search(reported[-1])
        assert found is not None
        values = {k: float(v) for k, v in _VALUE.findall(found.group(1))}
        return ProbingResult(req.wizard, self._in_machine(full, job, values), req.system)

    def _in_machine(self, full: Program, job: Job, values: dict[str, float]) -> dict[str, float]:
        """The routine's positions (in the work frame it probed in: the system before the result
        was written to it) as machine positions, and its angle against the machine's X axis: what
        the result says does not depend on the frame it changed. An axis the routine does not
        report is taken from the last contact (an edge found in X in a turned frame lies where
        that contact's Y is)."""
        axes = self._settings.config.axes
        contacts = [(i, r) for i, r in enumerate(job.probe_results) if r is not None and i < len(full.probes)]
        if not contacts:
            return values
        i, contact = contacts[-1]
        frame = full.frame_at(max(full.probes[i].move_index, 0))
        work = frame.to_program(np.array(contact.trip_position, dtype=float))
        placed = [k for k in values if k in _POSITIONS and k in axes]   # "A" is an angle, "D" a diameter
        for k in placed:
            work[axes.index(k)] = values[k]
        machine = frame.to_machine(work)
        out = {k: float(machine[axes.index(k)]) if k in placed else v for k, v in values.items()}
        if "A" in out:
            out["A"] = values["A"] + frame.rotation_deg
        return out


def probing_routine(req: ProbingRequest, probe: ProbeSettings, tool: int, active: str,
                    same_turn: bool = True) -> str:
    """The blocks a wizard runs: the probe's length in force (G43 H ``tool``) and the routine's
    call with ``[probe]``'s feeds and distances where the request leaves them; the routine writes
    the result into the system that takes it (G10 with its P number) while the system ``active``
    stays in use, as the DRO shows it. Only when that system is turned otherwise than the one in
    use (``same_turn`` False: a distance measured in one is not one along the other's axes) the
    routine runs in it and the system in use is selected again after."""
    search = probe.search_mm if req.search_mm is None else req.search_mm
    clear = probe.clearance_mm if req.clearance_mm is None else req.clearance_mm
    fast = probe.fast_feed_mm_min if req.fast_feed_mm_min is None else req.fast_feed_mm_min
    slow = probe.slow_feed_mm_min if req.slow_feed_mm_min is None else req.slow_feed_mm_min
    back = probe.retract_mm if req.retract_mm is None else req.retract_mm
    write = WORK_OFFSET_NAMES.index(req.system) + 1 if req.system else 0     # G10's P, 0: only reported
    args = (search, fast, slow, back, clear, write, *WIZARD[req.wizard].args(req))
    call = f"o<{req.wizard.value}> call " + " ".join(f"[{v:.6g}]" for v in args)
    switch = bool(req.system) and req.system != active and not same_turn
    lines = [req.system] if switch else []
    lines += [f"G43 H{tool}", call]
    if switch:
        lines.append(active)
    return "\n".join(lines)


def _name(req: ProbingRequest) -> str:
    return WIZARD[req.wizard].name
