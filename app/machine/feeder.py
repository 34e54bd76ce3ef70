"""Running a motion: jobs planned with the override budget, set-points streamed to the worker
``lead_s`` ahead (the feeder), pause points, program end, run summaries and the saved trace.

Serial numbers: every set-point pushed gets the next serial; the worker's ``samples_consumed``
says which one the drives reached (line, progress, resume point). Part of
``MachineController`` (mixed in).
"""

from __future__ import annotations

import os
from dataclasses import replace
from typing import Any

import numpy as np

from app.machine.errors import MachineError
from app.machine.jobs import Job, merge_max
from app.machine.model import Activity, MachineState, RunSummary, Severity, SpindleState, TrackingReport
from app.machine.timescale import PausePoint, TimeScaledExecutor, pause_points, reduced_machine
from planner.plan import Plan, plan_program
from planner.program import Program

__all__ = ["FeederMixin"]


class FeederMixin:
    """Jobs, set-point streaming, pause points, end of a run.

    Mixed into ``MachineController``, which holds the state.
    """

    @property
    def _lead_samples(self) -> int:
        ts = self._cfg.machine.planner.ts_s
        return max(int(self._cfg.controller.lead_s / ts), 10)

    def _plan(self, program: Program) -> Plan:
        return plan_program(program, reduced_machine(self._machine, self._budget))

    def _make_job(
        self,
        kind: Activity,
        program: Program,
        name: str,
        *,
        overrides: bool = True,
        single_block: bool = False,
    ) -> Job:
        if single_block:
            program = replace(program, moves=tuple(replace(m, exact_stop=True) for m in program.moves))
        plan = self._plan(program)
        pauses = pause_points(plan, single_block, True)
        ex = TimeScaledExecutor(
            plan,
            self._machine,
            self._budget,
            pauses,
            feed_override=self._feed_pct / 100.0 if overrides else 1.0,
            rapid_override=self._rapid_pct / 100.0 if overrides else 1.0,
        )
        job = Job(
            kind=kind,
            name=name,
            program=program,
            plan=plan,
            executor=ex,
            overrides=overrides,
            estimated_s=plan.cycle_time_s,
            machine=self._machine,
        )
        job.single_block = single_block
        return job

    def _start_job(self, job: Job) -> None:
        snap = self._snapshot_now()
        job.start_time_s = float(snap.time_s) if job.start_time_s < 0 else job.start_time_s
        if job.kind is Activity.PROGRAM and self._worker is not None:
            with self._lock:
                self._worker.reset_tracking()
                self._worker.drain_trace()
        with self._lock:
            # serial numbers of set-points: the worker's consumed count (+ what is still queued;
            # a stale snapshot still counts the queue, a flushed buffer counts nothing)
            self._pushed_total = int(snap.samples_consumed) + int(snap.buffer_level)
            job.serial_base = self._pushed_total
            self._job = job
        self._set_activity(job.kind)
        if self._state is not MachineState.RUNNING:
            self._set_state(MachineState.RUNNING, job.kind.value)
        else:
            self.stateChanged.emit(self._state, job.kind.value)
        if self._worker_mode != "manual":
            self._feed()

    def _feed(self) -> None:
        from ethercat.worker import WorkerState

        with self._lock:
            job, w = self._job, self._worker
            if job is None or w is None or job.aborted:
                return
            if w.state() is not WorkerState.ENABLED:
                return
            want = self._lead_samples - w.buffer_level()
            while want > 0 and job.pause is None:
                if job.executor.hold and job.executor.standing:
                    break  # held still on the path: the worker keeps the last set-point
                ch = job.executor.generate(min(want, 20))
                if ch is None:
                    break
                raw = ch.q + self._home_offset
                n = w.push(raw)
                if n < len(raw):  # pragma: no cover - lead is far below the ring capacity
                    raise MachineError("worker buffer full")
                job.record(ch, self._pushed_total)
                job.samples += n
                self._pushed_total += n
                want -= n
                if ch.pause is not None:
                    # the plan stands still here: repeat the point so the worker sees the
                    # motion end before its buffer runs empty (no underrun alarm)
                    hold = np.repeat(raw[-1:], 2, axis=0)
                    self._pushed_total += w.push(hold)
                    job.pause_serial = self._pushed_total  # before .pause: the poll reads both
                    job.pause = ch.pause

    def _consumed(self) -> int:
        snap = self._last_snap
        return int(snap.samples_consumed) if snap is not None else 0

    def _poll_job(self, job: Job, snap: Any) -> None:
        consumed = int(snap.samples_consumed)
        info = job.info_at(consumed)
        if info is not None:
            line, tau = info
            if line != self._line and job.kind in (Activity.PROGRAM, Activity.MDI):
                self._line = line
                self.lineChanged.emit(line)
            if job.kind is Activity.PROGRAM:
                t_end = job.executor.t_end + job.time_offset_s
                tau_g = tau + job.tau_offset_s
                frac = min(tau_g / t_end, 1.0) if t_end > 0 else 1.0
                ovr = max(self._feed_pct / 100.0, 1e-3)
                remaining = max(t_end - tau_g, 0.0) / ovr
                self._progress = (frac, remaining)
                self.progressChanged.emit(frac, remaining)
        if snap.time_s - self._tracking_emit_t >= 1.0 and job.kind is Activity.PROGRAM:
            self._tracking_emit_t = snap.time_s
            self._tracking = self._tracking_from(snap, "")
            self.trackingUpdated.emit(self._tracking)
        all_done = consumed >= self._pushed_total
        # pause points reached by the drives
        if job.pause is not None and consumed >= job.pause_serial:
            self._at_pause(job, job.pause, snap)
            return
        if job.stopping and job.executor.standing and all_done:
            self._finish_stop(job)

    def _at_pause(self, job: Job, p: PausePoint, snap: Any) -> None:
        kind = p.kind
        if kind == "end":
            self._finish_job(job, snap)
            return
        if job.stopping:
            self._finish_stop(job)
            return
        if kind == "spindle":
            self._apply_spindle(SpindleState(direction=int(np.sign(p.value)), rpm=abs(p.value)))
            self._release(job)
        elif kind == "dwell":
            if job.dwell_until is None:
                job.dwell_until = snap.time_s + p.value
                job.dwell_total_s += p.value
            elif snap.time_s >= job.dwell_until:
                job.dwell_until = None
                self._release(job)
        elif kind == "optional_pause" and not self._optional_stop:
            self._release(job)
        elif not job.waiting:
            job.waiting = True
            reason = {
                "pause": f"program paused (M00, line {p.line}): press cycle start",
                "optional_pause": f"optional stop (M01, line {p.line}): press cycle start",
                "tool_change": f"tool change (M06 T{int(p.value)}, line {p.line}): press cycle start",
                "single_block": f"single block: end of line {p.line}",
            }.get(kind, kind)
            self._set_state(MachineState.HOLD, reason)

    def _finish_stop(self, job: Job) -> None:
        resume = self._resume
        self._drop_job(completed=False, reason=job.stop_reason or "stopped")
        if self._state is MachineState.ALARM:
            self._resume = resume  # a STOP alarm keeps the point to resume from
            return
        self._set_state(MachineState.IDLE, job.stop_reason or "stopped")

    def _release(self, job: Job) -> None:
        with self._lock:
            job.pause = None
            job.waiting = False
            job.executor.release_pause()

    def _finish_job(self, job: Job, snap: Any) -> None:
        nxt = job.then
        completed_summary = self._drop_job(completed=True, reason="completed", snap=snap)
        if nxt is not None:
            if nxt.spindle_before is not None:
                self._apply_spindle(nxt.spindle_before)
            self._start_job(nxt)
            return
        self._set_state(MachineState.IDLE, "program end" if completed_summary else "done")

    def _drop_job(self, completed: bool, reason: str, snap: Any = None) -> RunSummary | None:
        """End the current job (under the lock). Emits programFinished for program jobs."""
        with self._lock:
            job, self._job = self._job, None
            if job is None:
                return None
            job.aborted = True
            if self._worker is not None and not completed:
                try:
                    self._worker.flush()
                except Exception:  # noqa: BLE001
                    pass
        if job.kind is not Activity.PROGRAM:
            return None
        last_line = self._line
        if completed and job.then is None:
            self._resume = None
            self._line = 0
        if snap is None:
            snap = self._last_snap
        # motion time: set-points sent (holds included) plus dwells; waits for the operator excluded
        measured = job.samples * job.plan.ts_s + job.dwell_total_s
        trace_path = self._save_trace(job)
        tracking = self._tracking_from(snap, trace_path) if snap is not None else TrackingReport()
        self._tracking = tracking
        summary = RunSummary(
            name=job.name,
            completed=completed,
            cycle_time_s=measured,
            estimated_s=job.estimated_s,
            last_line=last_line,
            tracking=tracking,
            limits=merge_max(job.carried_limits, job.meter.final()),
            reason=reason,
        )
        self._last_summary = summary
        self.trackingUpdated.emit(tracking)
        if completed:
            self.progressChanged.emit(1.0, 0.0)
        self.programFinished.emit(summary)
        return summary

    def _tracking_from(self, snap: Any, trace_path: str) -> TrackingReport:
        t = snap.tracking
        return TrackingReport(
            axes=self._cfg.axes,
            samples=int(t.samples),
            rmse=tuple(t.rmse),
            mse=tuple(t.mse),
            max_abs=tuple(t.max_abs),
            trace_path=trace_path or self._tracking.trace_path,
        )

    def _save_trace(self, job: Job) -> str:
        if not job.trace:
            return ""
        cyc = np.concatenate([c for c, _, _ in job.trace])
        ref = np.concatenate([r for _, r, _ in job.trace]) - self._home_offset
        act = np.concatenate([a for _, _, a in job.trace]) - self._home_offset
        path = self._store.path("last_run.npz")
        tmp = path.with_name(".last_run.tmp.npz")
        e = ref - act
        mse = (e * e).mean(axis=0) if len(e) else np.zeros(len(self._cfg.axes))
        try:
            np.savez_compressed(
                tmp,
                t=cyc * self._cfg.machine.planner.ts_s,
                reference=ref,
                actual=act,
                axes=np.array(self._cfg.axes),
                rmse=np.sqrt(mse),
                mse=mse,
            )
            os.replace(tmp, path)
        except OSError as exc:
            self._raise_alarm("persistence", f"cannot save the run trace: {exc}", Severity.WARNING, "trace")
            return ""
        return str(path)
