"""What a program reads from the machine: probing (G38.2-G38.5) and digital inputs (M66).

Parts of ``MachineController``: ``controller.prober`` owns the probe move under way,
``controller.waiter`` the M66 wait under way.

What follows such a read depends on its result, so the program was checked with a result
assumed (the probe run to its programmed end point with no contact, #5070 = 0, as
LinuxCNC's preview reads it; the input reading the awaited level), the run stops at rest
there, and once the machine has the result the program is read again from its start with
every result so far (``Job.reread``); the moves after the read are checked against the soft
limits before the motion goes on from where the machine stands (``continue_after``).

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

import math
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from app.machine.model import Activity, MachineState
from app.machine.outputs import analog_refusal
from app.machine.spindle import synchronised_refusal
from planner.errors import PlannerError, ProgramError
from planner.program import EventKind, InputRequest, ProbeRequest, ProbeResult, Program, WaitMode
from planner.resume import carry_overrides, program_from_moves

if TYPE_CHECKING:
    from app.machine.controller import MachineController
    from app.machine.jobs import Job

__all__ = ["InputWaiter", "ProbeRun", "Prober", "continue_after", "probe_refusal"]


def probe_overtravel_mm(feed_mm_min: float, jerk_mm_s3: float, reaction_s: float = 0.015) -> float:
    """How far the stylus travels past the contact at ``feed_mm_min``: the feed for the reaction
    (the feeder sees the latch, the stop is spliced a few cycles ahead of the drives), then the
    jerk-limited stop along the path, v sqrt(v / J)."""
    v = feed_mm_min / 60.0
    return v * (reaction_s + math.sqrt(v / jerk_mm_s3))


def probe_refusal(program: Program, drive: int | None, max_feed_mm_min: float) -> tuple[int, str]:
    """Why a program's probing cannot run on this machine, with the line ((0, "") when it can):
    no probe input, or a probe move faster than the stylus' overtravel allows."""
    for p in program.probes:
        if drive is None:
            return p.line, (f"{p.name} needs a probe input: this machine has none ([probe] drive in the "
                            "machine configuration)")
        if p.move_index < 0:
            continue
        feed = program.moves[p.move_index].feed_mm_s * 60.0
        if feed > max_feed_mm_min * (1.0 + 1e-9):
            return p.line, (f"{p.name} at F{feed:g} mm/min is faster than the probe allows ([probe] "
                            f"max_feed_mm_min = {max_feed_mm_min:g}: the stylus travels on past the "
                            "contact while the motion stops)")
    return 0, ""


@dataclass
class ProbeRun:
    """The probe move under way: its index in the program's probes, and the contact once seen."""

    index: int
    request: ProbeRequest
    trip_position: np.ndarray | None = None   # machine coordinates, latched by the worker


class Prober:
    """G38.x on the machine: arms the input before a probe move, stops the motion at the
    contact, and goes on with the result (the module docstring)."""

    def __init__(self, m: MachineController) -> None:
        self.m = m
        self.run: ProbeRun | None = None
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
        if job.stopping:                     # stopped meanwhile (stop, alarm): nothing goes on
            return
        if run is not None and run.trip_position is not None and job.executor.standing and all_done:
            self.finish(job)

    # ------------------------------------------------------------------ after the move
    def finish(self, job: Job) -> None:
        """At rest after the probe move (stopped at the contact, or at its end point)."""
        run, self.run = self.run, None
        w = self.m.worker
        if w is None:
            return
        if run is None:                      # never armed: its result would be a guess
            self.fail("a probe move ended without the probe armed: the program stops here")
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
        stop_program(self.m, cause, "probe")

    def _go_on(self, job: Job, index: int, result: ProbeResult) -> None:
        results: list[ProbeResult | None] = list(job.probe_results)
        results += [None] * (index + 1 - len(results))
        results[index] = result
        req = job.plan.program.probes[index]
        continue_after(self.m, job, EventKind.PROBE, index, f"{req.name} (line {req.line})",
                       tuple(results), job.wait_results, self.fail)


def stop_program(m: MachineController, cause: str, source: str) -> None:
    """A read that went wrong: a STOP alarm (``source`` names it), and no resume past it (what
    follows was read with a result the machine did not give)."""
    m.alarm_log.alarm_stop(cause, source, source)
    m.run.resume_point = None


def continue_after(m: MachineController, job: Job, kind: EventKind, index: int, where: str,
                   probes: tuple[ProbeResult | None, ...], waits: tuple[float | None, ...],
                   fail: Callable[[str], None]) -> None:
    """At rest after read ``index`` of ``kind`` (PROBE, INPUT): read the program again with the
    results and run what follows it from where the machine stands, or ``fail`` saying why not."""
    if job.reread is None:
        fail(f"{where}: the program cannot be read again with the result")
        return
    try:
        full = job.reread(probes, waits)
    except ProgramError as exc:
        e = exc.errors[0]
        fail(f"{where}: with the result, line {e.line} reads: {e.message}")
        return
    except PlannerError as exc:
        fail(f"{where}: with the result the program reads: {exc}")
        return
    rest = _after_event(full, kind, index)
    if rest is None:
        fail(f"{where}: the program read again does not have it")
        return
    here = np.asarray(m.pos.ref_raw, dtype=float) - m.pos.home_offset
    if rest.moves and float(np.max(np.abs(rest.start_position - here))) > 1e-6:
        fail(f"{where}: the program read again does not go on from where the machine stands")
        return
    issues = m.loader.check_program_limits(rest) if rest.moves else []
    if issues:
        fail(f"{where}: with the result, {issues[0]}")
        return
    for refusal in (synchronised_refusal, analog_refusal):
        at, why = refusal(full)
        if why:                          # a branch the first reading did not take
            fail(f"{where}: with the result, line {at}: {why}")
            return
    if not rest.moves:                   # nothing moves after it: the program ends here
        m.stream.finish_now(job, rest)
        return
    try:
        # after an operator's feed hold, the rest waits for cycle start
        new = m.stream.follow(job, rest, (full, len(full.moves) - len(rest.moves), 0.0),
                              held=m.states.state is MachineState.HOLD)
    except PlannerError as exc:
        fail(f"{where}: planner: {exc}")
        return
    new.probe_results, new.wait_results = probes, waits
    if job.kind is Activity.PROGRAM:
        m.programReadAgain.emit(full)        # the preview draws the path the machine takes

def _after_event(full: Program, kind: EventKind, index: int) -> Program | None:
    """What follows read ``index`` of ``kind`` in ``full``: its later moves, from where the move
    before the event ended, with the events that come after it in the program (a message right
    after it included; those before it were done already)."""
    at = next((k for k, e in enumerate(full.events) if e.kind is kind and int(e.value) == index), -1)
    if at < 0:
        return None
    after = full.events[at].after_move
    first = after + 1
    events = carry_overrides(full, first, [replace(e, after_move=e.after_move - first)
                                           for e in full.events[at + 1:]])
    start = full.moves[after].end if after >= 0 else full.start_position
    return program_from_moves(full, list(full.moves[first:]), events, start)


@dataclass
class _Wait:
    index: int
    request: InputRequest
    drive: int
    bit: int
    since_s: float            # worker time the wait began
    seen: int                 # the level read last (RISE / FALL need the other one first)


class InputWaiter:
    """M66: the wait under way, polled at rest."""

    def __init__(self, m: MachineController) -> None:
        self.m = m
        self.wait: _Wait | None = None

    def fail(self, cause: str) -> None:
        stop_program(self.m, cause, "input")

    def cancel(self) -> None:
        self.wait = None

    def at_pause(self, job: Job, index: int, snap: Any) -> None:
        """At the INPUT pause point (called by every poll while there)."""
        w = self.wait
        if w is None or w.index != index:
            inputs = job.plan.program.inputs
            if not 0 <= index < len(inputs):
                self.fail(f"input {index} is not in the program")
                return
            req = inputs[index]
            bits = self.m.conn.machine.input_bits.get(req.number)
            if bits is None:
                self.fail(f"M66 (line {req.line}): input P{req.number} is not on this machine ([[inputs]])")
                return
            level = self._level(snap, bits[0], bits[1])
            if level is None:
                self.fail(f"M66 (line {req.line}): the drive of input P{req.number} does not send its "
                          "digital inputs (0x60FD)")
                return
            w = self.wait = _Wait(index, req, bits[0], bits[1], float(snap.time_s), level)
            if req.mode is not WaitMode.IMMEDIATE:
                name = self.m.conn.machine.input_bits[req.number][2]
                how = {WaitMode.RISE: "to rise", WaitMode.FALL: "to fall", WaitMode.HIGH: "to read 1",
                       WaitMode.LOW: "to read 0"}[req.mode]
                self.m.stream.show_message(f"M66 (line {req.line}): waiting for input P{req.number}"
                                           + (f" ({name})" if name else "") + f" {how}, "
                                           f"{req.timeout_s:g} s at most")
        level = self._level(snap, w.drive, w.bit)
        value = self._value(w, level, float(snap.time_s))
        if value is None:
            return
        self.wait = None
        job.dwell_total_s += float(snap.time_s) - w.since_s   # the run's time, as a dwell's
        req = w.request
        if value < 0:
            self.m.stream.show_message(f"M66 (line {req.line}): input P{req.number} timed out after "
                                       f"{req.timeout_s:g} s: #5399 = -1")
        results: list[float | None] = list(job.wait_results)
        results += [None] * (index + 1 - len(results))
        results[index] = value
        continue_after(self.m, job, EventKind.INPUT, index, f"M66 (line {req.line})", job.probe_results,
                       tuple(results), self.fail)

    @staticmethod
    def _level(snap: Any, drive: int, bit: int) -> int | None:
        inputs = tuple(getattr(snap, "digital_inputs", ()) or ())
        return int(inputs[drive]) >> bit & 1 if drive < len(inputs) else None

    @staticmethod
    def _value(w: _Wait, level: int | None, now_s: float) -> float | None:
        """The value for #5399 once the wait is over, else None."""
        mode = w.request.mode
        if level is None:
            return None
        if mode is WaitMode.IMMEDIATE:
            return float(level)
        done = ((mode is WaitMode.HIGH and level == 1) or (mode is WaitMode.LOW and level == 0)
                or (mode is WaitMode.RISE and w.seen == 0 and level == 1)
                or (mode is WaitMode.FALL and w.seen == 1 and level == 0))
        w.seen = level
        if done:
            return float(level)
        if now_s - w.since_s >= w.request.timeout_s:
            return -1.0
        return None
