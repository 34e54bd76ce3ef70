"""Making jobs: a program (or what is left of one) planned for this machine with the override
budget, its executor at the operator's overrides, and the spindle's spin-ups its time counts."""

from __future__ import annotations

import math
from dataclasses import replace

from app.machine.infra.events import MachineEvents
from app.machine.model import Activity, ProgramInfo
from app.machine.motion.jobs import NO_TERMS, Job, JobTerms, Reads
from app.machine.motion.plans import RunPlanner, single_block_program
from app.machine.motion.spinup import spin_up_waits
from app.machine.motion.timescale import PauseFeed, PausePoint, TimeScaledExecutor, pause_points
from app.machine.ports import CoordinatesView, RunModes, Settings, SpindleView
from planner.core.machine import MachineSpec
from planner.core.program import Program
from planner.motion.plan import Plan
from planner.motion.window import PlanWindow

__all__ = ["JobMaker"]


class JobMaker:
    """Jobs for this machine, at the overrides of the moment (``Streamer.jobs``)."""

    def __init__(self, settings: Settings, coordinates: CoordinatesView, spindle: SpindleView,
                 modes: RunModes, events: MachineEvents) -> None:
        self._settings = settings
        self._coordinates = coordinates
        self._spindle = spindle
        self._modes = modes
        # the program loaded (its re-read for G38.x and M66, its cycle time), as the loader tells
        self._loaded: ProgramInfo | None = None
        events.program_loaded.connect(self._program_loaded)
        events.program_let_go.connect(self._program_gone)
        events.program_refused.connect(self._program_gone)

    def _program_loaded(self, info: ProgramInfo) -> None:
        self._loaded = info

    def _program_gone(self) -> None:
        self._loaded = None

    def planner(self) -> RunPlanner:
        """Plans bound to the machine and budget of now (for a worker thread)."""
        return RunPlanner.of(self._coordinates.machine(), self._settings.budget)

    def plan(self, program: Program) -> Plan:
        return self.planner()(program)

    def machine(self) -> MachineSpec:
        """The machine the jobs are made for (the work offsets in force)."""
        return self._coordinates.machine()

    def make_job(
        self,
        kind: Activity,
        program: Program,
        name: str,
        *,
        overrides: bool = True,
        single_block: bool = False,
        plan: Plan | PlanWindow | None = None,
        estimate_s: float = math.nan,
        stops: tuple[PausePoint, ...] | None = None,
        terms: JobTerms = NO_TERMS,
        whole_s: float | None = None,
        follows: Job | None = None,
    ) -> Job:
        """A job for ``program``. ``plan``: a ready plan of exactly this program (already the
        single-block variant when ``single_block``) with the current machine and budget, e.g.
        the one made at load time (``ProgramInfo.plan``): then nothing is planned here. A long
        program is planned as it runs (``RunPlanner.for_run``); ``estimate_s``: its planned
        time as far as known (the time left shows it), ``stops``: its pause points as a check
        pass found them (the spin-ups the time left counts). ``terms``: what the job is part of
        and what follows it; ``whole_s``: the time of the whole program it is a piece of (its
        progress and time left count from there; NaN: its own estimate); ``follows``: the job
        it goes on from as the same run (time, samples, trace, limits)."""
        modes, cfg = self._modes, self._settings.config
        if plan is None:
            if single_block:
                program = single_block_program(program)
            plan = self.planner().for_run(program, estimate_s)
        else:
            program = plan.program
        overrides_now = (modes.feed_pct / 100.0 if overrides else 1.0,
                         modes.rapid_pct / 100.0 if overrides else 1.0)
        machine, budget = self._coordinates.machine(), self._settings.budget
        if isinstance(plan, PlanWindow):
            # its pause points come with its segments; the spin-ups from the check pass's
            pauses = list(stops or ())
            ex = TimeScaledExecutor(plan, machine, budget, None, *overrides_now,
                                    pause_feed=PauseFeed(program, single_block, True))
        else:
            pauses = pause_points(plan, single_block, True)
            ex = TimeScaledExecutor(plan, machine, budget, pauses, *overrides_now)
        spin_ups = spin_up_waits(pauses, self._spindle.spindle, cfg.controller.spindle_spinup_s)
        info = self._loaded
        if terms.reread is None and kind is Activity.PROGRAM and info is not None:
            # G38.x, M66: the program is read again with each result
            terms = replace(terms, reread=info.reread)
        estimated_s = ex.planned_end_s + sum(wait for _tau, wait in spin_ups)
        if whole_s is not None:
            whole_s = estimated_s if math.isnan(whole_s) else whole_s
            terms = replace(terms, offset_s=max(whole_s - ex.planned_end_s, 0.0))
        return Job(kind=kind, name=name, program=program, plan=plan, executor=ex, overrides=overrides,
                   estimated_s=estimated_s, machine=machine, single_block=single_block, spin_ups=spin_ups,
                   terms=terms, follows=follows)

    def successor(self, job: Job, rest: Program, origin: tuple[Program, int, float], held: bool = False,
                  reads: Reads | None = None) -> Job:
        """The job that runs ``rest`` (what is left of ``job``'s program from where it stands,
        planned anew) as the same run (time, progress, trace, limits); ``held``: it waits for
        cycle start; ``reads``: the probe and input results so far (else ``job``'s). Raises
        PlannerError when the rest cannot be planned."""
        modes, info = self._modes, self._loaded
        # where the run stands on the whole program's timeline: a long rest is planned as it
        # runs, its end estimated from there
        at_s = job.tau_offset_s + job.executor.tau
        full_t = info.cycle_time_s if info is not None and job.kind is Activity.PROGRAM else math.nan
        probes, waits = reads if reads is not None else (job.probe_results, job.wait_results)
        terms = JobTerms(reason=job.reason, steps=tuple(job.steps.items()), origin=origin, reread=job.reread,
                         when_done=job.when_done, probe_results=probes, wait_results=waits)
        new = self.make_job(job.kind, rest, job.name,
                            single_block=modes.single_block and job.kind is Activity.PROGRAM,
                            estimate_s=max(job.executor.planned_end_s + job.tau_offset_s - at_s, 0.0),
                            terms=terms, whole_s=full_t, follows=job)
        new.executor.hold = held
        return new
