"""Plans for runs: made with the machine and the override budget of the moment (the
acceleration and jerk held back for the time scale, ``app.machine.motion.timescale``), whole
for a program of up to ``WINDOWED_RUN_MOVES`` moves, else as the run reaches them
(``planner.motion.window``)."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace

from app.machine.motion.timescale import Budget, reduced_machine
from planner.core.machine import MachineSpec
from planner.core.program import Program
from planner.motion.plan import Plan, plan_program
from planner.motion.window import PlanWindow

__all__ = ["WINDOWED_RUN_MOVES", "RunPlanner", "single_block_program"]

#: programs of more moves run from a plan made as they run (``planner.motion.window``): a whole plan
#: holds about 150 bytes a move (1.5 GB at 10,000,000 moves), a window a few thousand moves
WINDOWED_RUN_MOVES = 200_000


def single_block_program(program: Program) -> Program:
    """The program with an exact stop (G61) at every block end: single block's plan."""
    return replace(program, moves=program.moves.with_exact_stops())


@dataclass(frozen=True, eq=False)
class RunPlanner:
    """Plans for runs, bound to the machine and the override budget of the moment it was made
    (a change of the configuration meanwhile cannot reach into a plan under way in a worker
    thread): called as ``plan_program`` is (a whole ``Plan``), or ``window`` (planned as the
    run reaches it) for programs of more than ``WINDOWED_RUN_MOVES`` moves."""

    machine: MachineSpec   # the reduced limits the plan is made with

    @staticmethod
    def of(machine: MachineSpec, budget: Budget) -> RunPlanner:
        return RunPlanner(reduced_machine(machine, budget))

    def __call__(self, program: Program, progress: Callable[[int, int], None] | None = None) -> Plan:
        return plan_program(program, self.machine, progress=progress)

    def window(self, program: Program, estimate_s: float = math.nan) -> PlanWindow:
        return PlanWindow(program, self.machine, estimate_s=estimate_s)

    def for_run(self, program: Program, estimate_s: float = math.nan) -> Plan | PlanWindow:
        """What a run of ``program`` plays: a window for a long program, else the whole plan."""
        if len(program.moves) > WINDOWED_RUN_MOVES:
            return self.window(program, estimate_s)
        return self(program)
