"""The probing wizards on the simulated machine from random start positions.

    python -m bench.bench_probing [--starts 20] [--seed 1] [--only probe_bore]

The real controller on simulated drives (a manual clock, the worker's 1 ms cycle, the probe
latched from the drive's inputs, the motion stopped past each contact), a simulated part
(``ethercat.sim_part``: a block with a bore, a boss or a pocket, or turned for the angle) at a
known place, the probe (2 mm ball, 50 mm long) put at a random start of the kind each wizard
expects. Printed per wizard: runs, the largest error of what G55 took against the truth (mm, or
degrees for the angle), runs that failed, and the wall time. The last line is the JSON result.
"""

from __future__ import annotations

import argparse
import json
import math
import shutil
import tempfile
import time
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path

import numpy as np

from app.machine.controller import MachineController
from app.machine.model import MachineState, ProbeWizard, ProbingRequest
from ethercat.sim_part import Feature, SimPart
from planner.core.tools import Tool
from resources import shipped_machine

PROBE = Tool(99, 99, (("Z", 50.0),), 2.0, "3-D probe")
R = PROBE.diameter_mm / 2.0
TOP = -60.0
BLOCK = SimPart(x_mm=20.0, y_mm=10.0, half_x_mm=40.0, half_y_mm=30.0, top_mm=TOP, depth_mm=40.0)

# per wizard: (the request, the part, the truth by G55 column (9: the rotation), a start) made
# from a random generator
Case = tuple[ProbingRequest, SimPart, dict[int, float], tuple[float, float, float]]


def _z(rng: np.random.Generator) -> Case:
    start = (20.0 + rng.uniform(-30, 30), 10.0 + rng.uniform(-20, 20), TOP + rng.uniform(2, 8))
    return ProbingRequest(ProbeWizard.Z_SURFACE, system="G55"), BLOCK, {2: TOP}, start


def _edge(rng: np.random.Generator) -> Case:
    start = (-20.0 - R - rng.uniform(1, 8), 10.0 + rng.uniform(-25, 25), TOP - rng.uniform(3, 8))
    return ProbingRequest(ProbeWizard.EDGE, system="G55", axis="X", x_dir=1), BLOCK, {0: -20.0}, start


def _outside(rng: np.random.Generator) -> Case:
    start = (-20.0 - R - rng.uniform(1, 5), -20.0 - R - rng.uniform(1, 5), TOP - rng.uniform(3, 8))
    req = ProbingRequest(ProbeWizard.OUTSIDE_CORNER, system="G55", x_dir=1, y_dir=1, along_mm=10.0)
    return req, BLOCK, {0: -20.0, 1: -20.0}, start


def _inside(rng: np.random.Generator) -> Case:
    part = replace(BLOCK, feature=Feature.POCKET, feature_x_mm=25.0, feature_y_mm=12.0, pocket_half_x_mm=12.0,
                   pocket_half_y_mm=9.0)
    start = (37.0 - R - rng.uniform(1, 6), 21.0 - R - rng.uniform(1, 6), TOP - rng.uniform(3, 8))
    req = ProbingRequest(ProbeWizard.INSIDE_CORNER, system="G55", x_dir=1, y_dir=1)
    return req, part, {0: 37.0, 1: 21.0}, start


def _bore(rng: np.random.Generator) -> Case:
    part = replace(BLOCK, feature=Feature.BORE, feature_x_mm=23.0, feature_y_mm=12.0, feature_radius_mm=10.0)
    start = (23.0 + rng.uniform(-3, 3), 12.0 + rng.uniform(-3, 3), TOP - rng.uniform(3, 8))
    req = ProbingRequest(ProbeWizard.BORE, system="G55", diameter_mm=20.0, tolerance_mm=0.5)
    return req, part, {0: 23.0, 1: 12.0}, start


def _boss(rng: np.random.Generator) -> Case:
    part = replace(BLOCK, feature=Feature.BOSS, feature_x_mm=23.0, feature_y_mm=12.0, feature_radius_mm=8.0,
                   boss_height_mm=10.0)
    above = rng.uniform(2, 6)
    start = (23.0 + rng.uniform(-2, 2), 12.0 + rng.uniform(-2, 2), TOP + 10.0 + above)
    req = ProbingRequest(ProbeWizard.BOSS, system="G55", diameter_mm=16.0, tolerance_mm=0.5,
                         depth_mm=above + 5.0)
    return req, part, {0: 23.0, 1: 12.0}, start


def _angle(rng: np.random.Generator) -> Case:
    angle = rng.uniform(-5, 5)
    a = math.radians(angle)
    x0 = 20.0 + rng.uniform(-30, -5)
    face_y = 10.0 + (x0 - 20.0) * math.tan(a) - 30.0 / math.cos(a)
    start = (x0, face_y - R - rng.uniform(4.5, 7), TOP - rng.uniform(3, 8))
    req = ProbingRequest(ProbeWizard.ANGLE, system="G55", axis="Y", y_dir=1, along_mm=30.0, search_mm=15.0)
    return req, replace(BLOCK, angle_deg=angle), {9: angle}, start


CASES: dict[str, Callable[[np.random.Generator], Case]] = {
    "probe_z": _z, "probe_edge": _edge, "probe_corner_outside": _outside, "probe_corner_inside": _inside,
    "probe_bore": _bore, "probe_boss": _boss, "probe_angle": _angle,
}


def _idle(ctl: MachineController) -> bool:
    return ctl.state is MachineState.IDLE and ctl.stream.job is None


def run_one(ctl: MachineController, case: Case) -> float | str:
    """The largest error of one run (mm or degrees), or why it failed."""
    req, part, truth, (x, y, z) = case
    ctl.simulate_part(part)
    for block in ("G54", f"G53 G0 Z{z + PROBE.length_mm:.4f}", f"G53 G0 X{x:.4f} Y{y:.4f}"):
        if not ctl.mdi(block) and block != "G54":
            return f"cannot move to the start: {block}"
        ctl.run_until(lambda: _idle(ctl), 30)
    res = ctl.run_probing(req)
    if not res:
        return res.reason
    ctl.run_until(lambda: ctl.state is not MachineState.RUNNING and ctl.stream.job is None, 120)
    if ctl.active_alarms:
        return "; ".join(a.cause for a in ctl.active_alarms)
    errors = [abs((ctl.work_rotation("G55") if k == 9 else ctl.work_offsets["G55"][k]) - v)
              for k, v in truth.items()]
    return max(errors)


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m bench.bench_probing", description=__doc__.split("\n\n")[0])
    p.add_argument("--starts", type=int, default=20)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--only", choices=sorted(CASES))
    args = p.parse_args(argv)
    from PySide6.QtCore import QCoreApplication

    app = QCoreApplication.instance() or QCoreApplication([])  # noqa: F841 - the controller's signals
    out: dict[str, dict[str, float | int]] = {}
    with tempfile.TemporaryDirectory(prefix="bench-probing-") as tmp:
        config = Path(tmp) / "machine.toml"
        shutil.copyfile(shipped_machine("xyz_mill"), config)
        for name, make in CASES.items():
            if args.only and name != args.only:
                continue
            rng = np.random.default_rng(args.seed)
            state = Path(tmp) / name
            state.mkdir()
            ctl = MachineController(config, state_dir=state, worker_mode="manual")
            try:
                assert ctl.connect_bus() and ctl.set_machine_zero_here()
                assert ctl.set_tool(PROBE) and ctl.set_tool_in_spindle(PROBE.number)
                worst, failed = 0.0, 0
                t0 = time.perf_counter()
                for _ in range(args.starts):
                    got = run_one(ctl, make(rng))
                    if isinstance(got, str):
                        failed += 1
                        print(f"  {name}: {got}")
                        ctl.acknowledge_alarm()
                        if ctl.state is MachineState.ALARM:
                            ctl.reset()
                    else:
                        worst = max(worst, got)
                wall = time.perf_counter() - t0
            finally:
                ctl.shutdown()
            unit = "deg" if name == "probe_angle" else "mm"
            print(f"{name:22s} runs {args.starts:3d}  worst error {worst:.5f} {unit}  failed {failed}  "
                  f"{wall:6.1f} s")
            out[name] = {"runs": args.starts, "worst_error": worst, "failed": failed,
                         "wall_s": round(wall, 1)}
    print(json.dumps(out))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
