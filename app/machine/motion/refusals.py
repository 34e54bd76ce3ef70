"""This machine's abilities, which the load's refusal stage reads (``planner.pipeline.refusal``:
a probe input when ``[probe] drive`` is set, no spindle encoder, no analog outputs, the coolant
outputs wired), and the load's soft-limit violations as the program's issues at their lines."""

from __future__ import annotations

from app.machine.config import MachineConfig
from app.machine.model import ProgramIssue
from planner.geometry.softlimits import LimitViolation
from planner.pipeline import Abilities

__all__ = ["machine_abilities", "violation_issues"]


def machine_abilities(cfg: MachineConfig) -> Abilities:
    """What this machine can do that a program may ask for: its spindle is switched by a drive's
    digital outputs (no encoder, so no threading), its outputs are digital, it probes when the
    configuration names the probe's input, and switches coolant where its signals are wired."""
    probe = cfg.probe
    return Abilities(probe_input=probe.drive is not None, probe_max_feed_mm_min=probe.max_feed_mm_min,
                     spindle_encoder=False, analog_outputs=False,
                     coolant_mist=cfg.wiring.has("coolant_mist"),
                     coolant_flood=cfg.wiring.has("coolant_flood"))


def violation_issues(violations: list[LimitViolation]) -> tuple[ProgramIssue, ...]:
    """The soft-limit violations as the program's issues, at their lines."""
    return tuple(ProgramIssue(v.line, 1, str(v).split(": ", 1)[1], v.axis) for v in violations)
