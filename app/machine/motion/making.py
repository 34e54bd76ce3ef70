"""Making jobs: a program (or what is left of one) planned for this machine with the override
budget, its executor at the operator's overrides, and the spindle's spin-ups its time counts."""

from __future__ import annotations

import math

from app.machine.model import Activity
from app.machine.motion.jobs import Job, merge_max
from app.machine.motion.plans import RunPlanner, single_block_program
from app.machine.motion.spinup import spin_up_waits
from app.machine.motion.timescale import PauseFeed, PausePoint, TimeScaledExecutor, pause_points
from app.machine.ports import CoordinatesView, LoaderView, RunModes, Settings, SpindleView
from planner.core.machine import MachineSpec
from planner.core.program import Program
from planner.motion.plan import Plan
from planner.motion.window import PlanWindow

__all__ = ["JobMaker"]


class JobMaker:
    """Jobs for this machine, at the overrides of the moment (``Streamer.jobs``)."""

    def __init__(self, settings: Settings, coordinates: CoordinatesView, spindle: SpindleView) -> None:
        self._settings = settings
        self._coordinates = coordinates
        self._spindle = spindle
        self._modes: RunModes | None = None
        self._loader: LoaderView | None = None

    def wire(self, modes: RunModes, loader: LoaderView) -> None:
        self._modes, self._loader = modes, loader

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
    ) -> Job:
        """A job for ``program``. ``plan``: a ready plan of exactly this program (already the
        single-block variant when ``single_block``) with the current machine and budget, e.g.
        the one made at load time (``ProgramInfo.plan``): then nothing is planned here. A long
        program is planned as it runs (``RunPlanner.for_run``); ``estimate_s``: its planned
        time as far as known (the time left shows it), ``stops``: its pause points as a check
        pass found them (the spin-ups the time left counts)."""
        modes, cfg = self._modes, self._settings.config
        assert modes is not None
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
        job = Job(kind=kind, name=name, program=program, plan=plan, executor=ex, overrides=overrides,
                  estimated_s=ex.planned_end_s + sum(wait for _tau, wait in spin_ups), machine=machine)
        job.single_block = single_block
        job.spin_ups = spin_ups
        info = self._loader.program_info if self._loader is not None else None
        if kind is Activity.PROGRAM and info is not None:
            job.reread = info.reread        # G38.x, M66: the program is read again with each result
        return job

    def successor(self, job: Job, rest: Program, origin: tuple[Program, int, float],
                  held: bool = False) -> Job:
        """The job that runs ``rest`` (what is left of ``job``'s program from where it stands,
        planned anew) as the same run (time, progress, trace, limits); ``held``: it waits for
        cycle start. Raises PlannerError when the rest cannot be planned."""
        modes = self._modes
        assert modes is not None
        info = self._loader.program_info if self._loader is not None else None
        # where the run stands on the whole program's timeline: a long rest is planned as it
        # runs, its end estimated from there
        at_s = job.tau_offset_s + job.executor.tau
        full_t = info.cycle_time_s if info is not None and job.kind is Activity.PROGRAM else math.nan
        new = self.make_job(job.kind, rest, job.name,
                            single_block=modes.single_block and job.kind is Activity.PROGRAM,
                            estimate_s=max(job.executor.planned_end_s + job.tau_offset_s - at_s, 0.0))
        if math.isnan(full_t):
            full_t = new.estimated_s
        new.tau_offset_s = new.time_offset_s = max(full_t - new.executor.planned_end_s, 0.0)
        new.origin = origin
        new.start_time_s = job.start_time_s
        new.trace = job.trace
        new.samples, new.dwell_total_s = job.samples, job.dwell_total_s
        new.carried_limits = merge_max(job.carried_limits, job.meter.final())
        new.estimated_s = job.estimated_s
        new.serial_base = job.serial_base
        new.reread, new.probe_results, new.wait_results = job.reread, job.probe_results, job.wait_results
        new.when_done = job.when_done
        new.executor.hold = held
        return new

