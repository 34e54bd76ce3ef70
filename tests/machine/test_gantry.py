"""A gantry through the real controller on simulated drives (manual clock): the shipped gantry
mill's Y on two drives, each side homing to its own switch. The DRO shows one Y; homing
squares the two sides to their switches' offset; programs move both as one; a side that
stops while the gantry moves stops the machine with the gantry's alarm; the configuration
refuses what cannot work, at its line."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest

from app.machine.config import config_to_toml, load_config
from app.machine.errors import ConfigError
from app.machine.model import MachineState
from ethercat.worker import HomingStep
from resources import shipped_machine
from tests.machine.conftest import TEST_LEAD_S, make_controller, run_to_idle

GANTRY = shipped_machine("gantry_mill").read_text(encoding="utf-8")
SECOND = 3                   # the loop's drive of Y's second side (after X, Y, Z)
SQUARE_OFFSET = 0.4          # its switch sits this much further (gantry_offset - offset)


def _config(tmp_path: Path, text: str = GANTRY) -> Path:
    p = tmp_path / "machine.toml"
    p.write_text(text + f"\n[controller]\nlead_s = {TEST_LEAD_S}\n", encoding="utf-8")
    return p


def _drives(c) -> np.ndarray:  # type: ignore[no-untyped-def]
    """Every drive's actual position as the loop reads it (Y's second side included)."""
    return np.asarray(c.worker.snapshot().actual_position, dtype=float)


def test_the_gantry_homes_square_shows_one_axis_and_moves_as_one(qapp, tmp_path: Path, state_dir: Path
                                                                  ) -> None:
    """Home all: the two sides latch their own switches and the second side squares to the
    switches' offset (its step shown); the DRO has X, Y, Z and Y homed at 0; a program's move
    of Y moves both drives by the same amount, the pair's offset kept to a count."""
    c = make_controller(_config(tmp_path), state_dir, zero=False)
    try:
        assert len(c.machine_position) == 3
        steps: list[HomingStep] = []
        told: set[str] = set()
        c.poller.on_poll(lambda snap: steps.append(snap.homing_steps[1]))
        c.stateChanged.connect(lambda _state, reason: told.add(reason))
        assert c.home_all()
        assert c.run_until(lambda: c.state is MachineState.IDLE and all(c.homed), 120)
        assert HomingStep.SQUARE in steps
        assert any("Y squaring the gantry" in t for t in told), told
        snap = c.worker.snapshot()
        latched = snap.home_latched
        want = latched[SECOND] - latched[1] - SQUARE_OFFSET
        raw = _drives(c)
        assert abs((raw[SECOND] - raw[1]) - want) <= 1e-4
        # the simulated switches are at 195 and 195.4 in both drives' own counts: square is 0.4
        # apart less 0.4, within the latches' count each
        assert abs(want) <= 2e-4
        assert c.machine_position == pytest.approx((0.0, 0.0, 0.0), abs=1e-9)
        c.load_program("G90 G1 Y-60 F3000\nM2\n", wait=True)
        assert c.cycle_start()
        run_to_idle(c, 60)
        raw2 = _drives(c)
        assert c.machine_position[1] == pytest.approx(-60.0, abs=1e-4)
        assert raw2[1] - raw[1] == pytest.approx(-60.0, abs=1e-4)
        assert abs((raw2[SECOND] - raw2[1]) - want) <= 1e-4
        assert not [a for a in c.alarms if a.code.startswith("gantry")]
    finally:
        c.shutdown()


def test_a_side_that_stops_while_moving_stops_the_machine_with_the_gantrys_alarm(qapp, tmp_path: Path,
                                                                                 state_dir: Path) -> None:
    """Y's second drive jams half-way through a move: within a few cycles of the sides being
    0.2 mm apart both stop (quick stop), the machine goes to ALARM and the operator reads which
    gantry and by how much; Y stands short of its target."""
    c = make_controller(_config(tmp_path), state_dir)
    try:
        c.load_program("G90 G1 Y-80 F3000\nM2\n", wait=True)
        assert c.cycle_start()
        assert c.run_until(lambda: c.machine_position[1] < -30.0, 30)
        c.worker.inject("jam", SECOND)
        assert c.run_until(lambda: c.state is MachineState.ALARM, 10)
        text = " ".join(a.cause for a in c.alarms)
        assert "gantry Y: its drives Y and Y2" in text and "window 0.2" in text, text
        here = c.machine_position[1]
        c.run_until(lambda: False, 0.3)
        assert c.machine_position[1] == pytest.approx(here, abs=0.05)
        assert here > -79.0
    finally:
        c.shutdown()


def test_the_gantry_keys_are_read_written_back_and_refused_at_their_line(tmp_path: Path) -> None:
    cfg = load_config(_config(tmp_path))
    y = cfg.machine.axes[1]
    assert (y.gantry_drive, y.gantry_direction, y.gantry_skew_window) == (8, -1, 0.2)
    assert cfg.wiring.homing_of("Y").second_offset == pytest.approx(195.4)
    again = tmp_path / "again.toml"
    again.write_text(config_to_toml(cfg), encoding="utf-8")
    back = load_config(again)
    assert back.machine.axes == cfg.machine.axes and back.wiring.homing == cfg.wiring.homing
    # the second drive is a slave of its own
    text = GANTRY.replace("gantry_drive = 8 ", "gantry_drive = 2 ")
    with pytest.raises(ConfigError, match="slave 2 already drives an axis") as exc:
        load_config(_config(tmp_path, text))
    line = next(k for k, s in enumerate(text.splitlines(), 1) if s.startswith("gantry_drive = 2"))
    assert f":{line}:" in str(exc.value)
    # the drive's own homing homes one drive at a time
    text = GANTRY.replace('method = "switches"', 'method = "drive"')
    with pytest.raises(ConfigError, match="a gantry's two drives home together"):
        load_config(_config(tmp_path, text))
    # a second side's switch on an axis with one drive
    text = GANTRY.replace('home_Y = "5:7"', 'home_Y = "5:7"\nhome2_X = "4:7"')
    with pytest.raises(ConfigError, match="axis X has one drive"):
        load_config(_config(tmp_path, text))


def test_a_gantry_is_homed_again_after_connecting(qapp, tmp_path: Path, state_dir: Path) -> None:
    """The two sides may have been racked while the power was off: a homed gantry axis loses
    its homed state when the bus connects (a warning says why); the other axes keep theirs."""
    path = _config(tmp_path)
    c = make_controller(path, state_dir)
    assert all(c.homed)
    c.shutdown()
    c = make_controller(path, state_dir, zero=False)
    try:
        assert c.homed == (True, False, True)
        (alarm,) = [a for a in c.alarms if a.code == "gantry_unhomed"]
        assert "gantry Y" in alarm.cause and "home it" in alarm.cause
    finally:
        c.shutdown()


def test_the_shipped_gantry_mill_is_the_xyz_mill_with_a_second_y_drive(tmp_path: Path) -> None:
    mill = load_config(shipped_machine("xyz_mill"))
    shutil.copyfile(shipped_machine("gantry_mill"), tmp_path / "g.toml")
    gantry = load_config(tmp_path / "g.toml")
    assert [a.name for a in gantry.machine.axes] == [a.name for a in mill.machine.axes]
    assert [a.gantry_drive for a in gantry.machine.axes] == [None, 8, None]


def test_the_second_sides_limit_switch_stops_the_gantry_and_only_a_jog_away_follows(
        qapp, tmp_path: Path, state_dir: Path) -> None:
    """Y2's own positive limit switch (its drive's 0x60FD bit 1 by default) trips while Y moves:
    the machine stops with the alarm naming Y2, the reset asks for the override, and then Y
    may only jog away from it, both sides together."""
    c = make_controller(_config(tmp_path), state_dir)
    try:
        c.load_program("G90 G1 Y40 F1200\nM2\n", wait=True)
        assert c.cycle_start()
        assert c.run_until(lambda: c.machine_position[1] > 5.0, 10)
        assert c.simulate_input("limit_pos2_Y", True)
        c.advance(0.05)
        assert c.state is MachineState.ALARM
        alarm = next(a for a in c.active_alarms if a.code == "limit_switch")
        assert "axis Y2 on its positive limit switch" in alarm.cause
        c.advance(0.5)
        r = c.reset()
        assert not r and "axis Y2 is on its positive limit switch: override limits" in r.reason
        assert c.override_limits(True) and c.reset()
        r = c.jog_increment("Y", 1.0, 1)
        assert not r and "may only jog away from it (Y-)" in r.reason
        before = _drives(c)
        assert c.jog_increment("Y", 1.0, -1)
        run_to_idle(c)
        after = _drives(c)
        assert after[1] - before[1] == pytest.approx(-1.0, abs=1e-6)
        assert after[SECOND] - before[SECOND] == pytest.approx(-1.0, abs=1e-6)
    finally:
        c.shutdown()


def test_the_controller_sees_the_machines_axes_and_diagnostics_every_drive(qapp, tmp_path: Path,
                                                                           state_dir: Path) -> None:
    """``machine_view``: the per-axis fields of the loop's snapshot cut to X, Y, Z (Y homed once
    both its sides are, showing its second side's step while that squares); the per-drive
    fields keep all four drives."""
    import dataclasses

    from app.machine.infra.drives import machine_view

    c = make_controller(_config(tmp_path), state_dir)
    try:
        full = c.worker.snapshot()
        view = machine_view(full, c.worker)
        assert full.axis_names == ("X", "Y", "Z", "Y2")
        assert len(full.actual_position) == 4 and len(view.actual_position) == 3
        assert view.actual_position[1] == full.actual_position[1]
        for field in ("rmse", "mse", "max_abs", "window_rmse", "window_mse"):
            assert len(getattr(view.tracking, field)) == 3, field
        assert len(view.probe.position) == 3 and len(view.home_latched) == 3
        assert view.drive_states == full.drive_states and len(view.gantry_skew) == 4
        half = dataclasses.replace(full, homed=(True, True, True, False),
                                   homing_steps=(HomingStep.IDLE, HomingStep.DONE, HomingStep.IDLE,
                                                 HomingStep.SQUARE))
        view = machine_view(half, c.worker)
        assert view.homed == (True, False, True) and view.homing_steps[1] is HomingStep.SQUARE
        done = dataclasses.replace(half, homed=(True,) * 4, homing_steps=(HomingStep.DONE,) * 4)
        assert machine_view(done, c.worker).homed == (True, True, True)
        # the trace too: the axes' columns
        c.load_program("G91 G1 Y2 F600\nM2\n", wait=True)
        assert c.cycle_start()
        run_to_idle(c)
        c.advance(0.05)
        trace = c.drives.drain_trace()
        assert trace is not None and trace.reference.shape[1] == 3 and trace.actual.shape[1] == 3
    finally:
        c.shutdown()
