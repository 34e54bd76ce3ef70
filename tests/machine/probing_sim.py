"""The probing routines run by the interpreter against a simulated part, without drives: each
probe move is followed from where it starts until the stylus' ball touches the part
(``ethercat.sim_part``, the same part the simulated bus answers with), the result handed back
and the routine read again, as the controller does at each contact. What the routine finally
writes (its G10) and reports (its DEBUG line) is what a run on the machine would."""

from __future__ import annotations

import re
from dataclasses import dataclass

import numpy as np

from ethercat.sim_part import SimPart
from planner.core.machine import MachineSpec
from planner.core.program import ProbeResult, Program
from planner.core.tools import ToolTable
from planner.gcode.interpreter import parse_program

#: how far the stylus travels past the contact before the stop (mm): the machine's overtravel
OVERTRAVEL_MM = 0.02


class ProbeAlarm(Exception):
    """A probe move the machine refuses or ends in an alarm (G38.2 without contact)."""


@dataclass(frozen=True)
class Outcome:
    program: Program                 # read with every contact
    contacts: int                    # probe moves that touched
    reported: dict[str, float]       # the routine's "probe result:" values

    def system(self, base: int) -> dict[int, float]:
        """The parameters the routine left for the coordinate system numbered from ``base``
        (5241 for G55: X Y Z, then R at base + 9), from its last G10."""
        values: dict[int, float] = {}
        for sets in self.program.parameter_sets:
            values.update({k: v for k, v in sets.items() if base <= k <= base + 9})
        return values


def _contact(part: SimPart, a: np.ndarray, b: np.ndarray) -> float | None:
    """The fraction of the move a -> b (spindle gauge line, X Y Z) where the ball first touches,
    or None; 0.0 when it touches at the start."""
    if part.touches(*a):
        return 0.0
    length = float(np.linalg.norm(b - a))
    if length == 0.0:
        return None
    r = part.tip_radius_mm
    t = 0.0
    while t < 1.0:
        p = a + (b - a) * t
        gap = part.distance(p[0], p[1], p[2] - part.tip_length_mm + r) - r
        if gap <= 0.0:
            break
        t += max(gap, 1e-4) / length
    else:
        if not part.touches(*b):
            return None
        t = 1.0
    lo, hi = max(0.0, t - 2e-4 / length), min(1.0, t)
    if part.touches(*(a + (b - a) * lo)):
        lo = 0.0
    for _ in range(60):
        mid = (lo + hi) / 2.0
        if part.touches(*(a + (b - a) * mid)):
            hi = mid
        else:
            lo = mid
    return hi


def run(text: str, machine: MachineSpec, tools: ToolTable, tool: int, start: tuple[float, float, float],
        part: SimPart | None) -> Outcome:
    """Run the routine ``text`` from machine position ``start`` (the gauge line) against ``part``
    (None: nothing to touch), the ball's length and radius from ``tools``' entry of ``tool``."""
    spec = tools.get(tool)
    assert spec is not None
    if part is not None:
        part = SimPart(**{**{f: getattr(part, f) for f in part.__dataclass_fields__},
                          "tip_length_mm": spec.length_mm, "tip_radius_mm": spec.diameter_mm / 2.0})
    results: list[ProbeResult] = []
    contacts = 0
    while True:
        prog = parse_program(text, "probing", machine, start_position=start, tools=tools,
                             tool_in_spindle=tool, probe_results=tuple(results))
        if len(results) >= len(prog.probes):
            break
        req = prog.probes[len(results)]
        k = req.move_index
        a = np.asarray(prog.moves[k - 1].end if k > 0 else prog.start_position, dtype=float)
        b = np.asarray(req.target, dtype=float)
        t = _contact(part, a, b) if part is not None else None
        if t == 0.0:
            raise ProbeAlarm(f"{req.name} (line {req.line}): the probe already touches where the move starts")
        if t is None:
            if req.error_without_trip:
                raise ProbeAlarm(f"{req.name} (line {req.line}): the probe move ended without contact")
            results.append(ProbeResult(False, tuple(b), tuple(b)))
            continue
        trip = a + (b - a) * t
        direction = (b - a) / np.linalg.norm(b - a)
        stop = trip + direction * min(OVERTRAVEL_MM, float(np.linalg.norm(b - trip)))
        results.append(ProbeResult(True, tuple(trip), tuple(stop)))
        contacts += 1
    reported: dict[str, float] = {}
    for e in prog.events:
        found = re.search(r"probe result:(.*)", e.message or "")
        if found:
            reported = {k: float(v) for k, v in re.findall(r"([A-Z])=(-?\d+(?:\.\d+)?)", found.group(1))}
    return Outcome(prog, contacts, reported)
