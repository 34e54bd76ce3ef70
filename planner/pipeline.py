"""The one way a program becomes what runs: read -> refuse what the machine cannot do -> blend ->
soft limits on the path that will run -> plan. ``cnc-plan``, ``cnc-run`` and the panel all load
programs through ``load``; each passes what it knows of the machine (``Abilities``) and how it
plans (the last stage).

Every refusal is a ``ProgramError`` naming the file, the line and the column and saying why;
a path beyond the travel is a ``SoftLimitError`` listing each violation with its line and axis.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Generic, Protocol, TypeVar

import numpy as np

from planner.core.errors import PlannerError, ProgramError, SourceError
from planner.core.heap import trim_heap
from planner.core.machine import MachineSpec
from planner.core.program import Coolant, CoolantSwitch, EventKind, ProbeResult, Program
from planner.core.tools import ToolTable
from planner.gcode.interpreter import parse_program, read_program_bytes
from planner.geometry.blend import BlendReport, blend_report
from planner.geometry.softlimits import LimitViolation, check_and_bound
from planner.motion.blending import blend_program

__all__ = ["Abilities", "Loaded", "Refused", "Reread", "Rereading", "SoftLimitError", "load", "refusal",
           "travel"]

P = TypeVar("P")


@dataclass(frozen=True, slots=True)
class Abilities:
    """What the machine can do that a program may ask for. The default can do everything (a
    planning tool reads and plans what LinuxCNC reads); a machine says what it cannot."""

    probe_input: bool = True                  # a probe input for G38.x
    probe_max_feed_mm_min: float = math.inf   # the fastest a probe move may be (its overtravel)
    spindle_encoder: bool = True              # G33, G76: each pass starts at the same angle
    analog_outputs: bool = True               # M67, M68
    coolant_mist: bool = True                 # M7
    coolant_flood: bool = True                # M8


class Refused(ProgramError):
    """A program read without error that this machine cannot run (or that moves nothing), at
    the line that asks for it."""


class SoftLimitError(PlannerError):
    """The path that would run leaves the machine's travel: every violation, with its line."""

    def __init__(self, violations: Sequence[LimitViolation]) -> None:
        self.violations = tuple(violations)
        super().__init__(f"soft limit: {self.violations[0]}")


def travel(program: Program, machine: MachineSpec) -> tuple[np.ndarray, np.ndarray]:
    """The load's travel stage: ``program``'s bounds (machine coordinates, every move's
    extremes, arcs exact, a piece of the program at a time); ``SoftLimitError`` naming every
    violation when its path leaves the travel. A program the controller makes (the approach of
    a restart) is checked by the same stage."""
    violations, lo, hi = check_and_bound(program, machine)
    if violations:
        raise SoftLimitError(violations)
    return lo, hi


def refusal(program: Program, abilities: Abilities) -> tuple[int, str, str]:
    """(line, code, why) of the first thing in ``program`` this machine cannot run ((0, "", "")
    when it can run all of it)."""
    for p in program.probes:
        if not abilities.probe_input:
            return p.line, "G38", (f"{p.name} needs a probe input: this machine has none ([probe] drive "
                                   "in the machine configuration)")
        if p.move_index < 0:
            continue
        feed = program.moves[p.move_index].feed_mm_s * 60.0
        if feed > abilities.probe_max_feed_mm_min * (1.0 + 1e-9):
            return p.line, "G38", (f"{p.name} at F{feed:g} mm/min is faster than the probe allows ([probe] "
                                   f"max_feed_mm_min = {abilities.probe_max_feed_mm_min:g}: the stylus "
                                   "travels on past the contact while the motion stops)")
    if program.synchronised and not abilities.spindle_encoder:
        motion = program.synchronised[0]
        return motion.line, motion.code, (
            f"{motion.code} is spindle-synchronised motion: every pass of a thread must start at the same "
            "spindle angle, and this machine's spindle has no encoder to give it; it cannot run here")
    if not (abilities.coolant_mist and abilities.coolant_flood):
        for ev in program.events:
            if ev.kind is not EventKind.COOLANT:
                continue
            switch = ev.payload_as(CoolantSwitch).switch
            if switch is Coolant.MIST_ON and not abilities.coolant_mist:
                return ev.line, "M7", ("M7 switches mist coolant on, and this machine has no mist coolant "
                                       "output ([signals] coolant_mist in the machine configuration)")
            if switch is Coolant.FLOOD_ON and not abilities.coolant_flood:
                return ev.line, "M8", ("M8 switches flood coolant on, and this machine has no flood coolant "
                                       "output ([signals] coolant_flood in the machine configuration)")
    if program.analog_outputs and not abilities.analog_outputs:
        out = program.analog_outputs[0]
        return out.line, out.code, (f"{out.code} E{out.index} sets an analog output, and this machine has "
                                    "none (its drives' outputs are digital: M62-M65)")
    return 0, "", ""


def _column(text: str, line: int, code: str) -> int:
    """Where ``code`` stands on line ``line`` of ``text`` (1 when it cannot be found)."""
    if line <= 0:
        return 1
    start = 0
    for _ in range(line - 1):
        start = text.find("\n", start) + 1
        if start == 0:
            return 1
    end = text.find("\n", start)
    return text[start:end if end >= 0 else None].upper().find(code) + 1 or 1


@dataclass(frozen=True, eq=False)
class Loaded(Generic[P]):
    """A program as it runs: ``program`` (blended when the machine blends), ``programmed`` as
    read (LinuxCNC's canonical calls write it), its bounds (machine coordinates, arcs by their
    exact extremes; None when the travel was not checked), the blends made, and the last
    stage's result (the plan, however the caller made it)."""

    programmed: Program
    program: Program
    bounds: tuple[np.ndarray, np.ndarray] | None
    blends: BlendReport
    plan: P
    reread: Reread


@dataclass(frozen=True, eq=False)
class Rereading:
    """A program read again with what the machine read: the whole of it (``program``, blended
    as the first reading was) and ``part``, what runs from here (checked against the travel;
    None when the caller's cut found nothing)."""

    program: Program
    part: Program | None


class Reread(Protocol):
    """``Loaded.reread``: the same program from the same start, read with the probe results
    (G38.x) and the inputs' values (M66), through the load's stages in its order: refused as
    the load refuses, blended as it was blended, ``part`` of it cut (the whole when None),
    and that part checked against the travel. Raises as ``load`` raises."""

    def __call__(self, probes: tuple[ProbeResult | None, ...], waits: tuple[float | None, ...],
                 part: Callable[[Program], Program | None] | None = None) -> Rereading: ...


def load(source: str | os.PathLike[str], name: str, machine: MachineSpec, plan: Callable[[Program], P], *,
         start_position: Sequence[float] | np.ndarray | None = None, tools: ToolTable | None = None,
         tool_in_spindle: int = 0, spindle: tuple[int, float] = (0, 0.0),
         parameters: dict[int, float] | None = None, block_delete: bool = False,
         tool_offset: tuple[int, Sequence[float]] | None = None, abilities: Abilities | None = None,
         blend: bool | None = None, check_travel: bool = True,
         require_motion: bool = True, progress: Callable[[int, int], None] | None = None,
         between: Callable[[], None] = lambda: None) -> Loaded[P]:
    """Read ``source`` (a program's text, or its file: read from its bytes) as ``name`` (every
    message names it) for ``machine`` (from ``start_position`` with the tools, the spindle
    (direction, rpm), parameters and tool length offset the machine has in force), refuse what the machine
    cannot run (``abilities``), blend it (``blend``: the machine's look-ahead mode decides when
    None), check the path that will run against the travel (``check_travel``), refuse a program
    that moves nothing (``require_motion``), and plan it (``plan``). ``between`` runs between
    the stages (a load that may be cancelled raises there). Raises ``ProgramError`` (reading),
    ``Refused``, ``SoftLimitError`` or ``PlannerError``."""
    abilities = abilities or Abilities()
    do_blend = machine.planner.mode == "lookahead" if blend is None else blend
    text: str | None
    utf8: bytes | None
    if isinstance(source, os.PathLike):
        text, utf8 = read_program_bytes(source, machine.planner.max_program_bytes)
    else:
        text, utf8 = source, None

    def read(probes: tuple[ProbeResult | None, ...] = (), waits: tuple[float | None, ...] = (),
             report: Callable[[int, int], None] | None = None) -> Program:
        return parse_program(text, name, machine=machine, start_position=start_position, tools=tools,
                             tool_in_spindle=tool_in_spindle, spindle=spindle, parameters=parameters,
                             probe_results=probes,
                             input_results=waits, block_delete=block_delete, progress=report, utf8=utf8,
                             tool_offset=tool_offset)

    def refuse(programmed: Program) -> None:
        at, code, why = refusal(programmed, abilities)
        if why:
            whole = text if text is not None else (utf8 or b"").decode("utf-8", "replace")
            raise Refused([SourceError(name, at, _column(whole, at, code), why)])

    def blended(programmed: Program) -> Program:
        return blend_program(programmed, machine) if do_blend else programmed

    def reread(probes: tuple[ProbeResult | None, ...], waits: tuple[float | None, ...],
               part: Callable[[Program], Program | None] | None = None) -> Rereading:
        again = read(probes, waits)
        refuse(again)
        whole = blended(again)
        piece = part(whole) if part is not None else whole
        if check_travel and piece is not None and piece.moves:
            travel(piece, machine)
        return Rereading(whole, piece)

    try:
        programmed = read(report=progress)
    finally:
        trim_heap()   # the reading's freed temporaries back to the system
    refuse(programmed)
    program = blended(programmed)
    if require_motion and not program.moves:
        raise Refused([SourceError(name, 0, 0, "the program moves no axis: nothing to run (spindle, tool "
                                                    "and coolant codes alone are given in MDI, M61 Q for "
                                                    "the tool in the spindle)")])
    between()
    report = blend_report(program)
    bounds = travel(program, machine) if check_travel else None
    between()
    planned = plan(program)
    return Loaded(programmed, program, bounds, report, planned, reread)
