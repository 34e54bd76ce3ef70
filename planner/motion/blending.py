"""G64 P/Q: the program of record under a path tolerance, blended where it pays. The geometry
proposes (``planner.geometry.blend``: runs of lines joined by Q, fillets eased by clothoids,
corner pairs; ``planner.geometry.transition``: line-arc and arc-arc joints eased), the planner
decides: a blend is kept where it is quicker than the sharp joint's plan."""

from __future__ import annotations

import time

from planner.core.machine import MachineSpec
from planner.core.program import Program
from planner.geometry.blend import SpeedOracle, blend_corners, merge_naive_cam, round_fillets
from planner.geometry.transition import ease_joints
from planner.motion.plan import plan_program

__all__ = ["blend_program"]


def blend_program(program: Program, machine: MachineSpec, only_where_quicker: bool = True,
                  pass_times_s: dict[str, float] | None = None) -> Program:
    """The program under G64 P/Q: runs of lines joined by Q (``merge_naive_cam``), fillets eased
    by clothoids (``round_fillets``), joints of arcs eased by cubic-curvature transitions
    (``ease_joints``), then sharp line-line joints replaced by clothoid pairs
    (``blend_corners``), each judged against the plan of the program as it stands.

    Returns ``program`` itself when nothing is blended. Move indices change: events, modal
    texts and offset changes are moved to the new indices (each keeps its place in the path).
    ``only_where_quicker=False`` blends every eligible corner (smoothest motion: no velocity
    step at those joints, even where the sharp corner would be crossed sooner).
    ``pass_times_s``: filled with the seconds each pass took (the benchmark's).
    """
    speeds: SpeedOracle | None = (lambda p: plan_program(p, machine)) if only_where_quicker else None
    times = pass_times_s if pass_times_s is not None else {}
    t = time.perf_counter()
    for name, step in (("merge", merge_naive_cam),
                       ("fillets", lambda p: round_fillets(p, machine, speeds)),
                       ("arc_joints", lambda p: ease_joints(p, machine, speeds)),
                       ("corners", lambda p: blend_corners(p, machine, speeds))):
        program = step(program)
        now = time.perf_counter()
        times[name] = now - t
        t = now
    return program
