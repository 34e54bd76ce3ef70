"""The machine around the drives, through the real controller on simulated drives (manual
clock): the signal table, its one check, coolant, the door, the E-stop chain, limit switches,
the machine's buttons, homing to switches in sequence, and a property over random sequences."""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from app.machine.config import config_from_dict, config_to_toml, load_config
from app.machine.controller import MachineController
from app.machine.errors import ConfigError
from app.machine.model import MachineState, Severity
from ethercat.worker import HomingStep, WorkerState
from resources import shipped_machine
from tests.machine.conftest import make_controller, run_to_idle

MILL = shipped_machine("xyz_mill").read_text(encoding="utf-8")
FLOOD, MIST = 0, 1                # channels of the EL2008 (terminal 3 of the mill)
OUTPUTS = 3


def _config(text: str) -> Path:
    import tempfile

    p = Path(tempfile.mkdtemp()) / "machine.toml"
    p.write_text(text, encoding="utf-8")
    return p


def _outputs(c: MachineController) -> int:
    return c.worker.snapshot().terminal_outputs[OUTPUTS]


# ------------------------------------------------------------------------------ the table
def test_every_wired_signal_is_listed_with_where_it_is_and_what_it_reads(ctl: MachineController) -> None:
    ctl.advance(0.05)
    got = {r.key: r for r in ctl.signal_readings()}
    assert got["estop_chain_ok"].value is True and got["door_closed"].value is True
    assert got["estop_chain_ok"].where == "machine inputs (slave 4) channel 0"
    assert got["limit_neg_X"].where == "limit and home switches (slave 5) channel 0, normally closed"
    assert got["limit_neg_X"].value is False and got["home_X"].value is False
    assert got["coolant_flood"].direction == "out" and got["coolant_flood"].value is False
    assert got["estop_chain_ok"].hal == "iocontrol.0.emc-enable-in"
    keys = list(got)
    assert keys.index("estop_chain_ok") < keys.index("limit_pos_X") < keys.index("coolant_flood")


@pytest.mark.parametrize("change, message", [
    ('door_closed = "4:1"', 'signals.door_closed: bit 0 of slave 4 is already signal estop_chain_ok'),
    ('air_ok = "4:2"', "signals.air_ok: no slave at bus position 9"),
    ('lube_ok = "4:3"', "signals.lube_ok: slave 6 is a EL2008 (8 digital outputs 24 V 0.5 A), not a terminal "
                        "with digital inputs"),
    ('cycle_start = "4:4"', "signals.cycle_start: a EL1008 has channels 0..7, not 8"),
    ('feed_hold = "4:5"', "signals.feed_hold: 'five' is not a wire"),
    ('home_Z = "4:7"', "signals.limit_pos_B: this machine has no axis B"),
    ('type = "EL2008"', "bus.terminals[3].type: unknown terminal type 'EL2098'"),
    ('coolant_flood = "6:0"', "signals.coolant_flood: bit 17 of slave 0 is already [[inputs]] number 0"),
])
def test_the_one_check_refuses_a_wrong_wiring_naming_the_key_and_its_line(change: str, message: str) -> None:
    bad = {
        'door_closed = "4:1"': 'door_closed = "4:0"',
        'air_ok = "4:2"': 'air_ok = "9:2"',
        'lube_ok = "4:3"': 'lube_ok = "6:3"',
        'cycle_start = "4:4"': 'cycle_start = "4:8"',
        'feed_hold = "4:5"': 'feed_hold = "five"',
        'home_Z = "4:7"': 'home_Z = "4:7"\nlimit_pos_B = "5:0"',
        'type = "EL2008"': 'type = "EL2098"',
        'coolant_flood = "6:0"': 'coolant_flood = "6:0"\nspindle_at_speed = "0:17"',
    }[change]
    text = MILL.replace(change, bad, 1)
    line = next(n for n, ln in enumerate(text.splitlines(), 1)
                if ln.startswith(bad.splitlines()[-1].split(" =")[0] + " =") and bad.splitlines()[-1] in ln)
    if "spindle_at_speed" in bad:
        message = "signals.spindle_at_speed: bit 17 of slave 0 is already [[inputs]] number 0"
    with pytest.raises(ConfigError) as err:
        config_from_dict(tomllib.loads(text), "m.toml", text)
    assert f"m.toml:{line}: " in str(err.value) and message in str(err.value), str(err.value)


def test_homing_to_switches_needs_every_axis_and_a_default_gives_way_to_the_file() -> None:
    text = MILL.replace('[[homing.axes]]\naxis = "Y"', '[[homing.axes]]\naxis = "Z"', 1)
    with pytest.raises(ConfigError, match="an axis has two \\[\\[homing.axes\\]\\] tables"):
        config_from_dict(tomllib.loads(text), "m.toml", text)
    start = MILL.index('[[homing.axes]]\naxis = "Y"')
    text = MILL[:start] + MILL[MILL.index("\n\n", start):]
    with pytest.raises(ConfigError, match="m.toml:\\d+: homing.method: homing to switches needs a "
                                          "\\[\\[homing.axes\\]\\] table for every axis; missing: Y"):
        config_from_dict(tomllib.loads(text), "m.toml", text)
    # CiA 402's limit bits of the drives are the default, and give way to an input the file puts there
    plain = tomllib.loads(MILL)
    plain["signals"] = {}
    plain["inputs"] = [{"number": 0, "drive": 0, "bit": 1, "name": "x"}]
    cfg = config_from_dict(plain, "m.toml")
    keys = {s.key: s.wire.text() for s in cfg.wiring.signals}
    assert keys["limit_neg_X"] == "0:0" and "limit_pos_X" not in keys and keys["home_Y"] == "1:2"


def test_the_wiring_is_written_and_read_back_as_it_was(tmp_path: Path) -> None:
    cfg = load_config(shipped_machine("xyz_mill"))
    again = config_from_dict(tomllib.loads(config_to_toml(cfg)), "again.toml")
    assert again.wiring == cfg.wiring and again.homing == cfg.homing


# ------------------------------------------------------------------------------ coolant
def test_m8_and_m9_switch_the_flood_output_where_the_program_says(ctl: MachineController) -> None:
    prog = "G21 G90 G17\nG1 X5 F600\nM8\nG1 X10\nM9\nG1 X15\nM30\n"
    assert ctl.load_program(prog, name="coolant.nc", wait=True)
    seen: list[tuple[float, bool]] = []
    assert ctl.cycle_start(wait=True)
    while ctl.state is not MachineState.IDLE:
        ctl.advance(0.02)
        seen.append((ctl.machine_position[0], bool(_outputs(ctl) >> FLOOD & 1)))
    on = [x for x, flood in seen if flood]
    assert on and 5.0 - 0.2 <= min(on) and max(on) <= 10.0 + 0.2       # on from X5 to X10
    assert not any(flood for x, flood in seen if x < 4.8 or x > 10.5)
    assert ctl.coolant == (False, False)


@pytest.mark.parametrize("end", ["estop", "reset", "m30", "stop"])
def test_coolant_goes_off_at_estop_reset_program_end_and_stop(ctl: MachineController, end: str) -> None:
    if end in ("m30", "stop"):
        assert ctl.load_program("G21 G90\nM8\nM7\nG1 X20 F600\nM30\n", name="c.nc", wait=True)
        assert ctl.cycle_start(wait=True)
        assert ctl.run_until(lambda: ctl.coolant == (True, True), 2)
        assert _outputs(ctl) & 0b11 == 0b11
        if end == "stop":
            ctl.advance(0.3)
            assert ctl.stop()
        run_to_idle(ctl)
    else:
        assert ctl.mdi("M8")
        ctl.advance(0.01)
        assert ctl.coolant == (True, False) and _outputs(ctl) & 1
        if end == "estop":
            assert ctl.estop("test")
        else:
            assert ctl.reset()
    ctl.advance(0.01)
    assert ctl.coolant == (False, False) and _outputs(ctl) & 0b11 == 0


def test_a_program_with_m8_on_a_machine_without_flood_coolant_is_refused_at_its_line(qapp, state_dir: Path
                                                                                     ) -> None:
    text = MILL.replace('coolant_flood = "6:0"\n', "")
    c = make_controller(_config(text), state_dir)
    try:
        r = c.load_program("G21 G90\nG1 X1 F600\nM8\nG1 X2\nM30\n", name="c.nc", wait=True)
        assert not r and "line 3" in r.reason and "M8 switches flood coolant on, and this machine has no " \
            "flood coolant output ([signals] coolant_flood" in r.reason, r.reason
        assert not c.mdi("M8")
        assert c.mdi("M7")                         # the mist output is wired
    finally:
        c.shutdown()


# ------------------------------------------------------------------------------ the door
def test_the_door_holds_the_program_stops_the_spindle_and_cycle_start_waits_for_it(ctl: MachineController
                                                                                   ) -> None:
    assert ctl.load_program("G21 G90\nM3 S6000\nG1 X40 F600\nM5\nM30\n", name="d.nc", wait=True)
    assert ctl.cycle_start(wait=True)
    assert ctl.run_until(lambda: ctl.machine_position[0] > 5.0, 10)
    assert ctl.simulate_input("door_closed", False)
    assert ctl.run_until(lambda: ctl.state is MachineState.HOLD and not ctl.spindle.on, 2)
    held = ctl.machine_position
    r = ctl.cycle_start()
    assert not r and r.reason == "the door is open: close it first"
    assert not ctl.spindle_on(True, 3000) and not ctl.mdi("G0 X1")
    ctl.advance(0.5)
    assert ctl.machine_position == held and not ctl.spindle.on and ctl.spindle.rpm == 6000
    assert ctl.simulate_input("door_closed", None)           # closed again
    ctl.advance(0.05)
    t0 = ctl.machine_time_s()
    assert ctl.cycle_start()
    assert ctl.spindle.on and ctl.spindle.rpm == 6000        # turns again first
    spinup = ctl.config.controller.spindle_spinup_s
    ctl.advance(spinup - 0.1)
    assert ctl.machine_position == held                       # no motion before it is at speed
    assert ctl.run_until(lambda: ctl.machine_position[0] > held[0] + 1.0, 2)
    assert ctl.machine_time_s() - t0 >= spinup
    run_to_idle(ctl)
    assert ctl.last_run.completed and ctl.machine_position[0] == pytest.approx(40.0)


def test_a_jog_with_the_door_open_runs_at_the_setup_speed(ctl: MachineController) -> None:
    assert ctl.simulate_input("door_closed", False)
    ctl.advance(0.05)
    assert ctl.jog_increment("X", 1.0, 1)
    ctl.advance(0.1)
    x0 = ctl.machine_position[0]
    ctl.advance(0.2)
    speed = (ctl.machine_position[0] - x0) / 0.2
    assert 0.5 * 2.0 < speed <= 2.0 * 1.001                  # [interlocks] door_open_jog_mm_s = 2


# ------------------------------------------------------------------------------ E-stop chain
def test_the_e_stop_chain_opening_in_an_arc_is_an_e_stop_that_stays_until_it_closes(ctl: MachineController
                                                                                    ) -> None:
    assert ctl.load_program("G21 G90 G17\nG1 X10 F900\nG2 X30 Y0 R10\nM30\n", name="a.nc", wait=True)
    assert ctl.cycle_start(wait=True)
    assert ctl.run_until(lambda: ctl.current_line == 3, 5)
    ctl.advance(0.3)
    assert ctl.simulate_input("estop_chain_ok", False)
    ctl.advance(0.05)
    assert ctl.state is MachineState.ESTOP
    assert ctl.worker.snapshot().state in (WorkerState.QUICK_STOP, WorkerState.FAULT)
    assert any(a.code == "estop_chain" for a in ctl.active_alarms)
    ctl.advance(0.5)
    p = ctl.machine_position
    ctl.advance(0.5)
    assert ctl.machine_position == p                          # the drives stand
    r = ctl.estop_release()
    assert not r and "the E-stop chain is open" in r.reason
    assert ctl.state is MachineState.ESTOP
    assert ctl.simulate_input("estop_chain_ok", None)
    ctl.advance(0.05)
    assert ctl.estop_release()
    assert ctl.state is MachineState.IDLE and ctl.resume_line == 3


# ------------------------------------------------------------------------------ limit switches
def test_a_limit_switch_stops_the_program_and_only_a_jog_away_follows_the_override(ctl: MachineController
                                                                                  ) -> None:
    assert ctl.load_program("G21 G90\nG1 X40 F1200\nM30\n", name="l.nc", wait=True)
    assert ctl.cycle_start(wait=True)
    assert ctl.run_until(lambda: ctl.machine_position[0] > 5.0, 5)
    assert ctl.simulate_input("limit_pos_X", True)
    ctl.advance(0.05)
    assert ctl.state is MachineState.ALARM
    alarm = next(a for a in ctl.active_alarms if a.code == "limit_switch")
    assert "axis X on its positive limit switch" in alarm.cause
    ctl.advance(0.5)
    r = ctl.reset()
    assert not r and "axis X is on its positive limit switch: override limits" in r.reason
    assert ctl.override_limits(True)
    assert ctl.reset() and ctl.state is MachineState.IDLE
    r = ctl.jog_increment("X", 1.0, 1)
    assert not r and "may only jog away from it (X-)" in r.reason
    x0 = ctl.machine_position[0]
    assert ctl.jog_increment("X", 1.0, -1)
    run_to_idle(ctl)
    assert ctl.machine_position[0] == pytest.approx(x0 - 1.0)
    assert ctl.simulate_input("limit_pos_X", None)           # off the switch: the override ends
    ctl.advance(0.05)
    assert not ctl.worker.snapshot().limits_overridden


# ------------------------------------------------------------------------------ buttons
def test_the_machines_buttons_do_what_the_panels_do(ctl: MachineController) -> None:
    assert ctl.load_program("G21 G90\nG1 X30 F600\nM30\n", name="b.nc", wait=True)
    ctl.advance(0.05)
    for key, state in (("cycle_start", MachineState.RUNNING), ("feed_hold", MachineState.HOLD),
                       ("cycle_start", MachineState.RUNNING), ("stop", MachineState.IDLE)):
        assert ctl.simulate_input(key, True)
        ctl.advance(0.1)
        assert ctl.simulate_input(key, None)
        assert ctl.run_until(lambda s=state: ctl.state is s, 3), (key, ctl.state)
        ctl.advance(0.1)


# ------------------------------------------------------------------------------ homing
def test_home_all_homes_in_sequence_z_first_then_x_and_y_together(qapp, config_path: Path, state_dir: Path
                                                                  ) -> None:
    c = make_controller(config_path, state_dir, zero=False)
    try:
        steps: list[tuple[HomingStep, ...]] = []
        c.poller.on_poll(lambda snap: steps.append(snap.homing_steps))
        assert not any(c.homed)
        assert c.home_all()
        assert c.run_until(lambda: c.state is MachineState.IDLE and all(c.homed), 120)
        searching = [tuple(s[i] is HomingStep.SEARCH for i in range(3)) for s in steps]
        first_x = next(k for k, s in enumerate(searching) if s[0])
        last_z = max(k for k, s in enumerate(searching) if s[2])
        assert last_z < first_x                                   # Z before the others
        assert searching[first_x][1]                              # X and Y together
        assert c.machine_position == pytest.approx((0.0, 0.0, 0.0), abs=1e-9)
        home = c.positions.home_offset
        assert np.all(np.abs(home) <= 1e-4 + 1e-12)              # the simulated switches' edges
    finally:
        c.shutdown()


@pytest.mark.parametrize("switches", [True, False])
def test_an_unhomed_axis_jogs_between_its_limit_switches_not_its_soft_limits(qapp, state_dir: Path,
                                                                             switches: bool) -> None:
    """Unhomed, X stands at machine 0 where its soft limit (min = 0 here) would stop it. With
    both limit switches wired it jogs on (its machine coordinates mean nothing until homed; the
    switches guard it, as LinuxCNC jogs an unhomed joint); without them the soft limit refuses
    the jog, saying so."""
    text = MILL.replace('name = "X"\nkind = "linear"\ndrive_position = 0\ncounts_per_unit = 10000        '
                        '# encoder counts per mm\ndirection = 1\nmin = -250.0',
                        'name = "X"\nkind = "linear"\ndrive_position = 0\ncounts_per_unit = 10000\n'
                        'direction = 1\nmin = 0.0')
    text = text.replace("setter_x_mm = -230.0", "setter_x_mm = 230.0")
    assert "min = 0.0" in text and "setter_x_mm = 230.0" in text
    if not switches:
        text = text.replace('limit_neg_X = "!5:0"', 'limit_neg_X = ""').replace('limit_pos_X = "!5:1"',
                                                                                'limit_pos_X = ""')
    c = make_controller(_config(text), state_dir, zero=False)
    try:
        assert c.signals.has_limit_switches(0) is switches
        r = c.jog_increment("X", 1.0, -1)
        assert bool(r) is switches, r
        if switches:
            assert c.run_until(lambda: c.state is MachineState.IDLE
                               and abs(c.machine_position[0] + 1.0) < 1e-6, 10)
            assert c.jog_start("X", -1)
            # on past "min" until the simulated switch (2 mm beyond it) stops it as a limit
            assert c.run_until(lambda: c.state is MachineState.ALARM, 20)
            alarm = next(a for a in c.active_alarms if a.code == "limit_switch")
            assert "axis X on its negative limit switch" in alarm.cause
            assert -2.0 - 0.5 < c.machine_position[0] < -2.0
        else:
            assert "beyond its soft limit" in r.reason
            assert not c.jog_start("X", -1)
            assert c.machine_position[0] == 0.0
    finally:
        c.shutdown()


def test_an_axis_with_use_index_homes_to_the_encoders_index_past_its_switch(qapp, state_dir: Path) -> None:
    """Z with ``use_index``: past its switch edge (machine 95, left downward) it goes on to the
    simulated encoder's index (one per 5 mm, the one below 95 at drive Z 93.3333) and that
    index becomes machine Z 95 (the offset, as HOME_OFFSET with HOME_USE_INDEX). The step is
    shown while it searches."""
    z_table = 'axis = "Z"\nsearch_vel = 10.0\nlatch_vel = -0.1\n'
    assert z_table in MILL
    text = MILL.replace(z_table, 'axis = "Z"\nsearch_vel = 10.0\nlatch_vel = -2.0\nuse_index = true\n')
    c = make_controller(_config(text), state_dir, zero=False)
    try:
        steps: list[HomingStep] = []
        c.poller.on_poll(lambda snap: steps.append(snap.homing_steps[2]))
        assert c.home_all()
        assert c.run_until(lambda: c.state is MachineState.IDLE and all(c.homed), 120)
        assert HomingStep.INDEX in steps
        home = c.positions.home_offset
        assert home[2] == pytest.approx(93.3333 - 95.0, abs=1e-4 + 1e-9)   # the index, not the edge
        assert np.all(np.abs(home[:2]) <= 1e-4 + 1e-12)                  # X, Y: their switch edges
        assert c.machine_position == pytest.approx((0.0, 0.0, 0.0), abs=1e-9)
    finally:
        c.shutdown()


@pytest.mark.parametrize("method", ["set_here", "switches"])
def test_after_a_power_loss_a_machine_without_reference_switches_never_offers_run_from_line(
        qapp, state_dir: Path, method: str) -> None:
    """With "set here" homing, a control killed mid-run cannot know where the machine stands:
    its alarm says the part zero must be touched off again, and no resume at the line is kept;
    with home switches it offers to run from that line once homed."""
    import json

    text = MILL.replace('method = "switches"', f'method = "{method}"', 1)
    program = Path(state_dir).parent / "cut.nc"
    program.write_text("G21 G90\nG1 X5 F600\nG1 X10\nG1 X15\nM30\n")
    (state_dir / "state.json").write_text(json.dumps({
        "axes": ["X", "Y", "Z"], "raw_position": [7.0, 0.0, 0.0], "home_offset": [0.0, 0.0, 0.0],
        "homed": [True, True, True], "active_offset": "G54", "running": True, "saved": 1.7e9,
        "program": str(program), "line": 3}))
    c = make_controller(_config(text), state_dir, zero=False)
    try:
        (alarm,) = [a for a in c.alarms if a.code == "unclean_shutdown"]
        if method == "set_here":
            assert "no reference switches" in alarm.cause and "touch off the part zero again" in alarm.cause
            assert "run from line" not in alarm.cause and c.interrupted is None
            assert c.home_all() and all(c.homed)
        else:
            assert "run from line 3 once homed" in alarm.cause and c.interrupted == (str(program), 3)
        assert c.load_program(program, wait=True)
        assert (c.resume_line == 3) is (method == "switches")
    finally:
        c.shutdown()


# ------------------------------------------------------------------------------ the property
ACTIONS = ("cycle_start", "resume", "jog", "mdi", "estop_release", "reset", "override", "home")
INPUTS = (("estop_chain_ok", False), ("estop_chain_ok", None), ("door_closed", False), ("door_closed", None))


@settings(max_examples=12, deadline=None)
@given(st.lists(st.one_of(st.sampled_from(ACTIONS), st.sampled_from(INPUTS)), min_size=3, max_size=8))
def test_no_motion_while_a_stop_condition_holds(qapp, tmp_path_factory, steps: list) -> None:
    """Whatever the operator presses and the inputs do, the axes do not move while the E-stop
    chain is open, nor faster than the setup jog speed while the door is (once the stop they
    called for has ended)."""
    d = tmp_path_factory.mktemp("state")
    c = make_controller(Path(shipped_machine("xyz_mill")), d)
    try:
        assert c.load_program("G21 G90\nG1 X30 Y10 F900\nM30\n", name="p.nc", wait=True)
        assert c.cycle_start(wait=True)
        c.advance(0.2)
        for step in steps:
            if isinstance(step, tuple):
                c.simulate_input(*step)
            elif step == "cycle_start":
                c.cycle_start(wait=True)
            elif step == "resume":
                c.resume()
            elif step == "jog":
                c.jog_increment("Y", 1.0, -1)
            elif step == "mdi":
                c.mdi("G0 X1 Y1")
            elif step == "estop_release":
                c.estop_release()
            elif step == "reset":
                c.reset()
            elif step == "override":
                c.override_limits(True)
            else:
                c.home_all()
            c.advance(0.6)                      # a stop called for has ended by now
            chain_open = c.signals.value("estop_chain_ok") is False
            door_open = c.signals.value("door_closed") is False
            before = np.array(c.reference_position)
            c.advance(0.3)
            moved = float(np.abs(np.array(c.reference_position) - before).max())
            if chain_open:
                assert moved == 0.0, (step, c.state, c.state_reason)
            elif door_open:             # a jog at the setup speed at most
                assert moved <= 2.0 * 0.3 + 1e-9, (step, moved, c.state, c.state_reason)
    finally:
        c.shutdown()


def test_with_at_speed_wired_the_motion_waits_for_it_after_m3(qapp, state_dir: Path) -> None:
    """The spindle drive's at-speed signal gates the feed after M3 instead of the fixed spin-up
    time: the axes stand until it reads true; it never coming is a STOP alarm."""
    text = MILL.replace('home_Z = "4:7"', 'home_Z = "4:7"\nspindle_at_speed = "5:7"').replace(
        'home_Y = "5:7"\n', "")
    text = text.replace('[[homing.axes]]\naxis = "Y"', '[[homing.axes]]\naxis = "Y"\n', 1)
    c = make_controller(_config(text.replace('method = "switches"', 'method = "set_here"', 1)), state_dir)
    try:
        assert c.load_program("G21 G90\nM3 S5000\nG1 X10 F600\nM5\nM30\n", name="s.nc", wait=True)
        assert c.cycle_start(wait=True)
        c.advance(3.0)                      # longer than spindle_spinup_s: still waiting
        assert c.spindle.on and c.machine_position[0] == 0.0
        assert c.simulate_input("spindle_at_speed", True)
        assert c.run_until(lambda: c.machine_position[0] > 1.0, 1.0)
        run_to_idle(c)
        assert c.last_run.completed
        assert c.simulate_input("spindle_at_speed", False)
        assert c.load_program("G21 G90\nM3 S5000\nG1 X0 F600\nM30\n", name="s2.nc", wait=True)
        assert c.cycle_start(wait=True)
        c.advance(11.0)
        assert c.state is MachineState.ALARM
        assert any(a.code == "spindle_at_speed" for a in c.active_alarms)
        assert c.machine_position[0] == pytest.approx(10.0, abs=1e-3)
    finally:
        c.shutdown()


def test_a_programs_inputs_and_outputs_may_be_terminal_channels(qapp, state_dir: Path) -> None:
    """``[[outputs]]`` / ``[[inputs]]`` with ``slave`` (a terminal's bus position) and its
    channel: M64/M65 switch the terminal's output, M66 reads its input; a slave that is not such
    a terminal is refused naming the key."""
    from ethercat.sim_io import input_value

    text = MILL.replace('stop = "4:6"\n', "") + (
        '\n[[outputs]]\nnumber = 5\nslave = 6\nbit = 5\nname = "clamp"\n'
        '\n[[inputs]]\nnumber = 3\nslave = 4\nbit = 6\nname = "clamped"\n')
    bad = text.replace("number = 5\nslave = 6", "number = 5\nslave = 4")
    with pytest.raises(ConfigError, match="outputs\\[0\\].slave: slave 4 is a EL1008, not a terminal with "
                                          "digital outputs"):
        config_from_dict(tomllib.loads(bad), "m.toml", bad)
    both = text.replace("number = 5\nslave = 6", "number = 5\ndrive = 0\nslave = 6")
    with pytest.raises(ConfigError, match="give the drive .* or the slave .* of output 5, one of them"):
        config_from_dict(tomllib.loads(both), "m.toml", both)
    cfg = config_from_dict(tomllib.loads(text), "m.toml", text)
    assert config_from_dict(tomllib.loads(config_to_toml(cfg)), "again").machine.output_bits == \
        cfg.machine.output_bits == {5: (-7, 5, "clamp")}
    c = make_controller(_config(text.replace('method = "switches"', 'method = "set_here"', 1)), state_dir)
    try:
        assert c.load_program("G21 G90\nM64 P5\nG1 X2 F600\nM66 P3 L3 Q5\nM65 P5\nG1 X4\nM30\n", name="io.nc",
                              wait=True)
        assert c.cycle_start(wait=True)
        assert c.run_until(lambda: _outputs(c) >> 5 & 1, 2)
        assert c.run_until(lambda: c.machine_position[0] >= 2.0 - 1e-6, 5)
        c.advance(0.5)
        assert _outputs(c) >> 5 & 1 and c.machine_position[0] == pytest.approx(2.0, abs=1e-6)  # waits
        c.drives.inject("terminal_input", 1, input_value(6, True))
        run_to_idle(c)
        assert c.last_run.completed and not _outputs(c) >> 5 & 1
    finally:
        c.shutdown()


def test_air_lost_stops_the_motion_and_lube_lost_warns_as_configured(ctl: MachineController) -> None:
    assert ctl.load_program("G21 G90\nG1 X30 F600\nM30\n", name="a.nc", wait=True)
    assert ctl.cycle_start(wait=True)
    ctl.advance(0.5)
    assert ctl.simulate_input("lube_ok", False)               # [interlocks] lube_lost = "warning"
    ctl.advance(0.3)
    assert ctl.state is MachineState.RUNNING
    lube = next(a for a in ctl.active_alarms if a.code == "lube_ok_lost")
    assert lube.severity is Severity.WARNING and "lubrication lost" in lube.cause
    assert ctl.simulate_input("air_ok", False)                # [interlocks] air_lost = "stop"
    ctl.advance(0.05)
    assert ctl.state is MachineState.ALARM
    assert any(a.code == "air_ok_lost" and "air pressure lost" in a.cause for a in ctl.active_alarms)
    ctl.advance(1.0)
    p = ctl.machine_position
    ctl.advance(0.5)
    assert ctl.machine_position == p and 0.0 < p[0] < 30.0     # stopped along the path, not at its end
