"""Fixtures for the machine controller tests: a controller on the real CyclicWorker + SimBus in
"manual" worker mode (simulated time advanced by the test, deterministic and faster than real
time), a private copy of the XYZ mill configuration and a temporary state directory."""

from __future__ import annotations

import shutil
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest

from app.machine.config import DEFAULT_LEAD_S
from app.machine.controller import MachineController
from app.machine.model import MachineState
from resources import shipped_machine

# A feed hold, stop or override takes effect a few cycles ahead of the drives whatever the
# streaming lead (the controller splices the worker's queue), so these tests, which place
# holds at given points of short programs, run with the default lead.
TEST_LEAD_S = DEFAULT_LEAD_S


@pytest.fixture
def config_path(tmp_path: Path) -> Path:
    p = tmp_path / "machine.toml"
    shutil.copyfile(shipped_machine("xyz_mill"), p)
    with p.open("a", encoding="utf-8") as f:
        f.write(f"\n[controller]\nlead_s = {TEST_LEAD_S}\n")
    return p


@pytest.fixture
def state_dir(tmp_path: Path) -> Path:
    d = tmp_path / "state"
    d.mkdir()
    return d


def make_controller(config_path: Path, state_dir: Path, connect: bool = True, zero: bool = True
                    ) -> MachineController:
    ctl = MachineController(config_path, state_dir=state_dir, worker_mode="manual")
    if connect:
        assert ctl.connect_bus(), "connect failed"
        if zero:
            assert ctl.set_machine_zero_here()
    return ctl


@pytest.fixture
def ctl(qapp, config_path: Path, state_dir: Path) -> Iterator[MachineController]:
    c = make_controller(config_path, state_dir)
    yield c
    c.shutdown()


def refused_load(c: MachineController, text: str, reason: str) -> tuple[int, int, str, str]:
    """``text`` is refused at load with ``reason`` in what the controller says; the program's
    one issue as (line, column, message), what the Program page marks, and the whole reason."""
    errors: list = []
    c.programErrors.connect(errors.append)
    r = c.load_program(text, wait=True)
    assert not r and reason in r.reason, r
    (issue,) = errors[-1]
    return issue.line, issue.col, issue.message, r.reason


def run_to_idle(c: MachineController, timeout_s: float = 20.0) -> None:
    assert c.run_until(lambda: c.state is MachineState.IDLE and c.worker.buffer_level() == 0, timeout_s), \
        f"not idle after {timeout_s} s: {c.state} {c.state_reason}"


def trace(c: MachineController) -> dict[str, np.ndarray]:
    path = c.tracking.trace_path
    assert path, "no trace saved"
    with np.load(path) as z:
        return {k: z[k] for k in z.files}
