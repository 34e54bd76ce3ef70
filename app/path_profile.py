"""Speed, acceleration and jerk along the path of a planned program against time (Fig. 14).

Derived from the planner's 1 ms samples of the path length s(t) by the limit meter's finite
differences (``planner.motion.meter.path_vaj``, the same as ``cnc-plan --plot``); the
first ``max_time_s`` seconds only, so a long program never costs unbounded memory.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from planner.core.machine import MachineSpec
from planner.core.program import Program
from planner.motion.meter import path_vaj

MAX_TIME_S = 600.0


@dataclass(frozen=True, slots=True)
class PathProfile:
    t: np.ndarray      # s
    v: np.ndarray      # mm/s
    a: np.ndarray      # mm/s^2
    j: np.ndarray      # mm/s^3
    cycle_time_s: float
    truncated: bool    # True when only the first max_time_s are shown
    limits: tuple[float, float, float]  # Vmax, Amax, Jmax of the machine
    rapid_mm_s: float = 0.0  # G00 moves run up to this, above the feed limit Vmax


def path_profile(program: Program, machine: MachineSpec, max_time_s: float = MAX_TIME_S,
                 plan: object | None = None, cycle_time_s: float = math.nan) -> PathProfile:
    """From the controller's plan when given (what will run), else planned here as far as it
    is shown (a long program's plan is not held: ``cycle_time_s`` is its planned time, known
    from the load's check)."""
    from planner.motion.plan import Plan
    from planner.motion.window import PlanWindow

    source: Plan | PlanWindow = plan if isinstance(plan, Plan) else PlanWindow(program, machine,
                                                                             estimate_s=cycle_time_s)
    ts = source.ts_s
    t_parts, s_parts = [], []
    n = 0
    limit = int(max_time_s / ts) + 4
    chunks = source.iter_chunks() if isinstance(source, Plan) else source.iter_chunks(let_go=True)
    for chunk in chunks:
        t_parts.append(chunk.t)
        s_parts.append(chunk.s)
        n += len(chunk)
        if n >= limit:
            break
    t = np.concatenate(t_parts)[:limit] if t_parts else np.zeros(0)
    s = np.concatenate(s_parts)[:limit] if s_parts else np.zeros(0)
    lim = machine.limits
    limits = (lim.v_max_mm_s, lim.a_max_mm_s2, lim.j_max_mm_s3)
    if len(t) < 4:
        z = np.zeros(len(t))
        return PathProfile(t, z, z, z, source.cycle_time_s, False, limits, lim.rapid_mm_s)
    v, a, j = path_vaj(s, ts)
    return PathProfile(t, v, a, j, source.cycle_time_s, source.cycle_time_s > max_time_s, limits,
                       lim.rapid_mm_s)
