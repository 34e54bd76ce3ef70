"""Going on after the machine read something (a probe's contact, an input): the program is read
again from its start with every result so far (``Job.reread``), and what follows the read runs
from where the machine stands once it passes the soft limits; or the run stops with a STOP
alarm that leaves nothing to resume (what follows was read with a result the machine did not
give)."""

from __future__ import annotations

import os
from dataclasses import replace

import numpy as np

from app.machine.infra.events import PanelChannels
from app.machine.model import Activity, MachineState
from app.machine.motion.jobs import Job
from app.machine.motion.refusals import violation_issues
from app.machine.motion.streamer import Streamer
from app.machine.ports import AlarmSink, PositionsView
from app.machine.state.states import StateMachine
from planner.core.errors import PlannerError, ProgramError
from planner.core.program import EventKind, ProbeResult, Program, TableRef
from planner.gcode.modes import ABORT_MARK
from planner.geometry.resume import carry_overrides, program_from_store
from planner.pipeline import Refused, SoftLimitError

__all__ = ["ReadAgain"]


class ReadAgain:
    """The program read again with what the machine read, and the run going on with it."""

    def __init__(self, states: StateMachine, positions: PositionsView, motion: Streamer, alarms: AlarmSink,
                 out: PanelChannels) -> None:
        self._states = states
        self._positions = positions
        self._motion = motion
        self._alarms = alarms
        self._out = out

    def stop(self, cause: str, source: str) -> None:
        """A read that went wrong: a STOP alarm (``source`` names it), and no resume past it."""
        self._alarms.alarm_stop(cause, source, source, resumable=False)

    def continue_after(self, job: Job, kind: EventKind, index: int, where: str,
                       probes: tuple[ProbeResult | None, ...], waits: tuple[float | None, ...],
                       source: str) -> None:
        """At rest after read ``index`` of ``kind`` (PROBE, INPUT): read the program again with
        the results and run what follows it from where the machine stands, or stop saying why
        not (``source`` names the alarm's source)."""
        def fail(cause: str) -> None:
            self.stop(cause, source)

        if job.reread is None:
            fail(f"{where}: the program cannot be read again with the result")
            return
        try:
            again = job.reread(probes, waits, part=lambda full: after_event(full, kind, index))
        except Refused as exc:               # a branch the first reading did not take
            e = exc.errors[0]
            fail(f"{where}: with the result, line {e.line}: {e.message}")
            return
        except SoftLimitError as exc:
            fail(f"{where}: with the result, {violation_issues(list(exc.violations))[0]}")
            return
        except ProgramError as exc:
            e = exc.errors[0]
            if job.reason and not job.steps and os.path.isabs(e.file):
                # a routine the controller wrote (a probing wizard): what it says, under its name,
                # not the lines of its subroutines, which the operator never saw
                fail(f"{job.reason}: {e.message.partition(ABORT_MARK)[2] or e.message}")
            elif os.path.isabs(e.file):            # in a subroutine file (tool_measure.ngc ...)
                fail(f"{where}: with the result, {os.path.basename(e.file)} line {e.line} reads: {e.message}")
            else:
                fail(f"{where}: with the result, line {e.line} reads: {e.message}")
            return
        except PlannerError as exc:
            fail(f"{where}: with the result the program reads: {exc}")
            return
        full, rest = again.program, again.part
        if rest is None:
            fail(f"{where}: the program read again does not have it")
            return
        here = self._positions.reference_pos()
        if rest.moves and float(np.max(np.abs(rest.start_position - here))) > 1e-6:
            fail(f"{where}: the program read again does not go on from where the machine stands")
            return
        if not rest.moves:                   # nothing moves after it: the program ends here
            self._motion.finish_now(job, rest)
            return
        try:
            # after an operator's feed hold, the rest waits for cycle start
            self._motion.follow(job, rest, (full, len(full.moves) - len(rest.moves), 0.0),
                                held=self._states.state is MachineState.HOLD, reads=(probes, waits))
        except PlannerError as exc:
            fail(f"{where}: planner: {exc}")
            return
        if job.kind is Activity.PROGRAM:
            self._out.programReadAgain.emit(full)        # the preview draws the path the machine takes


def after_event(full: Program, kind: EventKind, index: int) -> Program | None:
    """What follows read ``index`` of ``kind`` in ``full``: its later moves, from where the move
    before the event ended, with the events that come after it in the program (a message right
    after it included; those before it were done already)."""
    at = next((k for k, e in enumerate(full.events)
               if e.kind is kind and e.payload_as(TableRef).index == index), -1)
    if at < 0:
        return None
    after = full.events[at].after_move
    first = after + 1
    events = carry_overrides(full, first, [replace(e, after_move=e.after_move - first)
                                           for e in full.events[at + 1:]])
    start = full.moves[after].end if after >= 0 else full.start_position
    return program_from_store(full, full.moves[first:].numbered_from_zero(), events, start)
