"""The machine controller on the real CyclicWorker + SimBus ("manual" worker mode: simulated
time driven by the test). Every state, command and reaction with short programs."""

from __future__ import annotations

import json
from dataclasses import replace
from datetime import timedelta
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from app.machine.config import load_config, save_config
from app.machine.controller import TRANSITIONS, MachineController
from app.machine.errors import MachineError
from app.machine.model import Activity, MachineState, Severity
from planner.core.tools import Tool
from tests.machine.conftest import make_controller, run_to_idle, trace

SHORT = "G0 X5 Y0\nG1 X20 F1800\nG3 X20 Y20 R10\nG1 X5\nM30\n"
LIMIT_KEYS = ("tangential_v", "tangential_a", "tangential_j", "axis_v", "axis_a", "axis_j")


def assert_within_limits(limits: dict[str, float]) -> None:
    for k in LIMIT_KEYS:
        assert limits[k] <= 1.0 + 1e-6, f"{k} = {limits[k]:.6f}"


def start(ctl: MachineController, text: str = SHORT) -> None:
    assert ctl.load_program(text, wait=True), "load refused"
    assert ctl.cycle_start(wait=True), "cycle start refused"
    assert ctl.state is MachineState.RUNNING


# ---------------------------------------------------------------------------- states
def test_transition_table_is_closed() -> None:
    for src, dsts in TRANSITIONS.items():
        assert src not in dsts
        assert MachineState.ESTOP in dsts or src is MachineState.ESTOP


def test_refusals_carry_reasons(qapp, config_path: Path, state_dir: Path) -> None:
    ctl = make_controller(config_path, state_dir, connect=False)
    refused: list[tuple[str, str]] = []
    ctl.commandRefused.connect(lambda a, r: refused.append((a, r)))
    try:
        r = ctl.cycle_start()
        assert not r and "disconnected" in r.reason
        assert ctl.connect_bus()
        assert ctl.state is MachineState.IDLE
        assert ctl.load_program(SHORT, wait=True)
        r = ctl.cycle_start()
        assert not r and "not homed" in r.reason and "X Y Z" in r.reason
        assert not ctl.mdi("G0 X1") and not ctl.run_from_line(2)
        r = ctl.feed_hold()
        assert not r and "nothing to hold" in r.reason
        assert ctl.jog_increment("X", 0.1)  # jogging is allowed before homing
        run_to_idle(ctl)
        assert refused and all(reason for _, reason in refused)
        with pytest.raises(MachineError):
            ctl.states.set_state(MachineState.HOLD)  # IDLE -> HOLD is not a legal transition
    finally:
        ctl.shutdown()


def test_estop_quick_stops_at_once_and_release(ctl: MachineController) -> None:
    start(ctl)
    ctl.advance(0.4)
    assert ctl.estop("test")
    assert ctl.state is MachineState.ESTOP
    assert ctl.worker.snapshot().state.name in ("QUICK_STOP", "FAULT")
    p0 = np.array(ctl.machine_position)
    ctl.advance(0.3)
    assert np.linalg.norm(np.array(ctl.machine_position) - p0) < 1.0  # stopped (quick-stop ramp only)
    assert not ctl.jog_start("X", 1)
    assert any(a.code == "estop" and a.severity is Severity.ESTOP for a in ctl.active_alarms)
    assert ctl.estop_release()
    assert ctl.state is MachineState.IDLE
    assert ctl.resume_line > 0  # the interrupted program can be resumed


# ---------------------------------------------------------------------------- program run
def test_a_fanuc_subprogram_runs_its_passes_and_ends_at_the_main_programs_end(ctl: MachineController) -> None:
    """M98 P L: the subprogram's passes run one after the other (the line shown is the
    subprogram's own), and the run ends at the main program's M30, not at the M99 after it."""
    text = ("G21 G90 F3000\nG0 X0 Y0 Z5\nM98 P100 L3\nG0 Z5\nM30\n"
            "O100 (a pass)\nG91 G1 Z-1\nG1 X10\nG1 Y2\nG1 X-10\nG90\nM99\n")
    lines: list[int] = []
    finished = []
    ctl.lineChanged.connect(lines.append)
    ctl.programFinished.connect(finished.append)
    assert ctl.load_program(text, wait=True)
    assert ctl.program_info.move_count == 14
    assert ctl.cycle_start()
    run_to_idle(ctl)
    assert finished[0].completed and finished[0].last_line == 4
    assert {8, 9, 10} <= set(lines)
    np.testing.assert_array_equal(ctl.reference_position, (0.0, 6.0, 5.0))


def test_program_runs_to_its_exact_end(ctl: MachineController) -> None:
    lines: list[int] = []
    progress: list[float] = []
    finished = []
    ctl.lineChanged.connect(lines.append)
    ctl.progressChanged.connect(lambda f, r: progress.append(f))
    ctl.programFinished.connect(finished.append)
    assert ctl.load_program(SHORT, wait=True)
    est = ctl.program_info.cycle_time_s
    assert 1.0 < est < 5.0
    assert ctl.cycle_start()
    run_to_idle(ctl)
    s = finished[0]
    assert s.completed and s.last_line == 4
    assert s.cycle_time_s == pytest.approx(est, abs=0.02)
    assert [x for x in lines if x] == sorted(x for x in lines if x) and 3 in lines
    assert progress[-1] == 1.0
    np.testing.assert_array_equal(ctl.reference_position, (5.0, 20.0, 0.0))
    ctl.advance(0.1)
    np.testing.assert_allclose(ctl.machine_position, (5.0, 20.0, 0.0), atol=2e-4)
    assert_within_limits(s.limits)
    assert s.tracking.samples > 1000 and all(r > 0 for r in s.tracking.rmse[:2])
    t = trace(ctl)
    assert set(t) >= {"t", "reference", "actual", "axes", "rmse", "mse"}
    assert t["reference"].shape == t["actual"].shape and t["reference"].shape[1] == 3
    assert ctl.state is MachineState.IDLE and ctl.activity is Activity.NONE


def test_all_program_errors_before_any_motion(ctl: MachineController) -> None:
    errors = []
    ctl.programErrors.connect(errors.append)
    r = ctl.load_program("G0 X1\nG1 X2 Q5 F100\nG2 X3 Y4\nG1 X1 F100\n", wait=True)
    assert not r
    assert [e.line for e in errors[0]] == [2, 3]
    assert not ctl.cycle_start()
    assert ctl.machine_position == (0.0, 0.0, 0.0)


def test_soft_limit_in_the_middle_of_an_arc_refused_with_its_line(ctl: MachineController) -> None:
    errors = []
    ctl.programErrors.connect(errors.append)
    r = ctl.load_program("G0 X200 Y-60\nG3 X200 Y60 R60 F600\nG0 X0 Y0\n", wait=True)
    assert not r and "line 2" in r.reason and "axis X" in r.reason
    (issue,) = errors[0]
    assert issue.line == 2 and issue.axis == "X" and "260" in issue.message
    assert ctl.program_info is None


def test_feed_hold_in_an_arc_then_resume_ends_exactly(ctl: MachineController) -> None:
    start(ctl)
    assert ctl.run_until(lambda: ctl.current_line == 3, 5)
    ctl.advance(0.15)
    assert ctl.feed_hold()
    assert ctl.state is MachineState.HOLD
    ctl.advance(0.6)
    held = np.array(ctl.reference_position)
    ctl.advance(0.3)
    np.testing.assert_array_equal(ctl.reference_position, held)  # standing still
    assert np.hypot(held[0] - 20.0, held[1] - 10.0) == pytest.approx(10.0, abs=1e-9)  # on the arc
    assert held[0] > 20.0  # in its first half, not at an end
    assert ctl.resume()
    run_to_idle(ctl)
    s = ctl.last_run
    assert s.completed
    np.testing.assert_array_equal(ctl.reference_position, (5.0, 20.0, 0.0))
    assert_within_limits(s.limits)


def test_override_changes_mid_move(ctl: MachineController) -> None:
    speeds = []
    ctl.speedChanged.connect(speeds.append)
    start(ctl, "G0 X5 Y0\nG1 X120 F1200\nM30\n")  # 20 mm/s programmed
    ctl.advance(1.2)
    v100 = ctl.snapshot().path_speed_mm_s
    assert v100 == pytest.approx(20.0, rel=0.02)
    assert ctl.set_feed_override(150)
    ctl.advance(1.0)
    assert ctl.snapshot().path_speed_mm_s == pytest.approx(30.0, rel=0.02)  # 150 % of 20, within Vmax 30
    assert ctl.set_feed_override(40)
    ctl.advance(1.0)
    assert ctl.snapshot().path_speed_mm_s == pytest.approx(8.0, rel=0.03)
    assert not ctl.set_feed_override(201)
    assert ctl.set_feed_override(100)
    run_to_idle(ctl)
    s = ctl.last_run
    assert s.completed
    np.testing.assert_array_equal(ctl.reference_position, (120.0, 0.0, 0.0))
    assert_within_limits(s.limits)
    d = np.diff(trace(ctl)["reference"][:, 0])
    assert np.max(np.abs(np.diff(d))) / 1e-6 < 1000.0  # no jump: acceleration stays bounded


def test_single_block_stops_after_every_block(ctl: MachineController) -> None:
    assert ctl.set_single_block(True)
    start(ctl)
    stops = 0
    while ctl.state is not MachineState.IDLE:
        assert ctl.run_until(lambda: ctl.state in (MachineState.HOLD, MachineState.IDLE), 10)
        if ctl.state is MachineState.HOLD:
            assert "single block" in ctl.state_reason
            stops += 1
            assert ctl.cycle_start()
    assert stops == 3  # after lines 1, 2, 3 (line 4 ends the program)
    np.testing.assert_array_equal(ctl.reference_position, (5.0, 20.0, 0.0))


def test_m00_pauses_and_m01_only_with_optional_stop(ctl: MachineController) -> None:
    text = "G1 X5 F1800\nM01\nG1 X10\nM00\nG1 X15\nM30\n"
    start(ctl, text)
    assert ctl.run_until(lambda: ctl.state is MachineState.HOLD, 5)
    assert "M00" in ctl.state_reason and ctl.reference_position[0] == 10.0
    assert ctl.cycle_start()
    run_to_idle(ctl)
    assert ctl.set_optional_stop(True)
    assert ctl.mdi("G0 X0")
    run_to_idle(ctl)
    start(ctl, text)
    assert ctl.run_until(lambda: ctl.state is MachineState.HOLD, 5)
    assert "M01" in ctl.state_reason and ctl.reference_position[0] == 5.0


def test_run_from_line_moves_safely_and_restores_the_spindle(ctl: MachineController) -> None:
    text = "G0 Z5\nM3 S1200\nG1 Z-1 F600\nG1 X10 F1800\nM3 S1500 G1 Y10\nG1 X0\nM5\nM30\n"
    assert ctl.load_program(text, wait=True)
    assert ctl.run_from_line(5)
    assert ctl.activity is Activity.APPROACH
    assert ctl.run_until(lambda: ctl.activity is Activity.PROGRAM, 20)
    assert ctl.spindle.direction == 1 and ctl.spindle.rpm == 1500.0  # as of line 5 (M3 S1500 on it)
    np.testing.assert_allclose(ctl.reference_position, (10.0, 0.0, -1.0), atol=1e-9)
    run_to_idle(ctl)
    np.testing.assert_array_equal(ctl.reference_position, (0.0, 10.0, -1.0))
    assert not ctl.spindle.on  # M5 at line 7


def test_run_from_line_keeps_the_offsets_and_tools_the_program_sets_later(ctl: MachineController) -> None:
    """What G10 sets after the restart line reaches the machine as in a whole run (the events
    name the program's parameter sets and tools, which the program from the line keeps)."""
    text = "G0 Z5\nG0 X10\nG0 X20\nG10 L2 P2 X7 Y8\nG10 L1 P3 Z4.5\nG0 X30\nM30\n"
    assert ctl.set_tool(Tool(3, 3, (("Z", 1.0),), 6.0, "drill"))
    assert ctl.load_program(text, wait=True)
    assert ctl.run_from_line(3)
    run_to_idle(ctl)
    assert ctl.work_offsets["G55"][:2] == (7.0, 8.0)
    assert ctl.tool_table.get(3).offset("Z") == 4.5


SAFE_RESTART = ("G0 Z5\nG0 X-20 Y0\nM3 S1200\nG1 Z-1 F600\nG1 X40 F1200\nG1 Y30\nG0 Z5\n"
                "G0 X60 Y60\nG1 Z-2 F600\nG1 X0 F1200\nG0 Z5\nM5\nM30\n")


@pytest.mark.parametrize("after", ["stop", "estop"])
def test_restart_after_a_stop_while_cutting_never_moves_sideways_low_and_spins_up_first(
        qapp, config_path: Path, state_dir: Path, after: str) -> None:
    with config_path.open("a", encoding="utf-8") as f:
        f.write("restart_clearance_mm = 30.0\nspindle_spinup_s = 1.5\n")   # [controller] is last
    ctl = make_controller(config_path, state_dir)
    try:
        start(ctl, SAFE_RESTART)
        assert ctl.run_until(lambda: ctl.current_line == 6, 20)             # cutting along Y at Z-1
        ctl.advance(0.3)
        if after == "stop":
            assert ctl.stop()
            run_to_idle(ctl)
        else:
            assert ctl.estop("test")
            assert ctl.run_until(lambda: not ctl.spindle.on, 1.0)
            assert ctl.estop_release()
            assert ctl.run_until(lambda: ctl.state is MachineState.IDLE, 5)
        assert not ctl.spindle.on
        assert ctl.reference_position[2] == pytest.approx(-1.0)
        assert ctl.run_from_line(10, wait=True), ctl.state_reason         # G1 X0 from (60, 60, -2)
        samples: list[tuple[float, tuple[float, ...], float]] = []

        def record() -> bool:
            samples.append((float(ctl.machine_time_s()),
                            ctl.reference_position, ctl.spindle.direction * ctl.spindle.rpm))
            return ctl.activity is Activity.PROGRAM

        assert ctl.run_until(record, 30)
        # the first sample is the last set-point before the stop; after an E-stop the drives
        # stopped short of it, and the approach starts where they stand
        del samples[0]
        t = np.array([s[0] for s in samples])
        p = np.array([s[1] for s in samples])
        rpm = np.array([s[2] for s in samples])
        assert p[:, 2].max() == pytest.approx(30.0)                        # up to the clearance
        sideways = np.abs(np.diff(p[:, :2], axis=0)).max(axis=1) > 1e-3   # encoder counts: 1e-4
        low = np.maximum(p[:-1, 2], p[1:, 2]) < 30.0 - 1e-9
        assert not (sideways & low).any(), f"moved in X or Y below the clearance height: {p[:4]}"
        top = int(np.argmax(p[:, 2]))
        going_down = np.arange(len(p)) > top
        below = going_down & (p[:, 2] < 5.0 - 1e-9)                       # under the retract plane
        assert below.any() and (rpm[below] == 1200.0).all()
        first_down = int(np.argmax(going_down & (p[:, 2] < 30.0 - 1e-9)))
        spun = int(np.argmax(rpm == 1200.0))
        assert (rpm[:spun] == 0.0).all() and spun > 0                     # retracted with it off
        assert t[first_down] - t[spun] >= 1.5 - 0.04                        # at speed first
        np.testing.assert_allclose(ctl.reference_position, (60.0, 60.0, -2.0), atol=1e-9)
        run_to_idle(ctl, 30)
        np.testing.assert_allclose(ctl.reference_position, (0.0, 60.0, 5.0), atol=1e-9)
    finally:
        ctl.shutdown()


# ---------------------------------------------------------------------------- manual
def test_lost_jog_release_stops_at_the_soft_limit(ctl: MachineController) -> None:
    assert ctl.mdi("G0 X240")
    run_to_idle(ctl)
    assert ctl.jog_start("X", 1)
    # the release never comes
    assert ctl.run_until(lambda: ctl.state is MachineState.IDLE, 10)
    assert ctl.reference_position[0] == 250.0
    assert not ctl.jog_start("X", 1)  # already at the limit


def test_jog_release_stops_jerk_limited(ctl: MachineController) -> None:
    assert ctl.jog_start("Y", -1)
    ctl.advance(0.5)
    assert ctl.jog_stop("Y")
    run_to_idle(ctl, 3)
    y = ctl.reference_position[1]
    assert -9.0 < y < -3.0  # 10 mm/s for 0.5 s, then a short stop
    ctl.advance(0.2)
    assert ctl.reference_position[1] == y


def test_incremental_jog(ctl: MachineController) -> None:
    for step in (1.0, 0.1, 0.01, 0.001):
        assert ctl.jog_increment("Z", step, -1)
        run_to_idle(ctl, 3)
    assert ctl.reference_position[2] == pytest.approx(-1.111, abs=1e-12)
    assert not ctl.jog_increment("Z", 0.5)
    assert ctl.mdi("G0 Z99.5")
    run_to_idle(ctl)
    r = ctl.jog_increment("Z", 1.0, 1)
    assert not r and "soft limit" in r.reason


@pytest.mark.parametrize("block, reason", [
    ("M3 S999999", "S999999 is over the spindle's maximum of 24000 rpm"),
    ("G4 P2", "G4 dwells between the moves of a program"),
    ("M0", "M0 pauses a running program"),
    ("M1", "M1 pauses a running program"),
    ("M6 T5", "M6 runs in a program; in MDI put the tool in by hand"),
    ("T5", "T selects the tool for a program's M6"),
    ("M61 Q9", "tool T9 is not in the tool table"),
    ("G43 H9 G0 Z1", "tool T9 is not in the tool table"),
])
def test_mdi_refuses_what_it_cannot_do_with_the_reason(ctl: MachineController, block: str,
                                                       reason: str) -> None:
    """Every MDI block does what it says or is refused saying why: nothing returns OK and
    silently does nothing, and a value over a limit names the limit, as the buttons do."""
    assert ctl.set_tool(Tool(5, 5, (("Z", 12.5),), 6.0, "flat"))
    spindle_before = ctl.spindle
    refused: list[tuple[str, str]] = []
    ctl.commandRefused.connect(lambda action, why: refused.append((action, why)))
    r = ctl.mdi(block)
    assert not r and reason in r.reason
    assert refused == [("mdi", r.reason)]
    assert ctl.spindle == spindle_before and ctl.state is MachineState.IDLE


@pytest.mark.parametrize("block", ["G91", "G20", "F500", "S1000", "G43 H0", "#1=5", "G61", "G18", "G0"])
def test_mdi_block_that_only_sets_modes_is_refused_not_forgotten(ctl: MachineController, block: str) -> None:
    """An MDI block is read on its own: G91 typed alone would change nothing that lasts (the
    next "G1 X10" would go to X10 absolute), so it is refused, saying how to write it."""
    r = ctl.mdi(block)
    assert not r and "an MDI block stands alone" in r.reason and "G91 G1 X10 F500" in r.reason
    assert ctl.mdi("(only a comment)")            # says nothing and does nothing
    assert ctl.mdi("G91 G1 X10 F500")
    run_to_idle(ctl)
    assert ctl.reference_position[0] == pytest.approx(10.0)


def test_mdi_g1_without_a_feed_is_refused_as_linuxcnc_refuses_it(ctl: MachineController) -> None:
    """An MDI block keeps no feed from the one before: "G1" alone has none, and LinuxCNC
    refuses a G01 with no feed even when it moves nowhere."""
    r = ctl.mdi("G1")
    assert not r and "feed rate is zero" in r.reason


@pytest.mark.parametrize("block", ["G41.1 D4", "G42.1 D4 G1 X20 Y5 F600", "G41 G1 X20 F600"])
def test_mdi_refuses_cutter_compensation(ctl: MachineController, block: str) -> None:
    r = ctl.mdi(block)
    assert not r and "cutter radius compensation (G41/G42) works across the moves of a program" in r.reason
    assert ctl.state is MachineState.IDLE


def test_mdi_m30_ends_like_a_program_end(ctl: MachineController) -> None:
    assert ctl.mdi("M3 S8000")
    assert ctl.spindle.on and ctl.spindle.rpm == 8000
    assert ctl.mdi("M30")
    assert not ctl.spindle.on and ctl.state is MachineState.IDLE


def test_mdi_with_the_same_checks(ctl: MachineController) -> None:
    assert ctl.mdi("G1 X3 Y4 F600")
    run_to_idle(ctl)
    np.testing.assert_array_equal(ctl.reference_position, (3.0, 4.0, 0.0))
    r = ctl.mdi("G0 X300")
    assert not r and "X" in r.reason and "soft limit" in r.reason
    assert not ctl.mdi("G1 X1 Q3")
    assert ctl.set_work_offset("G55", (10.0, 0.0, 0.0))
    assert ctl.select_work_offset("G55")
    assert ctl.mdi("G0 X0 Y0")
    run_to_idle(ctl)
    assert ctl.reference_position[0] == 10.0 and ctl.work_position[0] == pytest.approx(0.0, abs=1e-3)


def test_drive_homing_mode_6(qapp, config_path: Path, state_dir: Path) -> None:
    cfg = load_config(config_path)
    save_config(replace(cfg, homing=replace(cfg.homing, method="drive", drive_method=35)), config_path)
    ctl = make_controller(config_path, state_dir, zero=False)
    try:
        assert ctl.homed == (False, False, False)
        assert ctl.home_all()
        assert ctl.state is MachineState.HOMING
        assert ctl.run_until(lambda: ctl.state is MachineState.IDLE, 5)
        assert ctl.homed == (True, True, True)
        assert ctl.load_program(SHORT, wait=True) and ctl.cycle_start()
    finally:
        ctl.shutdown()


def test_offsets_positions_homed_state_survive_a_restart(qapp, config_path: Path, state_dir: Path) -> None:
    ctl = make_controller(config_path, state_dir)
    assert ctl.mdi("G0 X12 Y-7 Z-3")
    run_to_idle(ctl)
    ctl.advance(0.2)
    assert ctl.touch_off("Z", 0.0)
    assert ctl.set_work_offset("G56", {"X": 1.5, "Y": 2.5})
    assert ctl.select_work_offset("G56")
    pos = ctl.machine_position
    ctl.shutdown()
    again = make_controller(config_path, state_dir, zero=False)
    try:
        assert again.homed == (True, True, True)
        np.testing.assert_allclose(again.machine_position, pos, atol=2e-4)
        assert again.work_offsets["G54"][2] == pytest.approx(pos[2], abs=1e-9)
        assert again.work_offsets["G56"][:2] == (1.5, 2.5)
        assert again.active_offset == "G56"
    finally:
        again.shutdown()


def test_spindle_by_hand_and_from_the_program(ctl: MachineController) -> None:
    seen = []
    ctl.spindleChanged.connect(seen.append)
    assert ctl.spindle_on(clockwise=False, rpm=3000)
    assert ctl.spindle.direction == -1 and ctl.spindle.rpm == 3000
    ctl.advance(0.05)
    assert ctl.worker.snapshot().digital_outputs[0] == 0b11
    assert ctl.spindle_off() and ctl.worker.snapshot().digital_outputs[0] == 0
    start(ctl, "M3 S800\nG1 X5 F1800\nM5\nG1 X6\nM30\n")
    assert ctl.run_until(lambda: ctl.spindle.on, 3)
    assert ctl.spindle.rpm == 800
    run_to_idle(ctl)
    assert not ctl.spindle.on
    assert [s.direction for s in seen][-2:] == [1, 0]


# ---------------------------------------------------------------------------- faults and alarms
def test_drive_fault_mid_program_keeps_position_and_line(ctl: MachineController, state_dir: Path) -> None:
    start(ctl)
    assert ctl.run_until(lambda: ctl.current_line == 3, 5)
    ctl.advance(0.1)
    ctl.worker.inject("drive_fault", "Y", 0x2310)
    assert ctl.run_until(lambda: ctl.state is MachineState.ALARM, 1)
    ctl.advance(0.3)
    alarm = [a for a in ctl.active_alarms if a.severity is Severity.QUICK_STOP][0]
    assert alarm.source == "drive Y" and "0x2310" in alarm.cause
    assert ctl.resume_line == 3
    pos = np.array(ctl.machine_position)
    assert np.hypot(pos[0] - 20.0, pos[1] - 10.0) == pytest.approx(10.0, abs=0.1)  # near the arc
    saved = json.loads((state_dir / "alarms.json").read_text())
    assert any(a["cause"] == alarm.cause and a["state"] == "active" for a in saved)
    assert not ctl.cycle_start()
    assert ctl.reset()
    assert ctl.state is MachineState.IDLE
    assert json.loads((state_dir / "alarms.json").read_text())[-1]["state"] == "acknowledged"
    np.testing.assert_allclose(ctl.machine_position, pos, atol=1e-3)  # the position is kept
    assert ctl.resume()
    run_to_idle(ctl)
    assert ctl.last_run.completed
    np.testing.assert_array_equal(ctl.reference_position, (5.0, 20.0, 0.0))


def test_stop_keeps_where_it_stopped_and_cycle_start_never_starts_again_by_itself(
        ctl: MachineController) -> None:
    """After Stop (and a reset) the program is not run again from line 1 by a cycle start:
    the operator chooses to resume where it stopped or to start from the beginning."""
    start(ctl)
    ctl.advance(0.5)
    assert ctl.stop()
    run_to_idle(ctl, 3)
    assert not ctl.last_run.completed
    line = ctl.resume_line
    assert line > 0
    here = ctl.reference_position
    r = ctl.cycle_start(wait=True)
    assert not r and f"stopped at line {line}" in r.reason
    assert ctl.state is MachineState.IDLE
    ctl.advance(0.5)
    assert ctl.reference_position == here                 # nothing moved
    assert ctl.reset() and ctl.resume_line == line         # a reset keeps the point
    assert ctl.cycle_start(wait=True, from_start=True)     # the operator's choice
    assert ctl.resume_line == 0
    run_to_idle(ctl)
    assert ctl.last_run.completed


def test_stop_then_resume_goes_on_from_where_it_stopped(ctl: MachineController) -> None:
    start(ctl)
    ctl.advance(0.5)
    assert ctl.stop()
    run_to_idle(ctl, 3)
    stopped = np.array(ctl.reference_position)
    preview = ctl.restart_preview()
    assert not isinstance(preview, str)
    np.testing.assert_allclose(preview.path[0], stopped, atol=1e-3)       # from where it stands (actual)
    np.testing.assert_allclose(preview.path[-1], stopped, atol=1e-6)      # back to the stop point
    assert ctl.resume()
    run_to_idle(ctl)
    assert ctl.last_run.completed
    np.testing.assert_array_equal(ctl.reference_position, (5.0, 20.0, 0.0))


def test_stop_class_alarm_stops_along_the_path(ctl: MachineController) -> None:
    start(ctl)
    assert ctl.run_until(lambda: ctl.current_line == 3, 5)
    ctl.alarm_log.alarm_stop("test: coolant pressure lost", "controller", "test")  # a STOP-severity alarm
    assert ctl.state is MachineState.ALARM
    refused = ctl.reset()  # the axes are still braking along the arc: reset waits for standstill
    assert not refused and "stand" in refused.reason
    assert ctl.state is MachineState.ALARM
    assert ctl.run_until(lambda: ctl.worker.buffer_level() == 0 and ctl.stream.job is None, 2)
    p = np.array(ctl.reference_position)
    assert np.hypot(p[0] - 20.0, p[1] - 10.0) == pytest.approx(10.0, abs=1e-9)  # stopped on the arc
    assert ctl.resume_line == 3
    assert ctl.reset() and ctl.state is MachineState.IDLE
    assert ctl.resume()
    run_to_idle(ctl)
    np.testing.assert_array_equal(ctl.reference_position, (5.0, 20.0, 0.0))


def test_alarms_persist_across_a_restart(qapp, config_path: Path, state_dir: Path) -> None:
    ctl = make_controller(config_path, state_dir)
    ctl.worker.inject("drive_fault", "X", 0x4310)
    ctl.advance(0.1)
    assert ctl.state is MachineState.ALARM
    ctl.shutdown()
    again = make_controller(config_path, state_dir, zero=False)
    try:
        (a,) = [a for a in again.alarms if "0x4310" in a.cause]
        assert a.active and a.source == "drive X" and a.time_s > 0
        assert again.acknowledge_alarm(a.id)
        assert not again.active_alarms or all(x.id != a.id for x in again.active_alarms)
    finally:
        again.shutdown()


def test_single_block_switched_on_during_a_hold(ctl: MachineController) -> None:
    start(ctl)
    assert ctl.run_until(lambda: ctl.current_line == 2, 5)
    ctl.advance(0.1)
    assert ctl.feed_hold()
    assert ctl.run_until(lambda: ctl.worker.buffer_level() == 0, 2)  # standing still (any lead_s)
    assert ctl.set_single_block(True)
    assert ctl.cycle_start()  # re-planned from the held point with a stop at every block end
    assert ctl.run_until(lambda: ctl.state is MachineState.HOLD, 5)
    assert "single block" in ctl.state_reason
    np.testing.assert_array_equal(ctl.reference_position, (20.0, 0.0, 0.0))  # end of line 2
    assert ctl.set_single_block(False)
    assert ctl.cycle_start()  # and switched off again at that stop
    run_to_idle(ctl)
    s = ctl.last_run
    assert s.completed
    np.testing.assert_array_equal(ctl.reference_position, (5.0, 20.0, 0.0))
    assert_within_limits(s.limits)


def test_rapid_override_applies_to_rapids_only(ctl: MachineController) -> None:
    assert ctl.set_rapid_override(25)
    start(ctl, "G0 X100\nG1 X110 F1200\nM30\n")
    ctl.advance(1.5)
    assert ctl.snapshot().path_speed_mm_s == pytest.approx(12.5, rel=0.03)  # 25 % of the 50 mm/s rapid
    assert ctl.run_until(lambda: ctl.current_line == 2, 10)
    ctl.advance(0.3)
    assert ctl.snapshot().path_speed_mm_s == pytest.approx(20.0, rel=0.03)  # the feed is not affected
    run_to_idle(ctl)
    assert_within_limits(ctl.last_run.limits)
    assert not ctl.set_rapid_override(120)


def test_homing_not_required_when_the_configuration_says_so(qapp, config_path: Path, state_dir: Path) -> None:
    cfg = load_config(config_path)
    save_config(replace(cfg, homing=replace(cfg.homing, required=False)), config_path)
    ctl = make_controller(config_path, state_dir, zero=False)
    try:
        assert ctl.homed == (False, False, False)
        assert ctl.load_program("G1 X2 F1800\nM30\n", wait=True) and ctl.cycle_start()
        run_to_idle(ctl)
        assert ctl.last_run.completed
    finally:
        ctl.shutdown()


def test_damaged_state_file_is_reported(qapp, config_path: Path, state_dir: Path) -> None:
    (state_dir / "state.json").write_text('{"axes": ["X", "Y", "Z"], "raw_pos')
    ctl = make_controller(config_path, state_dir, connect=False)
    try:
        warn = [a for a in ctl.alarms if a.code == "state_file"]
        assert warn and "damaged" in warn[0].cause and warn[0].severity is Severity.WARNING
        assert list(state_dir.glob("state.json.damaged-*"))
        assert ctl.homed == (False, False, False)
    finally:
        ctl.shutdown()


_MDI_TOKENS = st.sampled_from([
    "G0", "G1", "G2", "G3", "G4", "G17", "G18", "G20", "G21", "G53", "G54", "G90", "G91", "M0", "M3", "M5",
    "M6", "M30", "T1", "F600", "F0", "S999999", "S-5", "X1", "Y-2", "Z0.5", "X1e400", "X[0/0]", "P2", "P-1",
    "R5", "I1", "J0", "#1=[10**300*10**300]", "#[[10**300*10**300]-[10**300*10**300]]=1", "(comment)", ";",
    "%", "Q3", "X9999", "A1", "[", "]", "#<x>", "\0", "\n",
])


@settings(max_examples=150, deadline=timedelta(seconds=5),
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.lists(_MDI_TOKENS, min_size=1, max_size=8).map(" ".join))
def test_mdi_fuzz_never_raises_and_says_why(ctl: MachineController, block: str) -> None:
    """Whatever is typed into MDI is done or refused with a reason; nothing escapes."""
    r = ctl.mdi(block)
    if not r:
        assert r.reason
    ctl.run_until(lambda: ctl.state is not MachineState.RUNNING, 5)
    if ctl.state is MachineState.HOLD:
        ctl.stop()
        ctl.run_until(lambda: ctl.state is MachineState.IDLE, 5)


SPINDLE_PROGRAM = "G0 X5 Y0\nM3 S8000\nG1 X120 F1200\nM30\n"


def _spindle_running(ctl: MachineController) -> None:
    start(ctl, SPINDLE_PROGRAM)
    assert ctl.run_until(lambda: ctl.current_line == 3, 5)
    ctl.advance(0.5)
    assert ctl.spindle.on and ctl.spindle.rpm == 8000


def test_stop_stops_the_spindle_once_the_axes_stand(ctl: MachineController) -> None:
    """Stop: the axes brake along the path with the spindle still cutting, then it goes off."""
    _spindle_running(ctl)
    assert ctl.stop()
    assert ctl.spindle.on                      # the tool still moves: the spindle keeps turning
    assert ctl.run_until(lambda: ctl.state is MachineState.IDLE, 1.0)
    assert not ctl.spindle.on and ctl.spindle.rpm == 8000   # off; the speed kept for the next start


def test_reset_stops_the_spindle(ctl: MachineController) -> None:
    assert ctl.spindle_on(True, 6000) and ctl.spindle.on
    assert ctl.reset() and not ctl.spindle.on


def test_program_end_stops_the_spindle(ctl: MachineController) -> None:
    start(ctl, "G0 X5 Y0\nM3 S8000\nG1 X10 F1200\nM30\n")
    run_to_idle(ctl)
    assert ctl.last_run.completed and not ctl.spindle.on


def test_estop_and_a_stop_alarm_stop_the_spindle(ctl: MachineController) -> None:
    _spindle_running(ctl)
    ctl.alarm_log.alarm_stop("test: coolant pressure lost", "controller", "test")
    assert ctl.run_until(lambda: ctl.stream.job is None, 1.0)
    assert not ctl.spindle.on
    assert ctl.reset() and ctl.spindle_on(True, 5000)
    assert ctl.estop("test") and not ctl.spindle.on


def _run_time(ctl: MachineController, text: str, percent: float) -> float:
    assert ctl.set_feed_override(percent)
    start(ctl, text)
    run_to_idle(ctl, 60)
    assert ctl.last_run.completed
    assert_within_limits(ctl.last_run.limits)
    return ctl.last_run.cycle_time_s


def test_feed_override_really_scales_a_feed_bound_program(ctl: MachineController) -> None:
    """F600 (10 mm/s) on a machine allowing 30 mm/s, lines and an arc tangent to each other:
    150 % ends at least 25 % sooner, 200 % at least 35 %, every limit held on the way (the
    time scale brakes for each cap ahead along an envelope, not from a worst case far off).
    Each run starts at the origin: the rapid comes in along X, no corner (all but a stop)
    between it and the feed moves."""
    text = "G0 X5 Y0\nG1 X45 F600\nG3 X45 Y40 R20\nG1 X5\nM30\n"

    def run_from_origin(percent: float) -> float:
        start(ctl, "G0 X-1 Y0\nG0 X0\nM30\n")
        run_to_idle(ctl, 60)
        return _run_time(ctl, text, percent)

    base = run_from_origin(100)
    assert run_from_origin(150) <= 0.75 * base
    assert run_from_origin(200) <= 0.65 * base


def test_an_override_the_limits_cap_is_reported(ctl: MachineController) -> None:
    """F1800 is the path limit (30 mm/s): 200 % cannot go faster, and the operator is told so;
    the remaining time is not divided by 2 either."""
    messages: list[str] = []
    ctl.message.connect(messages.append)
    assert ctl.set_feed_override(200)
    start(ctl, "G0 X5 Y0\nG1 X125 F1800\nM30\n")
    ctl.advance(1.5)
    assert any("feed override 200 % capped at 100 %" in m for m in messages), messages
    frac, remaining = ctl.progress
    total = ctl.plan.cycle_time_s
    assert remaining == pytest.approx(total * (1 - frac), rel=0.05)     # at 100 %, not halved
    run_to_idle(ctl)


def test_each_hold_is_named_for_what_it_is(ctl: MachineController) -> None:
    """Single block, M0, M1 and feed hold all stop in HOLD; the operator sees which."""
    from app.machine.model import HoldKind

    assert ctl.set_single_block(True)
    start(ctl, "G0 X5 Y0\nG1 X10 F1200\nM30\n")
    assert ctl.run_until(lambda: ctl.state is MachineState.HOLD, 5)
    assert ctl.hold_kind is HoldKind.SINGLE_BLOCK
    assert ctl.stop() and ctl.run_until(lambda: ctl.state is MachineState.IDLE, 5)
    assert ctl.hold_kind is HoldKind.NONE
    assert ctl.set_single_block(False) and ctl.set_optional_stop(True)
    for code, kind in (("M0", HoldKind.PROGRAM_STOP), ("M1", HoldKind.OPTIONAL_STOP)):
        start(ctl, f"G0 X1 Y0\n{code}\nG0 X2\nM30\n")
        assert ctl.run_until(lambda: ctl.state is MachineState.HOLD, 5)
        assert ctl.hold_kind is kind, (code, ctl.hold_kind)
        assert ctl.resume()
        run_to_idle(ctl)
    start(ctl, "G0 X5 Y0\nG1 X100 F1200\nM30\n")
    ctl.advance(0.5)
    assert ctl.feed_hold() and ctl.hold_kind is HoldKind.FEED_HOLD
    assert ctl.resume()
    ctl.advance(0.5)
    assert ctl.stop() and ctl.hold_kind is HoldKind.STOPPING     # braking along the path
    assert ctl.run_until(lambda: ctl.state is MachineState.IDLE, 5)


def test_a_tool_change_stops_the_spindle_and_it_stays_off_until_the_programs_m3(
        ctl: MachineController) -> None:
    """M6 as LinuxCNC reads it: the spindle stops for the change and stays stopped after cycle
    start until the program's own M3 (at that M3's speed, never the old tool's), and the motion
    waits the spin-up time there."""
    from app.machine.model import HoldKind

    assert ctl.set_tool(Tool(2, 2, (("Z", 0.0),), 6.0, "6 mm flat"))
    start(ctl, "M3 S1000\nG0 X10 Y0\nT2 M6\nG0 X11\nM3 S600\nG1 X20 F600\nM30\n")
    assert ctl.run_until(lambda: ctl.state is MachineState.HOLD, 10)
    assert ctl.hold_kind is HoldKind.TOOL_CHANGE and "insert tool T2" in ctl.state_reason
    assert ctl.tool_in_spindle == 0                                # not before the operator says so
    assert ctl.prompt is not None and (ctl.prompt.kind, ctl.prompt.line, ctl.prompt.tool) == (
        HoldKind.TOOL_CHANGE, 3, 2)
    assert ctl.current_line == 3                                   # the M6 line, not the next move
    assert ctl.run_until(lambda: not ctl.spindle.on, 1.0)
    ctl.advance(2.0)
    assert not ctl.spindle.on and ctl.reference_position[0] == 10.0
    assert ctl.current_line == 3                                   # still, while it waits
    assert ctl.cycle_start()
    assert ctl.prompt is None
    seen: list[tuple[float, float]] = []
    while ctl.reference_position[0] < 11.0:
        ctl.advance(0.01)
        seen.append((ctl.reference_position[0], ctl.spindle.rpm if ctl.spindle.on else 0.0))
    moving = [rpm for x, rpm in seen if x < 11.0]
    assert len(moving) > 10 and all(rpm == 0.0 for rpm in moving)  # the G0 X11 ran with it off
    assert ctl.run_until(lambda: ctl.spindle.on, 1.0)
    assert ctl.spindle.direction == 1 and ctl.spindle.rpm == 600.0
    spinup = ctl.config.controller.spindle_spinup_s
    assert spinup > 0.5
    ctl.advance(spinup - 0.2)
    assert ctl.reference_position[0] == 11.0                       # not yet: spinning up
    run_to_idle(ctl)
    assert ctl.reference_position[0] == 20.0 and not ctl.spindle.on
    assert ctl.tool_in_spindle == 2


def test_m6_of_the_tool_in_the_spindle_changes_nothing(ctl: MachineController) -> None:
    assert ctl.set_tool(Tool(2, 2, (("Z", 0.0),), 6.0, "6 mm flat")) and ctl.set_tool_in_spindle(2)
    said: list[str] = []
    ctl.stateChanged.connect(lambda _state, why: said.append(why))
    start(ctl, "M3 S1000\nG0 X10 Y0\nT2 M6\nG1 X20 F600\nM30\n")
    rpm: list[float] = []
    for _ in range(3000):
        if ctl.state is MachineState.IDLE:
            break
        ctl.advance(0.01)
        rpm.append(ctl.spindle.rpm if ctl.spindle.on else 0.0)
    assert ctl.last_run is not None and ctl.last_run.completed
    on = [i for i, r in enumerate(rpm) if r > 0.0]
    assert on and all(r == 1000.0 for r in rpm[on[0]:on[-1] + 1])   # never stopped for the M6
    assert not any("tool change" in why for why in said), said


def test_a_program_waits_for_the_spindle_to_reach_speed_before_cutting(ctl: MachineController) -> None:
    start(ctl, "G0 X1 Y0\nM3 S1000\nG1 X5 F600\nS800\nG1 X6\nM30\n")
    assert ctl.run_until(lambda: ctl.spindle.on, 5)
    x = ctl.reference_position[0]
    ctl.advance(ctl.config.controller.spindle_spinup_s - 0.2)
    assert ctl.reference_position[0] == x == 1.0
    run_to_idle(ctl)
    # a slower speed needs no wait: the whole run is the moves and the one spin-up, no more,
    # and the estimate (of the load and of the run) counts that one spin-up too
    assert ctl.last_run is not None and ctl.program_info is not None
    run, spinup = ctl.last_run, ctl.config.controller.spindle_spinup_s
    moving = ctl.program_info.plan.cycle_time_s
    assert run.cycle_time_s == pytest.approx(moving + spinup, abs=0.05)
    assert run.estimated_s == pytest.approx(moving + spinup, abs=1e-9)
    assert ctl.program_info.cycle_time_s == pytest.approx(moving + spinup, abs=1e-9)


def test_the_time_left_counts_the_spin_ups_ahead(ctl: MachineController) -> None:
    """Time left at the start: the moves and both spin-ups (the start, and the speed-up from
    800 to 900 rpm; the slow-down to 800 waits for nothing)."""
    seen: list[float] = []
    ctl.progressChanged.connect(lambda _frac, left: seen.append(left))
    spinup = ctl.config.controller.spindle_spinup_s
    start(ctl, "G0 X1 Y0\nM3 S1000\nG1 X5 F600\nS800\nG1 X6\nS900\nG1 X7\nM30\n")
    info = ctl.program_info
    assert info is not None
    assert info.cycle_time_s == pytest.approx(info.plan.cycle_time_s + 2 * spinup, abs=1e-9)
    assert ctl.run_until(lambda: bool(seen), 5)
    assert seen[0] == pytest.approx(info.plan.cycle_time_s + 2 * spinup, abs=0.1)
    assert ctl.run_until(lambda: ctl.reference_position[0] > 6.5, 30)
    assert ctl.run_until(lambda: len(seen) > 1 and seen[-1] < info.plan.cycle_time_s, 5)
    assert seen[-1] < 0.5 * spinup  # past both spin-ups: only the moves are left


def test_spin_ups_are_starts_reversals_and_speed_ups_and_a_tool_change_leaves_it_stopped() -> None:
    from app.machine.model import SpindleState
    from app.machine.motion.spinup import spin_up_waits
    from app.machine.motion.timescale import PausePoint
    from planner.core.program import Dwell, SpindleSpeed, ToolNumber

    def at(tau: float, kind: str, payload: object) -> PausePoint:
        return PausePoint(tau, kind, 1, 0, payload)

    def turn(rpm: float) -> SpindleSpeed:
        return SpindleSpeed(int(np.sign(rpm)), abs(rpm))

    pauses = [at(1, "spindle", turn(1000)), at(2, "spindle", turn(800)), at(3, "tool_change", ToolNumber(2)),
              at(4, "spindle", turn(-800)), at(5, "spindle", turn(0)), at(6, "tool_change", ToolNumber(3)),
              at(7, "dwell", Dwell(2.0)), at(8, "spindle", turn(900))]
    # 1000: a start; 800: slower; M6: stopped, not started again; -800: a start; 900 after the
    # second M6 and a dwell: a start
    assert spin_up_waits(pauses, SpindleState(), 2.5) == [(1, 2.5), (4, 2.5), (8, 2.5)]
    # already turning at the programmed speed when the program starts: no wait at its M3
    assert spin_up_waits(pauses[:2], SpindleState(1, 1000.0), 2.5) == []
    assert spin_up_waits(pauses, SpindleState(), 0.0) == []


def test_spindle_override_scales_the_commanded_speed_within_the_maximum(ctl: MachineController) -> None:
    messages: list[str] = []
    ctl.message.connect(messages.append)
    assert ctl.mdi("M3 S10000")
    assert ctl.set_spindle_override(120)
    assert ctl.spindle.commanded_rpm == pytest.approx(12000.0) and ctl.spindle.rpm == 10000.0
    assert ctl.mdi("S20000")                             # S alone changes the running spindle
    assert ctl.spindle.rpm == 20000.0 and ctl.spindle.direction == 1
    assert ctl.set_spindle_override(150)                 # 30,000 > 24,000 rpm: capped, and said
    assert ctl.spindle.commanded_rpm == pytest.approx(24000.0)
    assert any("capped at 120 %" in m for m in messages)
    for bad in (40, 151, float("nan")):
        r = ctl.set_spindle_override(bad)
        assert not r and "50-150 %" in r.reason


def test_a_program_leaves_its_offsets_and_parameters_with_the_machine(qapp, config_path: Path,
                                                                       state_dir: Path) -> None:
    """G10 L2, G92 and G28.1 take effect where the motion reaches them, are kept in the state
    folder (the next controller starts from them), and make the loaded program stale."""
    ctl = make_controller(config_path, state_dir)
    try:
        text = "G21 G90 F600\nG0 X1 Y1\nG10 L2 P2 X10 Y20\nG92 X5\nG28.1\nG0 X2\nM2\n"
        assert ctl.load_program(text, "offsets.ngc", wait=True)
        assert ctl.cycle_start()
        run_to_idle(ctl)
        assert ctl.work_offsets["G55"][:2] == (10.0, 20.0)
        params = ctl.coordinates.parameters
        assert params[5210] == 1.0 and params[5211] == -4.0 and (params[5161], params[5162]) == (1.0, 1.0)
        assert "changed since it was loaded" in ctl.loader.program_stale()
        np.testing.assert_allclose(ctl.reference_position[:2], (-2.0, 1.0))    # X2 with G92: 2 - 4
        ctl.advance(0.1)
        assert ctl.work_position[0] == pytest.approx(2.0, abs=1e-3)            # as the program reads it
        saved = json.loads((state_dir / "parameters.json").read_text())
        assert saved["5211"] == -4.0
    finally:
        ctl.shutdown()
    again = make_controller(config_path, state_dir, zero=False)
    try:
        assert again.coordinates.parameters[5211] == -4.0 and again.work_offsets["G55"][:2] == (10.0, 20.0)
        assert again.g92_offset is not None and again.g92_offset[0] == -4.0
        assert again.clear_g92()
        assert again.g92_offset is None and again.coordinates.parameters[5211] == 0.0
        assert again.mdi("G92 X1") and again.coordinates.parameters[5210] == 1.0
        assert again.mdi("G92.1")
        assert again.coordinates.parameters[5210] == 0.0 and again.coordinates.parameters[5211] == 0.0
    finally:
        again.shutdown()


def test_program_outputs_share_the_drive_word_with_the_spindle_and_go_off_on_estop(
        qapp, tmp_path: Path, state_dir: Path) -> None:
    """M64/M65 and a user M-code switch their bit of 0x60FE:1 where the motion reaches them,
    next to the spindle's bits of the same drive; E-stop switches them off."""
    from resources import shipped_machine

    config = tmp_path / "outputs.toml"
    config.write_text(shipped_machine("xyz_mill").read_text(encoding="utf-8") +
                      '\n[[outputs]]\nnumber = 1\ndrive = 0\nbit = 4\nname = "vacuum"\n'
                      '[[mcodes]]\ncode = 110\naction = "output"\noutput = 1\non = false\n', encoding="utf-8")
    ctl = make_controller(config, state_dir)
    try:
        def word() -> int:
            ctl.advance(0.01)
            return ctl.worker.snapshot().digital_outputs[0]

        assert ctl.mdi("M3 S1000") and word() == 0b00001
        assert ctl.load_program("G21 G90 F600\nG1 X1\nM64 P1\nG1 X2\nM2\n", "out.ngc", wait=True)
        assert ctl.cycle_start()
        run_to_idle(ctl)
        assert word() == 0b10000                    # program end: spindle off, the vacuum stays on
        assert ctl.mdi("M3 S1000") and word() == 0b10001
        assert ctl.mdi("M110") and word() == 0b00001   # the user M-code switches it off
        assert ctl.mdi("M64 P1") and word() == 0b10001
        ctl.estop("test")
        assert word() == 0b00000
    finally:
        ctl.shutdown()


def test_g10_tool_data_reaches_the_tool_table(ctl: MachineController, state_dir: Path) -> None:
    """G10 L10 in a program sets the tool's length where the motion reaches it; the table is saved
    and the loaded program is checked again before the next start."""
    from planner.core.tools import Tool

    assert ctl.tools.set_tool(Tool(1, 1, (("Z", 10.0),), 6.0, "end mill"))
    assert ctl.load_program("G21 G90 F600\nG0 Z30\nG10 L10 P1 Z5\nG0 Z31\nM2\n", "g10.ngc", wait=True)
    assert ctl.cycle_start()
    run_to_idle(ctl)
    assert ctl.tools.table.get(1).length_mm == 25.0
    assert "T1 P1 Z25" in (state_dir / "tools.tbl").read_text()
    assert "tool table changed" in ctl.loader.program_stale()


def test_work_position_reads_as_the_program_in_a_rotated_system(ctl: MachineController) -> None:
    """After a program rotates G54 (G10 L2 R90), the displayed work position is the program's."""
    assert ctl.load_program("G21 G90 F600\nG10 L2 P1 X10 Y0 R90\nG1 X3 Y1\nM2\n", "rot.ngc", wait=True)
    assert ctl.cycle_start()
    run_to_idle(ctl)
    ctl.advance(0.1)
    np.testing.assert_allclose(ctl.machine_position[:2], (9.0, 3.0), atol=1e-3)
    np.testing.assert_allclose(ctl.work_position[:2], (3.0, 1.0), atol=1e-3)


def test_program_messages_reach_the_operator_where_the_motion_is(ctl: MachineController) -> None:
    """(MSG,...) and (DEBUG,...) texts appear on the status line and in the alarm log when the
    motion reaches their line, in program order; the rest at the end; MDI's at once."""
    shown: list[str] = []
    ctl.message.connect(shown.append)
    text = "G21 G90 F600\n(MSG, roughing)\nG1 X2\n#<n> = 3\n(DEBUG, passes #<n>)\nG1 X4\n(MSG, done)\nM2\n"
    assert ctl.load_program(text, "msg.ngc", wait=True)
    assert ctl.cycle_start()
    run_to_idle(ctl)
    program_texts = [s for s in shown if s in ("roughing", " passes 3.000000", "done")]
    assert program_texts == ["roughing", " passes 3.000000", "done"]
    assert [a.cause for a in ctl.alarms if a.source == "program"][-3:] == program_texts
    assert ctl.mdi("(MSG, hello)") and "hello" in shown[-2:]


def test_g64_p_corners_are_blended_and_run_to_the_exact_end(ctl: MachineController) -> None:
    """A zigzag of 4 degree turns under G64 P0.02: the loaded program is the blended one (what
    the preview, progress and a resume count), it runs within every limit to its exact end,
    sooner than the same path with G61.1, and a hold inside it resumes on the same curve."""
    zigzag = "".join(f"X{5 + 10 * i} Y{0.35 * (i % 2):.2f}\n" for i in range(1, 9))
    text = "G0 X5 Y0\nG64 P0.02\nG1 F1800\n" + zigzag + "M30\n"
    assert ctl.load_program(text.replace("G64 P0.02", "G61.1"), wait=True)
    sharp_s = ctl.program_info.cycle_time_s
    assert ctl.load_program(text, wait=True)
    info = ctl.program_info
    kinds = [m.kind.name for m in info.program.moves]
    assert kinds.count("BLEND") >= 5
    assert info.move_count == len(kinds)
    assert info.cycle_time_s < 0.99 * sharp_s  # measured: 2.96 s against 3.04 s
    first = kinds.index("BLEND")
    blend = info.program.moves[first]
    assert ctl.cycle_start()
    ctl.advance(float(info.plan.t0[first]) + 0.01)   # the hold ramp ends on the blend
    assert ctl.feed_hold()
    ctl.advance(0.6)
    held = np.array(ctl.reference_position)
    on_curve = blend.evaluate(np.linspace(0.0, blend.length_mm, 20001))[0]
    assert np.sqrt(((on_curve - held) ** 2).sum(axis=1)).min() < 1e-3   # on the blend,
    corner = np.array([15.0, 0.35, 0.0])
    off = min(float(np.linalg.norm(np.cross(held - corner, d))) / float(np.linalg.norm(d))
              for d in (corner - (5.0, 0.0, 0.0), (25.0, 0.0, 0.0) - corner))
    assert 1e-4 < off <= 0.02                                            # off the programmed lines
    assert ctl.resume()
    run_to_idle(ctl)
    s = ctl.last_run
    assert s.completed
    np.testing.assert_array_equal(ctl.reference_position, (85.0, 0.35 * (8 % 2), 0.0))
    assert_within_limits(s.limits)


def test_block_delete_is_off_as_linuxcnc_starts_and_reads_the_program_again_when_switched(
        ctl: MachineController) -> None:
    """Lines starting with '/' run until the operator switches block delete on; the loaded
    program is then checked again without them (its path, its moves), and a switch during a
    run is refused with the reason, the run keeping the lines it was read with."""
    modes: list[tuple[bool, bool, bool]] = []
    ctl.modesChanged.connect(lambda *m: modes.append(m))
    text = "G1 X5 F1800\n/G1 Y20\nG1 X10\nM30\n"
    assert not ctl.block_delete
    assert ctl.load_program(text, wait=True)
    assert ctl.program_info is not None and ctl.program_info.move_count == 3
    assert ctl.set_block_delete(True)
    assert modes[-1] == (False, False, True) and ctl.snapshot().block_delete
    assert ctl.loader.wait_loaded()
    assert ctl.program_info is not None and ctl.program_info.move_count == 2
    assert ctl.cycle_start()
    refused = ctl.set_block_delete(False)
    assert not refused and "before cycle start" in refused.reason
    assert ctl.block_delete and modes[-1] == (False, False, True)
    run_to_idle(ctl)
    np.testing.assert_array_equal(ctl.reference_position, (10.0, 0.0, 0.0))   # Y20 skipped
    assert ctl.set_block_delete(False)
    assert ctl.loader.wait_loaded() and ctl.program_info.move_count == 3
    assert ctl.mdi("/G0 X0") and not ctl.block_delete
    run_to_idle(ctl)
    assert ctl.reference_position[0] == 0.0


def test_block_delete_switched_while_a_program_is_checked_is_caught_at_cycle_start(
        ctl: MachineController) -> None:
    text = "G1 X5 F1800\n/G1 Y20\nG1 X10\nM30\n"
    assert ctl.load_program(text)                 # checked in the background
    assert ctl.set_block_delete(True)             # meanwhile: that check read the '/' line
    assert ctl.loader.wait_loaded()
    assert ctl.loader.program_stale() == "block delete was switched since it was loaded"
    assert ctl.cycle_start(wait=True)             # checked again first, then run
    run_to_idle(ctl)
    np.testing.assert_array_equal(ctl.reference_position, (10.0, 0.0, 0.0))


def test_a_program_has_as_many_lines_as_an_editor_shows(ctl: MachineController) -> None:
    """1,000 lines each ended by a line end are 1,000 lines (not 1,001), as with no end on the last."""
    body = "".join(f"G1 X{i % 50} F600\n" for i in range(1000))
    assert ctl.load_program(body, wait=True)
    assert ctl.program_info.line_count == 1000
    assert ctl.load_program(body.rstrip("\n"), wait=True)
    assert ctl.program_info.line_count == 1000
