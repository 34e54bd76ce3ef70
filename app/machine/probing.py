"""G38.2-G38.5 on the machine: the probe armed at rest before its move, the motion stopped
along the path when the input changes, and the rest of the program read again with what the
machine measured.

A part of ``MachineController`` (``controller.prober``): it owns the probe move under way.

The program was checked with every probe touching at its programmed end point (what follows a
probe depends on where it touches). The run stops at rest before each probe move (the pause
point PROBE_START: the input is armed in the worker, refused when it reads the trip level
already) and after it (PROBE). The worker latches the actual positions in the cycle the input
changes; the feeder thread (every 2 ms) sees the latch and replaces the queued set-points by
the jerk-limited path stop a few cycles ahead of the drives (``Streamer.hold_motion``). At
rest, the program is read again from its start with the results so far (``Job.reread``): the
probe move now ends where the machine stands, #5061-#5070 hold the contact, and the moves after
it are checked against the soft limits before the motion goes on from there. A G38.2/G38.4 move
that ends without the change is an alarm (the program stops there), as in LinuxCNC.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np

from planner.errors import PlannerError, ProgramError
from planner.program import EventKind, ProbeRequest, ProbeResult, Program
from planner.resume import program_from_moves

if TYPE_CHECKING:
    from app.machine.controller import MachineController
    from app.machine.jobs import Job

__all__ = ["ProbeRun", "Prober"]


@dataclass
class ProbeRun:
    """The probe move under way: its index in the program's probes, and the contact once seen."""

    index: int
    request: ProbeRequest
    trip_position: np.ndarray | None = None   # machine coordinates, latched by the worker


class Prober:
    def __init__(self, m: MachineController) -> None:
        self.m = m
        self.run: ProbeRun | None = None
        self.last_result: ProbeResult | None = None
        # the worker and home offsets the simulated surface was placed for
        self._surface_at: tuple[object, tuple[float, ...]] | None = None

    # ------------------------------------------------------------------ before the move
    def arm(self, job: Job, index: int) -> str:
        """At rest before probe ``index`` of the job's program: watch the input. Returns why
        it cannot ("" when armed)."""
        probes = job.plan.program.probes
        if not 0 <= index < len(probes):
            return f"probe {index} is not in the program"
        req = probes[index]
        where = f"{req.name} (line {req.line})"
        cfg = self.m.config.probe
        w = self.m.worker
        if cfg.drive is None or w is None:
            return f"{where}: this machine has no probe input ([probe] drive in the machine configuration)"
        touching = bool(cfg.touching_level)
        level = touching if req.toward else not touching
        with self.m._lock:
            armed = w.arm_probe(cfg.drive, cfg.bit, level)
        if not armed:
            if not w.snapshot().digital_inputs:
                return f"{where}: the probe's drive does not send its digital inputs (0x60FD)"
            return (f"{where}: the probe already " + ("touches" if req.toward else "does not touch")
                    + " where the move starts")
        self.run = ProbeRun(index, req)
        return ""

    def place_simulated_surface(self) -> None:
        """Simulated drives: the surface the stylus touches, in the drive units of now (machine
        coordinates plus the home offset), placed again when the home offsets change (called
        by the poll)."""
        cfg = self.m.config.probe
        w = self.m.worker
        if (self.m.config.bus.kind != "sim" or cfg.sim_surface_mm is None or cfg.drive is None
                or w is None or not hasattr(w, "inject")):
            return
        offsets = tuple(float(v) for v in self.m.pos.home_offset)
        if self._surface_at is not None and self._surface_at[0] is w and self._surface_at[1] == offsets:
            return
        from ethercat.sim_bus import probe_surface_value

        i = self.m.config.axes.index(cfg.sim_axis)
        with self.m._lock:
            w.inject("probe_surface", i, probe_surface_value(cfg.bit, cfg.sim_surface_mm + offsets[i], True,
                                                             cfg.drive))
        self._surface_at = (w, offsets)

    # ------------------------------------------------------------------ during the move
    def watch(self) -> None:
        """From the feeder (under the lock): the latch seen, the motion stops along the path."""
        run, w = self.run, self.m.worker
        if run is None or run.trip_position is not None or w is None:
            return
        latched = w.probe_latched()
        if latched is None:
            return
        run.trip_position = np.asarray(latched, dtype=float) - self.m.pos.home_offset
        self.m.stream.hold_motion()

    def poll(self, job: Job, all_done: bool) -> None:
        """From the poll: stopped after the contact, the result is taken."""
        run = self.run
        if run is not None and run.trip_position is not None and job.executor.standing and all_done:
            self.finish(job)

    # ------------------------------------------------------------------ after the move
    def finish(self, job: Job) -> None:
        """At rest after the probe move (stopped at the contact, or at its end point)."""
        run, self.run = self.run, None
        w = self.m.worker
        if run is None or w is None:
            return
        with self.m._lock:
            latched = w.probe_latched()
            w.disarm_probe()
            snap = w.snapshot()
        if run.trip_position is None and latched is not None:        # changed in the last cycles
            run.trip_position = np.asarray(latched, dtype=float) - self.m.pos.home_offset
        req = run.request
        where = f"{req.name} (line {req.line})"
        stop = np.asarray(snap.reference_position, dtype=float) - self.m.pos.home_offset
        tripped = run.trip_position is not None
        if not tripped and req.error_without_trip:
            self.fail(f"{where}: the probe move ended without " + ("contact" if req.toward
                                                                   else "the contact being lost"))
            return
        trip = run.trip_position if run.trip_position is not None else stop
        result = ProbeResult(tripped, tuple(float(v) for v in trip), tuple(float(v) for v in stop))
        self.last_result = result
        axes = self.m.config.axes
        self.m.stream.show_message(
            f"{where}: " + (("contact at " if req.toward else "contact lost at ")
                            + " ".join(f"{a}{v:.4f}" for a, v in zip(axes, trip)) + " (machine)"
                            if tripped else "no contact"))
        self._go_on(job, run.index, result)

    def cancel(self) -> None:
        """The job ends (stop, reset, alarm, E-stop): the input is no longer watched."""
        if self.run is None:
            return
        self.run = None
        w = self.m.worker
        if w is not None:
            try:
                w.disarm_probe()
            except Exception:  # noqa: BLE001 - a worker already gone watches nothing
                pass

    def fail(self, cause: str) -> None:
        self.m.alarm_log.alarm_stop(cause, "probe", "probe")
        self.m.run.resume_point = None       # what follows a failed probe must not be run

    def _go_on(self, job: Job, index: int, result: ProbeResult) -> None:
        """Read the program again with the result and run the rest from where the machine stands."""
        results: list[ProbeResult | None] = list(job.probe_results)
        results += [None] * (index + 1 - len(results))
        results[index] = result
        where = f"{job.plan.program.probes[index].name} (line {job.plan.program.probes[index].line})"
        if job.reread is None:
            self.fail(f"{where}: the program cannot be read again after the probe")
            return
        try:
            full = job.reread(tuple(results))
        except ProgramError as exc:
            e = exc.errors[0]
            self.fail(f"{where}: with the probe's result, line {e.line} reads: {e.message}")
            return
        except PlannerError as exc:
            self.fail(f"{where}: with the probe's result the program reads: {exc}")
            return
        rest = _after_probe(full, index)
        if rest is None:
            self.fail(f"{where}: the program read again has no such probe")
            return
        gap = np.abs(rest.start_position - np.asarray(result.stop_position))
        if rest.moves and float(np.max(gap)) > 1e-6:
            self.fail(f"{where}: the program read again does not go on from where the machine stands")
            return
        issues = self.m.loader.check_program_limits(rest) if rest.moves else []
        if issues:
            self.fail(f"{where}: with the probe's result, {issues[0]}")
            return
        if not rest.moves:                   # the probe was the last move: the program ends here
            self.m.stream.finish_now(job, rest)
            return
        try:
            new = self.m.stream.follow(job, rest, (full, len(full.moves) - len(rest.moves), 0.0))
        except PlannerError as exc:
            self.fail(f"{where}: planner: {exc}")
            return
        new.probe_results = tuple(results)


def _after_probe(full: Program, index: int) -> Program | None:
    """What follows probe ``index`` of ``full``: its later moves, starting where the probe move
    ended, with the events that come after its result in the program (a message right after
    the probe included; those before it were done before the probe)."""
    at = next((k for k, e in enumerate(full.events)
               if e.kind is EventKind.PROBE and int(e.value) == index), -1)
    if at < 0:
        return None
    after = full.events[at].after_move
    first = after + 1
    events = [replace(e, after_move=e.after_move - first) for e in full.events[at + 1:]]
    start = full.moves[after].end if after >= 0 else full.start_position
    return program_from_moves(full, list(full.moves[first:]), events, start)
