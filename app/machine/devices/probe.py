"""What a program reads from the machine: probing (G38.2-G38.5) and digital inputs (M66).

``Prober`` (``controller.prober``) owns the probe move under way; ``InputWaiter``
(``app.machine.devices.inputs``) the M66 wait under way.

What follows such a read depends on its result, so the program was checked with a result
assumed (the probe run to its programmed end point with no contact, #5070 = 0, as
LinuxCNC's preview reads it; the input reading the awaited level), the run stops at rest
there, and once the machine has the result the program is read again from its start with
every result so far (``Job.reread``); the moves after the read are checked against the soft
limits before the motion goes on from where the machine stands (``ReadAgain``).

Probing: the run stops at rest before each probe move (the pause point PROBE_START: the input
is armed in the worker, refused when it reads the trip level already) and after it (PROBE).
The worker latches the actual positions in the cycle the input changes; the feeder thread
(every 2 ms) sees the latch and replaces the queued set-points by the jerk-limited path stop a
few cycles ahead of the drives (``Streamer.hold_motion``). At rest the probe move ends where
the machine stands and #5061-#5070 hold the contact. A G38.2/G38.4 move that ends without the
change is an alarm (the program stops there), as in LinuxCNC.

M66: at rest (pause point INPUT) the input is read at once (L0) or waited for (rise, fall,
high, low) at the poll's rate, for at most Q seconds; #5399 holds the value, -1 after the
timeout, as in LinuxCNC.
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from app.machine.devices.reads import ReadAgain
from app.machine.infra.drives import DriveLink
from app.machine.motion.jobs import Job
from app.machine.motion.pauses import PauseHandlers
from app.machine.motion.streamer import Streamer
from app.machine.motion.timescale import PauseKind, PausePoint
from app.machine.ports import PositionsView, Settings, ToolsView
from ethercat.sim_part import SimPart
from ethercat.worker import WorkerSnapshot
from planner.core.program import EventKind, ProbeRequest, ProbeResult, TableRef

__all__ = ["ProbeRun", "Prober"]


@dataclass
class ProbeRun:
    """The probe move under way: its index in the program's probes, and the contact once seen."""

    index: int
    request: ProbeRequest
    trip_position: np.ndarray | None = None   # machine coordinates, latched by the worker


class Prober:
    """G38.x on the machine: arms the input before a probe move, stops the motion at the
    contact, and goes on with the result (the module docstring)."""

    def __init__(self, settings: Settings, drives: DriveLink, positions: PositionsView, motion: Streamer,
                 reads: ReadAgain, pauses: PauseHandlers, tools: ToolsView) -> None:
        self._settings = settings
        self._tools = tools
        self._drives = drives
        self._positions = positions
        self._motion = motion
        self._reads = reads
        self.run: ProbeRun | None = None
        # the worker and home offsets the simulated surface was placed for
        self._surface_at: tuple[object, tuple[float, ...]] | None = None
        # the simulated workpiece (machine coordinates), and what it was placed for
        self._part: SimPart | None = None
        self._part_at: tuple[object, ...] | None = None
        motion.on_feed(self.watch)
        motion.on_poll(self.poll)
        motion.on_job_end(self.cancel)
        pauses.on(PauseKind.PROBE_START, self._at_start)
        pauses.on(PauseKind.PROBE, self._at_end)

    # ------------------------------------------------------------------ before the move
    def _at_start(self, job: Job, point: PausePoint, _snap: WorkerSnapshot) -> bool:
        why = self.arm(job, point.payload_as(TableRef).index)
        if why:
            self.fail(why)
            return False
        return True

    def arm(self, job: Job, index: int) -> str:
        """At rest before probe ``index`` of the job's program: watch the input. Returns why
        it cannot ("" when armed)."""
        probes = job.plan.program.probes
        if not 0 <= index < len(probes):
            return f"probe {index} is not in the program"
        req = probes[index]
        where = _where(job, req.name, req.line)
        cfg = self._settings.config.probe
        if cfg.drive is None or not self._drives.attached:
            return f"{where}: this machine has no probe input ([probe] drive in the machine configuration)"
        touching = bool(cfg.touching_level)
        level = touching if req.toward else not touching
        if not self._drives.arm_probe(cfg.drive, cfg.bit, level):
            snap = self._drives.snapshot()
            if snap is None or not snap.digital_inputs:
                return f"{where}: the probe's drive does not send its digital inputs (0x60FD)"
            return (f"{where}: the probe already " + ("touches" if req.toward else "does not touch")
                    + " where the move starts")
        self.run = ProbeRun(index, req)
        return ""

    def place_simulated_surface(self, _snap: WorkerSnapshot) -> None:
        """Simulated drives: the surface the stylus touches, in the drive units of now (machine
        coordinates plus the home offset), placed again when the home offsets change (called
        by the poll)."""
        cfg = self._settings.config
        probe = cfg.probe
        w = self._drives.worker
        if cfg.bus.kind != "sim" or probe.sim_surface_mm is None or probe.drive is None or w is None:
            return
        offsets = tuple(float(v) for v in self._positions.home_offset)
        if self._surface_at is not None and self._surface_at[0] is w and self._surface_at[1] == offsets:
            return
        from ethercat.sim_bus import probe_surface_value

        i = cfg.axes.index(probe.sim_axis)
        self._drives.inject("probe_surface", i, probe_surface_value(probe.bit,
                                                                    probe.sim_surface_mm + offsets[i],
                                                                     True, probe.drive))
        self._surface_at = (w, offsets)

    def simulate_part(self, part: SimPart | None) -> bool:
        """Simulated drives: a workpiece the stylus touches (``ethercat.sim_part``, machine
        coordinates), besides the surface; the ball's radius and length come from the tool in
        the spindle as the table gives them. Placed at the next poll and again when the home
        offsets or the tool change; None takes it away. False on a real bus."""
        cfg = self._settings.config
        if cfg.bus.kind != "sim" or cfg.probe.drive is None or not {"X", "Y", "Z"} <= set(cfg.axes):
            return False
        self._part, self._part_at = part, None
        return True

    def place_simulated_part(self, _snap: WorkerSnapshot) -> None:
        """From the poll: the simulated workpiece in the drives' units of now."""
        cfg = self._settings.config
        w = self._drives.worker
        if cfg.bus.kind != "sim" or cfg.probe.drive is None or w is None:
            return
        tool = self._tools.table.get(self._tools.in_spindle)
        length = tool.length_mm if tool is not None else 0.0
        radius = tool.diameter_mm / 2.0 if tool is not None else 0.0
        offsets = tuple(float(v) for v in self._positions.home_offset)
        key = (w, offsets, length, radius, self._part)
        if self._part_at == key:
            return
        self._part_at = key
        if self._part is None:
            self._drives.inject("probe_part_off", 0, 0)
            return
        from ethercat.sim_bus import probe_part_values

        axes = cfg.axes
        ix, iy, iz = (axes.index(a) for a in "XYZ")
        part = replace(self._part, tip_length_mm=length, tip_radius_mm=radius).shifted(
            offsets[ix], offsets[iy], offsets[iz])
        for name, index, value in probe_part_values(part, (ix, iy, iz), cfg.probe.bit, cfg.probe.drive):
            self._drives.inject(name, index, value)

    # ------------------------------------------------------------------ during the move
    def watch(self) -> None:
        """From the feeder (under the motion's lock): the latch seen, the motion stops along
        the path."""
        run = self.run
        if run is None or run.trip_position is not None:
            return
        latched = self._drives.probe_latched()
        if latched is None:
            return
        run.trip_position = np.asarray(latched, dtype=float) - self._positions.home_offset
        self._motion.hold_motion()

    def poll(self, job: Job, all_done: bool) -> None:
        """From the poll: stopped after the contact, the result is taken."""
        run = self.run
        if job.stopping:                     # stopped meanwhile (stop, alarm): nothing goes on
            return
        if run is not None and run.trip_position is not None and job.executor.standing and all_done:
            self.finish(job)

    # ------------------------------------------------------------------ after the move
    def _at_end(self, job: Job, _point: PausePoint, _snap: WorkerSnapshot) -> bool:
        self.finish(job)
        return False

    def finish(self, job: Job) -> None:
        """At rest after the probe move (stopped at the contact, or at its end point)."""
        run, self.run = self.run, None
        if not self._drives.attached:
            return
        if run is None:                      # never armed: its result would be a guess
            self.fail("a probe move ended without the probe armed: the program stops here")
            return
        latched = self._drives.probe_latched()
        self._drives.disarm_probe()
        snap = self._drives.snapshot()
        if snap is None:
            return
        home = self._positions.home_offset
        if run.trip_position is None and latched is not None:        # changed in the last cycles
            run.trip_position = np.asarray(latched, dtype=float) - home
        req = run.request
        where = _where(job, req.name, req.line)
        stop = np.asarray(snap.reference_position, dtype=float) - home
        tripped = run.trip_position is not None
        if not tripped and req.error_without_trip:
            self.fail(f"{where}: the probe move ended without " + ("contact" if req.toward
                                                                   else "the contact being lost"))
            return
        trip = run.trip_position if run.trip_position is not None else stop
        result = ProbeResult(tripped, tuple(float(v) for v in trip), tuple(float(v) for v in stop))
        axes = self._settings.config.axes
        self._motion.show_message(
            f"{where}: " + (("contact at " if req.toward else "contact lost at ")
                            + " ".join(f"{a}{v:.4f}" for a, v in zip(axes, trip)) + " (machine)"
                            if tripped else "no contact"))
        results: list[ProbeResult | None] = list(job.probe_results)
        results += [None] * (run.index + 1 - len(results))
        results[run.index] = result
        self._reads.continue_after(job, EventKind.PROBE, run.index, where, tuple(results), job.wait_results,
                                   "probe")

    def cancel(self) -> None:
        """The job ends (stop, reset, alarm, E-stop): from then on nothing watches the input."""
        if self.run is None:
            return
        self.run = None
        self._drives.disarm_probe()

    def fail(self, cause: str) -> None:
        self._reads.stop(cause, "probe")


def _where(job: Job, code: str, line: int) -> str:
    """The probe move as the operator knows it: its line in a program; in a routine the
    controller wrote, what that step does (the tool setter's), else what the routine does
    (a probing wizard: its lines are in subroutines the operator never saw)."""
    step = job.steps.get(line) or job.reason
    return f"{code} ({step})" if step else f"{code} (line {line})"
