"""M66 run on the machine (real CyclicWorker + SimBus in manual mode; the shipped XYZ mill's
input P0 is bit 17 of X's drive): the motion waits at rest, #5399 takes what the input read
(-1 after the timeout), and the program goes on from there with it."""

from __future__ import annotations

import pytest

from app.machine.controller import MachineController
from app.machine.model import MachineState
from tests.machine.conftest import run_to_idle

WAIT_HIGH = "G21 G90\nG0 X5\nM66 P0 L3 Q2\n(DEBUG,read #5399)\nG0 X[10 + #5399 * 10]\nM2\n"
BIT = 1 << 17


def _start(ctl: MachineController, text: str) -> list[str]:
    said: list[str] = []
    ctl.message.connect(said.append)
    r = ctl.load_program(text, wait=True)
    assert r, r.reason
    assert ctl.cycle_start(wait=True)
    return said


def _x_drive(ctl: MachineController):
    return ctl.worker._loop.bus.models[0]                      # the simulated drive of X


def test_the_motion_waits_for_the_input_and_goes_on_with_its_value(ctl: MachineController) -> None:
    said = _start(ctl, WAIT_HIGH)
    assert ctl.run_until(lambda: ctl.waiter.wait is not None, 10.0)
    waiting = "M66 (line 3): waiting for input P0 (spare) to read 1, 2 s at most"
    assert any(m.startswith(waiting) for m in said)
    ctl.advance(1.0)
    assert ctl.state is MachineState.RUNNING and ctl.machine_position[0] == pytest.approx(5.0, abs=1e-6)
    _x_drive(ctl).digital_inputs |= BIT
    run_to_idle(ctl)
    assert ctl.last_run is not None and ctl.last_run.completed
    assert "read 1.000000" in said
    assert ctl.machine_position[0] == pytest.approx(20.0, abs=1e-6)


def test_a_timeout_reads_minus_one(ctl: MachineController) -> None:
    said = _start(ctl, WAIT_HIGH)
    run_to_idle(ctl)
    assert "read -1.000000" in said
    assert any("timed out after 2 s" in m for m in said)
    assert ctl.machine_position[0] == pytest.approx(0.0, abs=1e-6)
    assert ctl.last_run is not None and ctl.last_run.completed
    assert ctl.last_run.cycle_time_s >= 2.0                # the wait is part of the run


def test_a_rise_needs_the_input_low_first(ctl: MachineController) -> None:
    _x_drive(ctl).digital_inputs |= BIT                     # high already: a rise is still to come
    said = _start(ctl, "G21 G90\nM66 P0 L1 Q3\n(DEBUG,read #5399)\nG0 X1\nM2\n")
    assert ctl.run_until(lambda: ctl.waiter.wait is not None, 10.0)
    ctl.advance(0.5)
    assert ctl.waiter.wait is not None
    _x_drive(ctl).digital_inputs &= ~BIT
    ctl.advance(0.2)
    _x_drive(ctl).digital_inputs |= BIT
    run_to_idle(ctl)
    assert "read 1.000000" in said and ctl.machine_position[0] == pytest.approx(1.0, abs=1e-6)


def test_m66_in_mdi_is_refused_with_the_reason(ctl: MachineController) -> None:
    r = ctl.mdi("M66 P0 L0")
    assert not r and "an MDI block keeps no value for the next one" in r.reason


def test_a_stop_while_waiting_ends_the_wait(ctl: MachineController) -> None:
    _start(ctl, WAIT_HIGH)
    assert ctl.run_until(lambda: ctl.waiter.wait is not None, 10.0)
    assert ctl.stop()
    run_to_idle(ctl)
    assert ctl.waiter.wait is None and ctl.machine_position[0] == pytest.approx(5.0, abs=1e-6)
    assert ctl.last_run is not None and not ctl.last_run.completed
