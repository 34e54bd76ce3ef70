"""What this machine cannot run, said at the line that asks for it (``planner.pipeline.refusal``
with this machine's abilities: a probe input when ``[probe] drive`` is set, no spindle encoder,
no analog outputs), and a path beyond the soft limits."""

from __future__ import annotations

from app.machine.config import MachineConfig
from app.machine.model import ProgramIssue
from planner.core.machine import MachineSpec
from planner.core.program import Program
from planner.geometry.softlimits import LimitViolation, check_program
from planner.pipeline import Abilities
from planner.pipeline import refusal as pipeline_refusal

__all__ = ["limit_issues", "machine_abilities", "refusal", "violation_issues"]


def machine_abilities(cfg: MachineConfig) -> Abilities:
    """What this machine can do that a program may ask for: its spindle is switched by a drive's
    digital outputs (no encoder, so no threading), its outputs are digital, it probes when the
    configuration names the probe's input, and switches coolant where its signals are wired."""
    probe = cfg.probe
    return Abilities(probe_input=probe.drive is not None, probe_max_feed_mm_min=probe.max_feed_mm_min,
                     spindle_encoder=False, analog_outputs=False,
                     coolant_mist=cfg.wiring.has("coolant_mist"),
                     coolant_flood=cfg.wiring.has("coolant_flood"))


def refusal(program: Program, cfg: MachineConfig) -> tuple[int, str]:
    """(line, why) of the first thing in ``program`` this machine cannot run, (0, "") when none."""
    at, _code, why = pipeline_refusal(program, machine_abilities(cfg))
    return at, why


def violation_issues(violations: list[LimitViolation]) -> tuple[ProgramIssue, ...]:
    """The soft-limit violations as the program's issues, at their lines."""
    return tuple(ProgramIssue(v.line, 1, str(v).split(": ", 1)[1], v.axis) for v in violations)


def limit_issues(program: Program, machine: MachineSpec) -> list[ProgramIssue]:
    """Soft-limit issues of a program's whole path (MDI, run from line, a read again)."""
    return list(violation_issues(check_program(program, machine)))
