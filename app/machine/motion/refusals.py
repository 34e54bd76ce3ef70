"""What this machine cannot run, said at the line that asks for it: probing without a probe input
(or faster than the stylus allows), spindle-synchronised motion without a spindle encoder,
analog outputs; and a path beyond the soft limits."""

from __future__ import annotations

from app.machine.model import ProgramIssue
from planner.machine import MachineSpec
from planner.program import Program
from planner.softlimits import LimitViolation, check_program

__all__ = ["analog_refusal", "limit_issues", "probe_refusal", "synchronised_refusal", "violation_issues"]


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


def synchronised_refusal(program: Program) -> tuple[int, str]:
    """Why this machine cannot run a program's spindle-synchronised motion (G33, G76), with its
    line ((0, "") when it has none). Each pass of a thread must start at the same spindle angle;
    this spindle is switched by a drive's digital outputs and has no encoder to give its angle,
    so the passes would each cut a thread of their own. (G33.1 rigid tapping runs: it goes in
    and back out once, and a floating tap holder takes up the difference.)"""
    for motion in program.synchronised:
        return motion.line, (f"{motion.code} is spindle-synchronised motion: every pass of a thread must "
                             "start at the same spindle angle, and this machine's spindle has no encoder "
                             "to give it; it cannot run here")
    return 0, ""


def analog_refusal(program: Program) -> tuple[int, str]:
    """Why this machine cannot run a program's M67/M68, with the line ((0, "") when it has
    none): its drives' outputs are digital (0x60FE); it has no analog output to set."""
    for out in program.analog_outputs:
        return out.line, (f"{out.code} E{out.index} sets an analog output, and this machine has none "
                          "(its drives' outputs are digital: M62-M65)")
    return 0, ""


def violation_issues(violations: list[LimitViolation]) -> tuple[ProgramIssue, ...]:
    """The soft-limit violations as the program's issues, at their lines."""
    return tuple(ProgramIssue(v.line, 1, str(v).split(": ", 1)[1], v.axis) for v in violations)


def limit_issues(program: Program, machine: MachineSpec) -> list[ProgramIssue]:
    """Soft-limit issues of a program's whole path (a load, MDI, run from line, a read again)."""
    return list(violation_issues(check_program(program, machine)))
