"""Manual motion: continuous and incremental jog, MDI. Every motion is planned and checked like a
program (soft limits on the whole path); a continuous jog is planned to the soft limit, so a
lost release stops there. Part of ``MachineController`` (mixed in).
"""

from __future__ import annotations

import numpy as np

from app.machine.errors import MachineError
from app.machine.model import Activity, CommandResult, SpindleState
from planner.errors import PlannerError, ProgramError
from planner.interpreter import parse_program
from planner.program import EventKind, Move, MoveKind, Program

__all__ = ["JOG_INCREMENTS", "ManualMixin"]

JOG_INCREMENTS: tuple[float, ...] = (0.001, 0.01, 0.1, 1.0)  # mm or degrees


class ManualMixin:
    """Jog and MDI.

    Mixed into ``MachineController``, which holds the state.
    """

    def _single_axis_program(self, i: int, target: float, feed_mm_s: float, name: str) -> Program:
        cur = self._machine_pos()
        end = cur.copy()
        end[i] = target
        rotary = self._cfg.machine.rotary
        length = abs(target - cur[i])
        move = Move(
            index=0,
            line=0,
            kind=MoveKind.LINE,
            start=cur.copy(),
            end=end,
            feed_mm_s=feed_mm_s,
            length_mm=length,
            arc=None,
            exact_stop=True,
        )
        return Program(
            name=name,
            axes=self._cfg.axes,
            rotary=rotary,
            moves=(move,),
            events=(),
            start_position=cur.copy(),
            line_count=0,
        )

    def jog_start(self, axis: str | int, direction: int, speed_fraction: float = 1.0) -> CommandResult:
        """Continuous jog of one axis toward + (1) or - (-1) at ``speed_fraction`` of the jog
        speed. The motion is planned to end at the soft limit, so a lost release stops exactly
        there; ``jog_stop`` is a jerk-limited stop.
        """
        try:
            i = self._axis(axis)
        except MachineError as exc:
            return self._refuse("jog", str(exc))
        why = self.refusal("jog")
        if why:
            return self._refuse("jog", why)
        if direction not in (1, -1):
            return self._refuse("jog", f"direction must be +1 or -1, got {direction}")
        ax = self._cfg.machine.axes[i]
        cur = float(self._machine_pos()[i])
        limit = ax.max_pos if direction > 0 else ax.min_pos
        if (limit - cur) * direction <= 1e-9:
            return self._refuse("jog", f"axis {ax.name} is at its soft limit {limit:g}")
        frac = min(max(float(speed_fraction), 0.01), 1.0)
        feed = min(self._cfg.controller.jog_speed_mm_s * frac, ax.v_max)
        prog = self._single_axis_program(i, limit, feed, f"jog {ax.name}{'+' if direction > 0 else '-'}")
        job = self._make_job(Activity.JOG, prog, prog.name, overrides=False)
        self._start_job(job)
        return self._ok("jog")

    def jog_stop(self, axis: str | int | None = None) -> CommandResult:
        """Release: jerk-limited stop of the jog (harmless when nothing jogs)."""
        with self._lock:
            job = self._job
            if job is None or job.kind is not Activity.JOG:
                return self._ok("jog_stop")
            self._hold_motion()
            job.stopping = True
            job.stop_reason = "jog released"
        return self._ok("jog_stop")

    def jog_increment(self, axis: str | int, step: float, direction: int = 1) -> CommandResult:
        """Move one axis by ``direction * step`` (0.001 / 0.01 / 0.1 / 1 mm or degrees), refused
        when the target is beyond the soft limit.
        """
        try:
            i = self._axis(axis)
        except MachineError as exc:
            return self._refuse("jog", str(exc))
        why = self.refusal("jog")
        if why:
            return self._refuse("jog", why)
        step = abs(float(step))
        if not any(abs(step - s) < 1e-12 for s in JOG_INCREMENTS):
            return self._refuse("jog", f"increment must be one of {JOG_INCREMENTS}, got {step:g}")
        ax = self._cfg.machine.axes[i]
        target = float(self._machine_pos()[i]) + (1 if direction > 0 else -1) * step
        if not ax.min_pos - 1e-9 <= target <= ax.max_pos + 1e-9:
            return self._refuse(
                "jog",
                f"axis {ax.name} would reach {target:.4f}, beyond its soft limit "
                f"[{ax.min_pos:g}, {ax.max_pos:g}]",
            )
        prog = self._single_axis_program(
            i, target, min(self._cfg.controller.jog_speed_mm_s, ax.v_max), f"jog {ax.name} {step:g}"
        )
        job = self._make_job(Activity.JOG, prog, prog.name, overrides=False)
        self._start_job(job)
        return self._ok("jog")

    def mdi(self, block: str) -> CommandResult:
        """Execute one G-code block with the active work offset and the same checks as a program
        (parse, soft limits on the whole path, homed rule).
        """
        why = self.refusal("mdi")
        if why:
            return self._refuse("mdi", why)
        text = block.strip()
        if not text:
            return self._refuse("mdi", "empty block")
        if "\n" in text:
            return self._refuse("mdi", "MDI takes one block (one line)")
        if self._active_offset != "G54":
            text = f"{self._active_offset} {text}"
        try:
            prog = parse_program(text, "MDI", machine=self._machine, start_position=self._machine_pos())
        except ProgramError as exc:
            return self._refuse("mdi", "; ".join(e.message for e in exc.errors))
        except PlannerError as exc:
            return self._refuse("mdi", str(exc))
        issues = self._check_program_limits(prog)
        if issues:
            return self._refuse("mdi", f"soft limit: {issues[0].message}")
        if not prog.moves:
            for ev in prog.events:
                if ev.kind is EventKind.SPINDLE:
                    self._apply_spindle(SpindleState(direction=int(np.sign(ev.value)), rpm=abs(ev.value)))
            return self._ok("mdi")
        try:
            job = self._make_job(Activity.MDI, prog, "MDI")
        except PlannerError as exc:
            return self._refuse("mdi", f"planner: {exc}")
        self._start_job(job)
        return self._ok("mdi")
