"""A spindle on its own CiA 402 drive through the real controller on simulated drives (manual
clock): ``[spindle]`` read and checked at its line, S x override sent to the drive, the first
feed move after M3 waiting until the speed the drive reads is in the band, a spindle that loses
speed in the cut holding the program with an alarm, its drive's fault stopping the motion, and
E-stop stopping it."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

import numpy as np
import pytest

from app.machine.config import config_from_dict, config_to_toml, load_config
from app.machine.controller import MachineController
from app.machine.errors import ConfigError, MachineError
from app.machine.model import MachineState
from app.machine.program.scenario import ScenarioRunner, parse_op
from ethercat.worker import SpindleState
from resources import shipped_machine
from tests.machine.conftest import TEST_LEAD_S, make_controller, run_to_idle

MILL = shipped_machine("xyz_mill").read_text(encoding="utf-8")
SPINDLE = "[spindle]\ndrive = 8\naccel_rpm_s = 4000\nat_speed_pct = 5\nspeed_loss_s = 0.3\n"


def _config(tmp_path: Path, spindle: str = SPINDLE) -> Path:
    p = tmp_path / "machine.toml"
    p.write_text(MILL + f"\n{spindle}\n[controller]\nlead_s = {TEST_LEAD_S}\n", encoding="utf-8")
    return p


@pytest.fixture
def sctl(qapp, tmp_path: Path):  # type: ignore[no-untyped-def]
    state = tmp_path / "state"
    state.mkdir()
    c = make_controller(_config(tmp_path), state)
    yield c
    c.shutdown()


def test_the_spindle_section_is_read_round_trip_and_checked_at_its_line(tmp_path: Path) -> None:
    cfg = load_config(_config(tmp_path))
    s = cfg.spindle
    assert (s.drive, s.mode, s.accel_rpm_s, s.speed_loss_s) == (8, 9, 4000.0, 0.3)
    assert s.spec is not None and s.spec.position == 8
    assert s.spec.velocity_per_rpm == pytest.approx(10_000 / 60)
    again = config_from_dict(tomllib.loads(config_to_toml(cfg)), str(tmp_path / "machine.toml"))
    assert again.spindle == cfg.spindle
    assert load_config(shipped_machine("xyz_mill")).spindle.spec is None       # left out: the bits
    p = _config(tmp_path, "[spindle]\ndrive = 7\n")                             # the handwheel's EL5101
    with pytest.raises(ConfigError) as err:
        load_config(p)
    line = p.read_text().splitlines().index("drive = 7") + 1
    assert f"machine.toml:{line}: spindle.drive: slave 7 is a EL5101" in str(err.value)
    p = _config(tmp_path, "[spindle]\ndrive = 8\nmode = 8\n")
    with pytest.raises(ConfigError, match="spindle.mode"):
        load_config(p)


def test_the_spindle_drive_may_have_its_own_bus_drives_table_with_a_velocity_mapping(tmp_path: Path) -> None:
    """A ``[[bus.drives]]`` table at the spindle's position (its identity, start-up SDOs and a
    mapping of its own: a velocity one) is read, and reaches the bus as that drive's setup; a
    table at a position that is no drive's is refused naming the axes' and the spindle's."""
    table = ('\n[[bus.drives]]\nposition = 8\nmapping = "write"\n'
             'rx = ["0x6040:0:16", "0x60FF:0:32", "0x6060:0:8"]\n'
             'tx = ["0x6041:0:16", "0x606C:0:32", "0x6061:0:8", "0:0:8"]\n')
    cfg = load_config(_config(tmp_path, SPINDLE + table))
    (d,) = [d for d in cfg.bus.drives if d.position == 8]
    setup = d.setup()
    assert setup.mapping is not None and setup.mapping.velocity
    assert [e.index for e in setup.mapping.rx] == [0x6040, 0x60FF, 0x6060]
    p = _config(tmp_path, SPINDLE + table.replace("position = 8", "position = 9"))
    with pytest.raises(ConfigError, match=r"9 is not the drive of any axis \(\[0, 1, 2\]\) or the "
                                          r"spindle \(8\)"):
        load_config(p)


def _record(c: MachineController, seconds: float, step_s: float = 0.005) -> dict[str, np.ndarray]:
    rows = []
    for _ in range(int(round(seconds / step_s))):
        c.advance(step_s)
        s = c.worker.snapshot()
        rows.append((float(s.time_s), float(s.reference_position[0]), s.spindle_rpm_command,
                     s.spindle_rpm_actual))
    a = np.array(rows)
    return {"t": a[:, 0], "x": a[:, 1], "cmd": a[:, 2], "rpm": a[:, 3]}


def test_the_first_feed_move_waits_until_the_drive_reads_the_speed(sctl: MachineController) -> None:
    """M3 S6000 then a feed move: the drive is commanded 6,000 rpm (ramped at 4,000 rpm/s), and X
    does not move before the speed read is within 5 % of it; the override scales the speed sent."""
    c = sctl
    x0 = float(c.reference_position[0])
    assert c.mdi("M3 S6000 G1 X10 F600")
    rec = _record(c, 3.0)
    moving = np.flatnonzero(np.abs(rec["x"] - x0) > 1e-9)
    assert len(moving) > 0
    first = int(moving[0])
    assert rec["rpm"][first] >= 0.95 * 6000 and rec["rpm"][:first].min() < 0.95 * 6000
    assert rec["t"][first] - rec["t"][0] >= 6000 / 4000 * 0.95     # the ramp took its time
    run_to_idle(c)
    assert c.spindle.on and c.worker.snapshot().spindle_state == SpindleState.RUNNING
    assert c.set_spindle_override(120)
    c.advance(1.0)
    s = c.worker.snapshot()
    assert s.spindle_rpm_command == pytest.approx(7200.0)
    assert s.spindle_rpm_actual == pytest.approx(7200, abs=2)
    assert c.mdi("M4")
    c.advance(4.0)
    assert c.worker.snapshot().spindle_rpm_actual == pytest.approx(-7200, abs=2)
    assert c.mdi("M5")
    c.advance(3.0)
    s = c.worker.snapshot()
    assert s.spindle_state == SpindleState.OFF and abs(s.spindle_rpm_actual) < 1.0


def test_an_override_change_holds_the_feed_until_the_spindle_reads_its_new_speed(
        sctl: MachineController) -> None:
    """At speed in the cut, the override from 100 to 150 %: X slows to a stand along its path,
    stands while the spindle reads below 95 % of the new speed, and moves again once it is
    there; a change within the band does not stop the feed."""
    c = sctl
    messages: list[str] = []
    c.message.connect(messages.append)
    assert c.load_program("M3 S4000\nG1 X80 F600\nM5\nM30\n", wait=True)
    assert c.cycle_start()
    c.advance(2.5)
    assert c.state is MachineState.RUNNING and float(c.reference_position[0]) > 1.0
    assert c.set_spindle_override(150)
    assert "spindle override 150 %: the feed waits until the spindle turns at 6000 rpm" in messages
    rec = _record(c, 2.0)
    v = np.abs(np.diff(rec["x"]))
    slow = rec["rpm"][1:] < 0.95 * 6000
    assert v[slow][-5:].max() == 0.0                      # standing while below the band
    assert v[-20:].min() > 0.0 and rec["rpm"][-1] >= 0.95 * 6000        # moving again at speed
    assert c.state is MachineState.RUNNING
    n = len(messages)
    assert c.set_spindle_override(147)                    # 5880 rpm: within 5 % of 6000
    rec = _record(c, 0.3)
    assert np.abs(np.diff(rec["x"])).min() > 0.0 and len(messages) == n


def test_an_override_changed_during_a_feed_hold_holds_the_resume_until_the_spindle_reads_it(
        sctl: MachineController) -> None:
    """In a feed hold the override goes from 100 to 150 %, and cycle start is pressed at once:
    the program is running again, but X stands until the spindle reads within 5 % of 6000 rpm,
    then moves."""
    c = sctl
    assert c.load_program("M3 S4000\nG1 X80 F600\nM5\nM30\n", wait=True)
    assert c.cycle_start()
    c.advance(2.5)
    assert c.feed_hold()
    assert c.run_until(lambda: c.state is MachineState.HOLD, 5)
    c.advance(0.5)
    assert c.set_spindle_override(150)
    c.advance(0.01)
    assert c.resume() and c.state is MachineState.RUNNING
    rec = _record(c, 1.5)
    v = np.abs(np.diff(rec["x"]))
    slow = rec["rpm"][1:] < 0.95 * 6000
    assert slow[:10].all() and v[slow].max() == 0.0        # standing while below the band
    assert v[-20:].min() > 0.0 and rec["rpm"][-1] >= 0.95 * 6000


def test_a_spindle_that_loses_speed_in_the_cut_holds_the_program_with_an_alarm(
        sctl: MachineController) -> None:
    c = sctl
    assert c.load_program("M3 S8000\nG1 X60 F300\nM5\nM30\n", wait=True)
    assert c.cycle_start()
    c.advance(3.5)
    assert c.state is MachineState.RUNNING and float(c.reference_position[0]) > 0.5
    assert c.simulate_spindle_load(3000)                      # bogged down to 3,000 rpm
    c.advance(1.5)
    assert c.state is MachineState.ALARM
    alarm = next(a for a in c.alarms if a.code == "spindle_speed")
    assert re.fullmatch(r"the spindle lost speed: (\d+) rpm read against 8000 commanded for 0\.3 s "
                        r"\(a band of 5 %\)", alarm.cause)
    assert int(alarm.cause.split()[4]) < 0.95 * 8000
    x = float(c.reference_position[0])
    c.advance(1.0)
    assert float(c.reference_position[0]) == x and x < 59.0                  # X stands, short of the end


def test_a_fault_of_the_spindle_drive_stops_the_motion_and_e_stop_stops_the_spindle(
        sctl: MachineController) -> None:
    c = sctl
    assert c.load_program("M3 S5000\nG1 X60 F300\nM30\n", wait=True)
    assert c.cycle_start()
    c.advance(3.0)
    assert c.state is MachineState.RUNNING
    c.worker.inject("spindle_fault", 0, 0x2310)
    c.advance(1.0)
    assert c.state is MachineState.ALARM
    assert any("the spindle's drive faulted (error code 0x2310" in a.cause for a in c.alarms)
    x = float(c.reference_position[0])
    c.advance(0.5)
    assert float(c.reference_position[0]) == x


def test_e_stop_quick_stops_the_spindle_drive(sctl: MachineController) -> None:
    c = sctl
    assert c.spindle_on(True, 9000)
    c.advance(3.0)
    assert c.worker.snapshot().spindle_rpm_actual == pytest.approx(9000, abs=2)
    assert c.estop("test")
    c.advance(2.0)
    s = c.worker.snapshot()
    assert abs(s.spindle_rpm_actual) < 1.0 and s.spindle_state == SpindleState.OFF and not c.spindle.on


def test_a_script_bogs_the_spindle_down_and_the_run_holds_with_the_alarm(sctl: MachineController) -> None:
    """``{"op": "spindle_load", "rpm": 2000}`` in a script: the program holds with the speed loss
    alarm, the axes stand and then the spindle stops; the load taken off (null), the spindle
    turns at its speed again."""
    c = sctl
    assert c.load_program("M3 S6000\nG1 X80 F300\nM5\nM30\n", wait=True)
    assert c.cycle_start()
    ops = tuple(parse_op(t, f"s:{k}") for k, t in enumerate((
        '{"after_s": 3, "op": "spindle_load", "rpm": 2000}',
        '{"after_s": 1.5, "op": "spindle_load", "rpm": null}'), 1))
    runner = ScenarioRunner(c, ops, c.machine_time_s)
    states = []
    for _ in range(200):
        runner.step()
        c.advance(0.033)
        states.append(c.state)
    assert runner.done and all(r["ok"] for r in runner.results), runner.results
    assert MachineState.ALARM in states and any(a.code == "spindle_speed" for a in c.alarms)
    # the axes stood, then the spindle stopped too; the load is off: it turns at its speed again
    assert not c.spindle.on and abs(c.worker.snapshot().spindle_rpm_actual) < 1.0
    assert c.reset() and c.spindle_on(True, 6000)
    c.advance(2.5)
    assert c.worker.snapshot().spindle_rpm_actual == pytest.approx(6000, abs=2)
    with pytest.raises(MachineError, match="spindle_load needs"):
        parse_op('{"after_s": 0, "op": "spindle_load"}', "s:1")


def test_loading_a_spindle_without_its_own_drive_is_refused_saying_why(ctl: MachineController) -> None:
    r = ctl.simulate_spindle_load(1000)
    assert not r and "no drive of its own ([spindle] drive)" in r.reason
