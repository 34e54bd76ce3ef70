"""G64 P/Q: the program of record under a path tolerance, blended where it pays. The geometry
proposes (``planner.geometry.blend``: runs of lines joined by Q, fillets eased by clothoids,
corner pairs; ``planner.geometry.transition``: line-arc and arc-arc joints eased), the planner
decides: a blend is kept where it is quicker than the sharp joint's plan."""

from __future__ import annotations

from planner.core.machine import MachineSpec
from planner.core.program import Program
from planner.geometry.blend import SpeedOracle, blend_corners, merge_naive_cam, round_fillets
from planner.geometry.transition import ease_joints
from planner.motion.plan import plan_program

__all__ = ["blend_program"]


def blend_program(program: Program, machine: MachineSpec, only_where_quicker: bool = True) -> Program:
    """The program under G64 P/Q: runs of lines joined by Q (``merge_naive_cam``), fillets eased
    by clothoids (``round_fillets``), joints of arcs eased by cubic-curvature transitions
    (``ease_joints``), then sharp line-line joints replaced by clothoid pairs
    (``blend_corners``), each judged against the plan of the program as it stands.

    Returns ``program`` itself when nothing is blended. Move indices change: events, modal
    texts and offset changes are moved to the new indices (each keeps its place in the path).
    ``only_where_quicker=False`` blends every eligible corner (smoothest motion: no velocity
    step at those joints, even where the sharp corner would be crossed sooner).
    """
    speeds: SpeedOracle | None = (lambda p: plan_program(p, machine)) if only_where_quicker else None
    program = round_fillets(merge_naive_cam(program), machine, speeds)
    program = ease_joints(program, machine, speeds)
    return blend_corners(program, machine, speeds)
