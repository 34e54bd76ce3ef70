"""The machine runs a program with the interpolation the configuration names, exactly as
``cnc-plan --interp`` interpolates it: the controller's time scaling evaluates the plan with
the planner's own evaluator (Taylor's Eq. 16 steps included), not a closed form of its own."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from app.machine.config import config_to_toml, load_config
from app.machine.motion.timescale import Budget, reduced_machine
from cli.plan import main as cnc_plan
from ethercat.worker import ReplaceResult
from tests.machine.conftest import make_controller, run_to_idle

# arcs, lines and a helix: many profile phase switches, where Eq. 16 drifts from the exact s(t)
PROGRAM = """G21 G90 G17
G0 X2 Y1
G1 X20 Y1 F2400
G2 X30 Y11 R10
G3 X40 Y21 I0 J10
G1 X40 Y35 Z-2
G2 X40 Y35 I-6 J0 Z-4
G1 X5 Y35 F3000
M30
"""


def _set_interpolation(src: Path, dst: Path, interpolation: str) -> None:
    text = src.read_text(encoding="utf-8")
    dst.write_text(text.replace('interpolation = "exact"', f'interpolation = "{interpolation}"'),
                   encoding="utf-8")


def _cnc_plan(tmp_path: Path, config: Path, interpolation: str) -> np.ndarray:
    prog = tmp_path / "p.nc"
    prog.write_text(PROGRAM, encoding="utf-8")
    out = tmp_path / f"{interpolation}.npz"
    args = [str(prog), "--config", str(config), "--interp", interpolation, "--samples", str(out)]
    assert cnc_plan(args) == 0
    with np.load(out) as z:
        return z["q"]


def _run_on_the_machine(config: Path, state_dir: Path) -> np.ndarray:
    ctl = make_controller(config, state_dir)
    try:
        # the worker's queue by serial, as pushed and replaced (a replace drops what follows)
        queued: dict[int, np.ndarray] = {}
        worker = ctl.worker
        real_push, real_replace = worker.push, worker.replace

        def recording_push(q: np.ndarray) -> int:
            first = ctl.stream.pushed_total      # a push follows the last set-point recorded
            n = real_push(q)
            queued.update((first + i, np.array(q[i], dtype=float)) for i in range(n))
            return n

        def recording_replace(serial: int, q: np.ndarray) -> tuple[ReplaceResult, int]:
            result, n = real_replace(serial, q)
            if result is ReplaceResult.DONE:
                for k in [k for k in queued if k >= serial]:
                    del queued[k]
                queued.update((serial + i, np.array(q[i], dtype=float)) for i in range(n))
            return result, n

        worker.push, worker.replace = recording_push, recording_replace
        assert ctl.load_program(PROGRAM, wait=True)
        assert ctl.cycle_start()
        run_to_idle(ctl, 60)
        assert ctl.last_run.completed
        assert sorted(queued) == list(range(len(queued)))
        return np.vstack([queued[k] for k in range(len(queued))])
    finally:
        ctl.shutdown()


@pytest.mark.parametrize("interpolation", ["taylor", "exact"])
def test_program_runs_as_cnc_plan_interpolates_it(qapp, config_path: Path, state_dir: Path, tmp_path: Path,
                                                  interpolation: str) -> None:
    machine_cfg = tmp_path / f"machine_{interpolation}.toml"
    _set_interpolation(config_path, machine_cfg, interpolation)
    cfg = load_config(machine_cfg)
    assert cfg.machine.planner.interpolation == interpolation
    # the controller plans with the override budget: cnc-plan gets the same reduced limits
    budget = Budget(1.0 - cfg.controller.accel_reserve, 1.0 - cfg.controller.jerk_reserve)
    reduced = tmp_path / f"reduced_{interpolation}.toml"
    reduced.write_text(config_to_toml(replace(cfg, machine=reduced_machine(cfg.machine, budget))),
                       encoding="utf-8")
    planned = _cnc_plan(tmp_path, reduced, interpolation)
    other = _cnc_plan(tmp_path, reduced, "exact" if interpolation == "taylor" else "taylor")
    sent = _run_on_the_machine(machine_cfg, state_dir)
    # the machine's first set-point is planned time Ts (sample 1); it ends on the end point
    n = min(len(sent), len(planned) - 1)
    assert n > 0.95 * (len(planned) - 1)
    np.testing.assert_allclose(sent[:n], planned[1:n + 1], rtol=0, atol=1e-9)
    # and the two methods really differ on this program, so the comparison tells them apart
    assert np.max(np.abs(other[1:n + 1] - planned[1:n + 1])) > 1e-7
