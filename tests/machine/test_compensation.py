"""Leadscrew compensation through the real controller on simulated drives (manual clock): the
axis' keys and its table are read and checked with the configuration (errors at the key's line
or the table's), a compensated axis moves with the share of its limits its reserve leaves, the
compensation is on only while the axis is homed, the drives get nominal + correction within the
axis' own limits, and the DRO stays nominal."""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np
import pytest

from app.machine.config import config_from_dict, config_to_toml, load_config
from app.machine.controller import MachineController
from app.machine.errors import ConfigError
from planner.core.limits import LimitSet
from resources import shipped_machine
from tests.machine.conftest import TEST_LEAD_S, make_controller, run_to_idle

MILL = shipped_machine("xyz_mill").read_text(encoding="utf-8")
X_KEYS = "following_error_window = 1.0\n"          # the end of X's table in the shipped mill
X_RATED = (100.0, 2000.0, 40000.0)                  # X's v_max, a_max, j_max there
TS = 0.001


def _config(tmp_path: Path, x_lines: str, table: str | None = None) -> Path:
    """The mill with ``x_lines`` in X's table, its path limits as high as X's own (so that X's
    limits govern its moves)."""
    path_limits = "a_max_mm_s2 = 1000.0\nj_max_mm_s3 = 10000.0\nrapid_mm_s = 50.0\n"
    assert MILL.count(X_KEYS) >= 1 and MILL.count(path_limits) == 1
    text = MILL.replace(X_KEYS, X_KEYS + x_lines, 1).replace(
        path_limits, "a_max_mm_s2 = 2000.0\nj_max_mm_s3 = 40000.0\nrapid_mm_s = 100.0\n")
    text += f"\n[controller]\nlead_s = {TEST_LEAD_S}\n"
    if table is not None:
        (tmp_path / "x.comp").write_text(table, encoding="utf-8")
    p = tmp_path / "machine.toml"
    p.write_text(text, encoding="utf-8")
    return p


def _line_of(path: Path, key: str) -> int:
    return next(k for k, line in enumerate(path.read_text().splitlines(), 1) if line.startswith(key))


# ------------------------------------------------------------------------------ configuration
def test_backlash_and_a_table_are_read_round_trip_and_reserve_their_share(tmp_path: Path) -> None:
    """``backlash`` and a ``comp_file`` beside the configuration (types 0 and 1) are read with
    it and written back as they were; the axis' motion limits are (1 - comp_reserve) of its
    own, the planner's limits follow, and an axis without compensation keeps all of its."""
    cfg = load_config(_config(tmp_path, "backlash = 0.02\ncomp_reserve = 0.2\n"))
    x, y = cfg.machine.axes[:2]
    assert x.compensated and not y.compensated
    assert (x.v_motion, x.a_motion, x.j_motion) == pytest.approx(tuple(0.8 * r for r in X_RATED))
    assert (y.v_motion, y.a_motion) == (y.v_max, y.a_max)
    lim = LimitSet.from_machine(cfg.machine)
    assert lim.a_axis[0] == pytest.approx(0.8 * X_RATED[1]) and lim.a_axis[1] == y.a_max
    (spec,) = cfg.compensation
    assert spec.axis == 0 and spec.comp.forward(3.0) == 0.01 and spec.comp.reverse(3.0) == -0.01
    assert spec.take_up == pytest.approx(tuple(0.2 * r for r in X_RATED))
    again = config_from_dict(tomllib.loads(config_to_toml(cfg)), str(tmp_path / "machine.toml"))
    assert again.machine == cfg.machine and again.compensation == cfg.compensation

    table = "-250 -250.004 -249.990\n0 0.001 0.012\n250 250.006 250.018\n"
    cfg = load_config(_config(tmp_path, 'comp_file = "x.comp"\ncomp_file_type = 0\n', table))
    (spec,) = cfg.compensation
    assert spec.comp.nominal == (-250.0, 0.0, 250.0)
    assert spec.comp.forward.y == pytest.approx((0.004, -0.001, -0.006))
    again = config_from_dict(tomllib.loads(config_to_toml(cfg)), str(tmp_path / "machine.toml"))
    assert again.compensation == cfg.compensation and again.machine.axes[0].comp_file == "x.comp"


def test_a_bad_table_or_key_is_refused_at_its_line(tmp_path: Path) -> None:
    """The table's own problem names the table's file and line; a missing file, backlash beside
    a table and a table too steep for the reserve name the configuration's line of the key."""
    p = _config(tmp_path, 'comp_file = "x.comp"\ncomp_file_type = 1\n', "0 0 0\n10 0.001 0.002\n5 0 0\n")
    with pytest.raises(ConfigError) as err:
        load_config(p)
    assert f"{tmp_path / 'x.comp'}:3: nominal 5 is not above 10 on line 2" in str(err.value)

    p = _config(tmp_path, 'comp_file = "none.comp"\n')
    with pytest.raises(ConfigError) as err:
        load_config(p)
    assert f"machine.toml:{_line_of(p, 'comp_file')}: axes[0].comp_file: " in str(err.value)
    assert "none.comp: no such file (axis X)" in str(err.value)

    p = _config(tmp_path, 'backlash = 0.01\ncomp_file = "x.comp"\n', "0 0 0\n")
    with pytest.raises(ConfigError) as err:
        load_config(p)
    assert f"machine.toml:{_line_of(p, 'backlash')}: axes[0].backlash: backlash and comp_file" \
        in str(err.value)

    steep = "".join(f"{x} {0.3 * (x % 2)} {0.3 * (x % 2)}\n" for x in range(-250, 251))
    p = _config(tmp_path, 'comp_file = "x.comp"\ncomp_file_type = 1\n', steep)
    with pytest.raises(ConfigError) as err:
        load_config(p)
    assert f"machine.toml:{_line_of(p, 'comp_file')}: axes[0].comp_file: x.comp: at full speed" \
        in str(err.value)
    assert "raise comp_reserve" in str(err.value)


# ------------------------------------------------------------------------------ on the machine
def _spy(c: MachineController) -> list[float]:
    """Every position the loop sends X's drive, one per cycle (what ``_send_ref`` computed)."""
    loop = c.worker._loop
    assert loop is not None
    sent: list[float] = []
    original = loop._send_ref

    def send(bus, row):  # type: ignore[no-untyped-def]
        original(bus, row)
        sent.append(float(loop.cmd[0]))

    loop._send_ref = send  # type: ignore[method-assign]
    return sent


def _sampled(y: np.ndarray) -> tuple[float, float, float]:
    v = np.diff(y) / TS
    a = np.diff(v) / TS
    j = np.diff(a) / TS
    return tuple(float(np.abs(x).max(initial=0.0)) for x in (v, a, j))  # type: ignore[return-value]


def test_on_while_homed_the_drive_gets_nominal_plus_backlash_and_the_dro_stays_nominal(
        qapp, tmp_path: Path) -> None:
    """Unhomed, X's drive gets its set-points as they are. Homed, reversing moves at full speed
    put X's drive at nominal +- half the backlash by the direction of the last move, every sample
    within X's own limits; the DRO reads the nominal positions; E-stop and reset keep the
    compensation with the homed state, and nothing jumps."""
    state = tmp_path / "state"
    state.mkdir()
    c = make_controller(_config(tmp_path, "backlash = 0.05\n"), state, zero=False)
    try:
        c.advance(0.2)
        snap = c.worker.snapshot()
        assert not snap.compensation_on[0] and snap.compensation[0] == 0.0
        sent = _spy(c)
        assert c.set_machine_zero_here()
        c.advance(0.5)
        snap = c.worker.snapshot()
        assert snap.compensation_on[0] and not any(snap.compensation_on[1:])
        assert snap.compensation[0] == 0.0               # X has not moved yet: no direction, none
        for target in (40.0, 5.0, 60.0, 59.9, 60.2):
            assert c.mdi(f"G0 X{target:g}")
            run_to_idle(c)
            c.advance(0.3)
            up = target > 5.0 and target != 59.9
            loop = c.worker._loop
            assert loop is not None
            half = 0.025 if up else -0.025
            assert float(loop.cmd[0]) == pytest.approx(float(loop.ref[0]) + half, abs=1e-12)
            assert c.machine_position[0] == pytest.approx(target, abs=2e-4), target
        v, a, j = _sampled(np.array(sent))
        assert v <= X_RATED[0] * (1 + 1e-9) and a <= X_RATED[1] * (1 + 1e-9), (v, a)
        assert j <= X_RATED[2] * (1 + 1e-6), j
        assert a > 0.7 * X_RATED[1] and v > 0.85 * X_RATED[0]        # moves near what motion may
        before = c.machine_position[0]
        assert c.estop("test")
        c.advance(0.1)
        assert c.estop_release()
        c.advance(0.5)
        assert c.homed[0] and c.worker.snapshot().compensation_on[0]
        assert c.machine_position[0] == pytest.approx(before, abs=2e-4)       # nothing jumped
    finally:
        c.shutdown()


def test_homing_to_the_switches_latches_through_the_compensation_and_switches_it_on_after(
        qapp, tmp_path: Path) -> None:
    """Homed to its switch with backlash configured: every homing latches the switch with the
    correction of the latch's direction, whatever X did before, so X ends at its home position
    (0) with its drive at the same place both times (to a count): the first homing from
    power-up, and a second one after X was left having moved up."""
    state = tmp_path / "state"
    state.mkdir()
    c = make_controller(_config(tmp_path, "backlash = 0.05\n"), state, zero=False)
    try:
        ends, drive = [], []
        for k in range(2):
            if k:
                for block in ("G0 X-20", "G0 X-10"):              # left having moved up
                    assert c.mdi(block)
                    run_to_idle(c)
            assert c.home_all()
            assert c.run_until(lambda: all(c.homed) and c.state.value == "idle", 120)
            c.advance(0.5)
            snap = c.worker.snapshot()
            assert snap.compensation_on[0]
            loop = c.worker._loop
            assert loop is not None
            # the last move to home (0) came from the switch at +245: down
            assert float(loop.cmd[0]) == pytest.approx(float(loop.ref[0]) - 0.025, abs=1e-12)
            ends.append(c.machine_position[0])
            drive.append(float(loop.cmd[0]))
        assert ends == pytest.approx([0.0, 0.0], abs=2e-4)
        assert drive[1] == pytest.approx(drive[0], abs=1e-4)
    finally:
        c.shutdown()
