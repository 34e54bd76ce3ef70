"""The handwheel through the real controller on simulated drives (manual clock): it moves the
homed axis given to it in IDLE only, every other motion takes the axis from it first, the
soft limit, the door, E-stop and a jumping counter stop it, the pendant's selector chooses
when wired, the configuration is checked at its line, and the scenario runner turns it."""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np
import pytest

from app.machine.config import config_from_dict, config_to_toml, load_config
from app.machine.controller import MachineController
from app.machine.errors import ConfigError, MachineError
from app.machine.model import MachineState, Severity
from app.machine.program.scenario import ScenarioRunner, parse_op
from ethercat.worker import WheelState
from resources import shipped_machine
from tests.machine.conftest import make_controller, run_to_idle

MILL = shipped_machine("xyz_mill").read_text(encoding="utf-8")
COUNT_MM = 1e-4                       # one drive count


def _config(tmp_path: Path, text: str) -> Path:
    p = tmp_path / "machine.toml"
    p.write_text(text, encoding="utf-8")
    return p


def _rest(c: MachineController, seconds: float = 1.5) -> None:
    c.advance(seconds)


def _x(c: MachineController) -> float:
    return float(c.reference_position[0])


def test_the_wheel_moves_the_homed_axis_given_to_it_by_its_steps(ctl: MachineController) -> None:
    _rest(ctl, 0.1)
    assert ctl.select_handwheel("X") and ctl.set_handwheel_step(1)          # x10: 0.01 mm a detent
    _rest(ctl, 0.1)
    assert ctl.handwheel.live and ctl.handwheel.axis == "X" and ctl.handwheel.step == 0.01
    assert ctl.turn_handwheel(4 * 100)                                        # 100 detents
    _rest(ctl)
    assert _x(ctl) == pytest.approx(1.0, abs=COUNT_MM)
    assert ctl.turn_handwheel(-4 * 30)                                        # 30 back at x10
    _rest(ctl)
    assert ctl.set_handwheel_step(2) and ctl.turn_handwheel(4 * 2)           # 2 on at x100
    _rest(ctl)
    assert _x(ctl) == pytest.approx(1.0 - 0.3 + 0.2, abs=COUNT_MM)
    assert ctl.machine_position[1:] == pytest.approx((0.0, 0.0), abs=COUNT_MM)


def test_it_is_not_live_unhomed_running_or_with_the_door_open(qapp, config_path: Path,
                                                               state_dir: Path) -> None:
    c = make_controller(config_path, state_dir, zero=False)
    try:
        _rest(c, 0.1)
        assert c.select_handwheel("Y")
        _rest(c, 0.1)
        assert not c.handwheel.live and c.handwheel.why == "axis Y is not homed: home it first"
        c.turn_handwheel(400)
        _rest(c)
        assert float(c.reference_position[1]) == 0.0
        assert c.set_machine_zero_here()
        _rest(c, 0.1)
        assert c.handwheel.live
        # a block running: the wheel lets go, and its counts move nothing meanwhile
        assert c.mdi("G1 X5 F600")
        c.turn_handwheel(400)
        c.advance(0.2)
        assert c.state is MachineState.RUNNING and not c.handwheel.live and c.handwheel.axis == ""
        run_to_idle(c)
        _rest(c)
        assert float(c.reference_position[1]) == 0.0 and _x(c) == pytest.approx(5.0, abs=1e-9)
        # the door open: at the setup speed (2 mm/s on the mill)
        assert c.select_handwheel("Y") and c.set_handwheel_step(2)
        assert c.simulate_input("door_closed", False)
        _rest(c, 0.1)
        assert c.handwheel.live
        rows: list[np.ndarray] = []
        c.add_trace_sink(lambda _cycles, reference, _actual, _lines: rows.append(reference[:, 1].copy()))
        c.turn_handwheel(4 * 20)                                              # 2 mm
        _rest(c, 2.0)
        ref = np.concatenate(rows)
        assert float(np.abs(np.diff(ref)).max()) / 0.001 <= 2.0 * (1 + 1e-9)
        assert float(ref[-1]) == pytest.approx(2.0, abs=COUNT_MM)
    finally:
        c.shutdown()


def test_no_wheel_with_the_door_open_where_jogging_needs_it_closed(qapp, tmp_path: Path,
                                                                   state_dir: Path) -> None:
    text = MILL.replace("door_open_jog_mm_s = 2.0", "door_open_jog_mm_s = 0.0")
    c = make_controller(_config(tmp_path, text), state_dir)
    try:
        assert c.select_handwheel("X") and c.simulate_input("door_closed", False)
        _rest(c, 0.1)
        assert not c.handwheel.live
        assert c.handwheel.why == "the door is open: the handwheel needs it closed on this machine"
    finally:
        c.shutdown()


def test_a_jog_waits_for_the_wheel_to_stand_and_gives_it_back_mdi_takes_it(ctl: MachineController) -> None:
    assert ctl.select_handwheel("X") and ctl.set_handwheel_step(2)
    _rest(ctl, 0.1)
    ctl.turn_handwheel(40 * 4)                                                # 4 mm: still moving
    ctl.advance(0.1)
    r = ctl.jog_increment("Z", 1.0, -1)
    assert not r and r.reason == "the handwheel is still moving axis X: let it stand, then try again"
    _rest(ctl, 2.0)
    x = _x(ctl)
    assert ctl.jog_increment("Z", 1.0, -1)
    run_to_idle(ctl)
    _rest(ctl, 0.2)
    assert _x(ctl) == x and float(ctl.reference_position[2]) == pytest.approx(-1.0, abs=1e-9)
    assert ctl.handwheel.live and ctl.handwheel.axis == "X"                   # given back after the jog
    assert ctl.mdi("G0 Z0")
    run_to_idle(ctl)
    _rest(ctl, 0.2)
    assert ctl.handwheel.axis == "" and not ctl.handwheel.live                # MDI leaves it off
    ctl.turn_handwheel(400)
    _rest(ctl)
    assert _x(ctl) == x


def test_it_stops_at_the_soft_limit(ctl: MachineController) -> None:
    assert ctl.mdi("G0 X249.8")
    run_to_idle(ctl)
    assert ctl.select_handwheel("X") and ctl.set_handwheel_step(2)
    _rest(ctl, 0.1)
    ctl.turn_handwheel(4 * 10)                                                # 1 mm asked, 0.2 left
    _rest(ctl, 2.0)
    assert _x(ctl) == pytest.approx(250.0, abs=COUNT_MM) and _x(ctl) <= 250.0 + 1e-9
    ctl.turn_handwheel(-4)
    _rest(ctl)
    assert _x(ctl) == pytest.approx(249.9, abs=COUNT_MM)


def test_e_stop_and_a_jumping_counter_leave_it_off_until_selected_again(ctl: MachineController) -> None:
    assert ctl.select_handwheel("X")
    _rest(ctl, 0.1)
    ctl.estop("test")
    _rest(ctl, 0.2)
    assert ctl.handwheel.axis == "" and not ctl.handwheel.live
    assert ctl.estop_release()
    ctl.reset()
    _rest(ctl, 0.2)
    assert ctl.state is MachineState.IDLE and ctl.handwheel.axis == ""
    x = _x(ctl)
    ctl.turn_handwheel(400)
    _rest(ctl)
    assert _x(ctl) == x
    # selected again: a counter that jumps moves nothing and is told as a warning
    assert ctl.select_handwheel("X")
    _rest(ctl, 0.1)
    terminal = ctl.config.wiring.terminal_index(7)
    ctl.drives.inject("encoder_add", terminal, 20_000)
    _rest(ctl, 0.5)
    assert _x(ctl) == x and ctl.handwheel.axis == "" and ctl.state is MachineState.IDLE
    (alarm,) = [a for a in ctl.active_alarms if a.code == "handwheel"]
    assert alarm.severity is Severity.WARNING and "jumped by 20000 counts" in alarm.cause
    assert ctl.worker.snapshot().handwheel_state == WheelState.OFF


PENDANT = MILL.replace('''[[bus.terminals]]
position = 7''', '''[[bus.terminals]]
position = 8
type = "EL1008"
name = "pendant"

[[bus.terminals]]
position = 7''').replace('''spindle_enable = "6:4"''', '''spindle_enable = "6:4"
jog_enable_X = "8:0"
jog_enable_Y = "8:1"
jog_scale_x10 = "8:2"
jog_scale_x100 = "8:3"''')


def test_the_pendants_selector_chooses_axis_and_step(qapp, tmp_path: Path, state_dir: Path) -> None:
    assert "jog_enable_X" in PENDANT
    c = make_controller(_config(tmp_path, PENDANT), state_dir)
    try:
        _rest(c, 0.1)
        assert c.handwheel.selector and c.handwheel.axis == ""
        r = c.select_handwheel("X")
        assert not r and "selector chooses" in r.reason
        assert c.simulate_input("jog_enable_Y", True) and c.simulate_input("jog_scale_x100", True)
        _rest(c, 0.1)
        assert c.handwheel.axis == "Y" and c.handwheel.step == 0.1 and c.handwheel.live
        c.turn_handwheel(8)
        _rest(c)
        assert float(c.reference_position[1]) == pytest.approx(0.2, abs=COUNT_MM)
        assert c.simulate_input("jog_enable_X", True)                          # two at once: none
        _rest(c, 0.1)
        assert c.handwheel.axis == "" and not c.handwheel.live
    finally:
        c.shutdown()


@pytest.mark.parametrize("change, message", [
    ("terminal = 7", "handwheel.terminal: slave 6 is a EL2008"),
    ("steps = [0.001, 0.01, 0.1]", "handwheel.steps: three steps (x1, x10, x100), not 2"),
    ('mode = "position"', "handwheel.mode"),
])
def test_a_wrong_handwheel_table_is_refused_at_its_line(tmp_path: Path, change: str, message: str) -> None:
    bad = {"terminal = 7": "terminal = 6", "steps = [0.001, 0.01, 0.1]": "steps = [0.001, 0.01]",
           'mode = "position"': 'mode = "fast"'}[change]
    text = MILL.replace(change, bad, 1)
    assert text != MILL
    line = text.splitlines().index(next(s for s in text.splitlines() if s.startswith(bad))) + 1
    with pytest.raises(ConfigError) as info:
        load_config(_config(tmp_path, text))
    assert message in str(info.value) and f":{line}" in str(info.value), str(info.value)


def test_the_handwheel_table_round_trips() -> None:
    cfg = config_from_dict(tomllib.loads(MILL.replace('mode = "position"', 'mode = "velocity"')))
    again = config_from_dict(tomllib.loads(config_to_toml(cfg)))
    assert again.wiring.handwheel == cfg.wiring.handwheel
    assert again.wiring.handwheel.mode.value == "velocity" and again.wiring.handwheel.terminal == 7


def test_the_scenario_runner_gives_and_turns_the_wheel(ctl: MachineController) -> None:
    ops = tuple(parse_op(t, f"s:{k}") for k, t in enumerate((
        '{"after_s": 0, "op": "handwheel", "axis": "Z"}',
        '{"after_s": 0, "op": "handwheel_step", "scale": 2}',
        '{"after_s": 0.1, "op": "mpg", "counts": -100}'), 1))
    runner = ScenarioRunner(ctl, ops, ctl.machine_time_s)
    for _ in range(100):
        runner.step()
        ctl.advance(0.033)
    assert runner.done and all(r["ok"] for r in runner.results), runner.results
    assert float(ctl.reference_position[2]) == pytest.approx(-2.5, abs=COUNT_MM)
    for text, why in (('{"after_s": 0, "op": "mpg", "counts": 1.5}', "counts must be a whole number"),
                      ('{"after_s": 0, "op": "handwheel_step", "scale": 3}', "scale must be 0"),
                      ('{"after_s": 0, "op": "handwheel"}', "handwheel needs")):
        with pytest.raises(MachineError, match=why):
            parse_op(text, "s:1")


def test_a_motion_right_after_the_wheel_starts_where_the_wheel_left_the_axis(ctl: MachineController) -> None:
    """The wheel moves X between two polls (the loop's cycles run, the panel has not read the
    positions since): a jog of Z pressed then reads them again before it is planned, so X
    stays where the wheel left it and no set-point jumps."""
    assert ctl.select_handwheel("X") and ctl.set_handwheel_step(2)
    _rest(ctl, 0.1)
    rows: list[np.ndarray] = []
    ctl.add_trace_sink(lambda _c, reference, _a, _l: rows.append(reference.copy()))
    terminal = ctl.config.wiring.terminal_index(7)
    ctl.drives.inject("encoder_add", terminal, 8)              # 0.2 mm, the loop only
    ctl.drives.step(1500)                                      # at rest, no poll meanwhile
    assert ctl.machine_position[0] == 0.0                      # what the panel last read
    assert ctl.jog_increment("Z", 1.0, -1)
    run_to_idle(ctl)
    _rest(ctl, 0.2)
    assert _x(ctl) == pytest.approx(0.2, abs=1e-12)
    ref = np.concatenate(rows)
    assert float(np.abs(np.diff(ref[:, 0])).max()) < 0.01        # no step of X between two samples


def test_giving_the_wheel_another_axis_while_it_moves_one_waits_for_it_to_stand(
        ctl: MachineController) -> None:
    assert ctl.select_handwheel("X") and ctl.set_handwheel_step(2)
    _rest(ctl, 0.1)
    ctl.turn_handwheel(40 * 4)
    ctl.advance(0.15)                                                          # X moving
    assert ctl.select_handwheel("Y")
    ctl.advance(0.05)
    assert not ctl.handwheel.live and ctl.handwheel.axis == "Y"
    assert ctl.run_until(lambda: ctl.handwheel.live, 5.0)                     # once X stands
    x = _x(ctl)
    ctl.turn_handwheel(4 * 3)
    _rest(ctl)
    assert float(ctl.reference_position[1]) == pytest.approx(0.3, abs=COUNT_MM) and _x(ctl) == x
