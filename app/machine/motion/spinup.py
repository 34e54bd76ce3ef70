"""The spindle's spin-ups a run waits for: the motion stands while the spindle comes up to
speed (``[controller] spindle_spinup_s``), and the cycle time and the time left count it."""

from __future__ import annotations

from collections.abc import Iterable

from app.machine.model import SpindleState
from app.machine.motion.timescale import PauseKind, PausePoint
from planner.core.program import SpindleSpeed

__all__ = ["spin_up_waits", "spins_up"]


def spins_up(old: SpindleState, new: SpindleState) -> bool:
    """Whether switching from ``old`` to ``new`` makes the motion wait for the spindle: it
    starts, reverses or speeds up."""
    return new.on and (not old.on or old.direction != new.direction or new.rpm > old.rpm)


def spin_up_waits(pauses: Iterable[PausePoint], start: SpindleState,
                  spin_up_s: float) -> list[tuple[float, float]]:
    """(planned time, wait) of every spin-up a run through these pause points
    (``timescale.pause_points``) waits for, from the spindle state ``start``: an M3/M4/S that
    starts, reverses or speeds the spindle up (after a tool change, M6 having stopped it, the
    program's M3/M4 starts it again). The run's cycle time and the time left
    count them: the motion stands while the spindle comes up to speed."""
    waits: list[tuple[float, float]] = []
    state = start
    for p in pauses:
        if p.kind is PauseKind.SPINDLE:
            speed = p.payload_as(SpindleSpeed)
            new = SpindleState(direction=speed.direction, rpm=speed.rpm)
            if spins_up(state, new) and spin_up_s > 0.0:
                waits.append((float(p.tau_s), spin_up_s))
            state = new
        elif p.kind is PauseKind.TOOL_CHANGE:
            state = SpindleState()          # M6 stops the spindle until the program's M3/M4
    return waits
