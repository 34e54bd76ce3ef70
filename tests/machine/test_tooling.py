"""The controller's tool table and tool in the spindle: edited, persisted, read by programs
(G43 at check time), and safe when its file is damaged."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from app.machine.controller import MachineController
from app.machine.errors import ConfigError
from app.machine.model import MachineState
from planner.core.tools import Tool
from tests.machine.conftest import make_controller, run_to_idle, trace

T1 = Tool(1, 1, (("Z", 40.0),), 6.0, "6 mm flat")


def test_g43_moves_by_the_tools_length_and_a_table_change_rechecks_the_program(
        ctl: MachineController) -> None:
    assert ctl.set_tool(T1) and ctl.set_tool_in_spindle(1)
    assert ctl.load_program("G43\nG0 Z5\nM30\n", wait=True)
    assert ctl.cycle_start(wait=True)
    run_to_idle(ctl)
    assert ctl.reference_position[2] == pytest.approx(45.0)          # 5 above the work, 40 mm tool
    assert ctl.mdi("G0 Z0") and run_to_idle(ctl) is None
    assert ctl.set_tool(T1.with_offset("Z", 20.0))
    assert "tool table changed" in ctl.loader.program_stale()
    assert ctl.cycle_start(wait=True)                               # checked again, then run
    run_to_idle(ctl)
    assert ctl.reference_position[2] == pytest.approx(25.0)


def test_a_program_with_an_unknown_tool_is_refused_at_its_line(ctl: MachineController) -> None:
    r = ctl.load_program("G0 Z5\nT3 M6\nM30\n", wait=True)
    assert not r and "T3 is not in the tool table" in r.reason
    assert ctl.program_info is None


def test_the_table_and_the_tool_in_the_spindle_survive_a_restart(qapp, config_path: Path,
                                                                state_dir: Path) -> None:
    ctl = make_controller(config_path, state_dir)
    try:
        assert ctl.set_tool(T1) and ctl.set_tool(Tool(7, 3, (("Z", -1.5),), 3.0, "ball"))
        assert ctl.load_program("T7 M6\nG0 X1\nM30\n", wait=True) and ctl.cycle_start(wait=True)
        assert ctl.run_until(lambda: ctl.state is MachineState.HOLD, 5)
        assert ctl.cycle_start()                                   # the tool is in
        run_to_idle(ctl)
        assert ctl.tool_in_spindle == 7
    finally:
        ctl.shutdown()
    assert (state_dir / "tools.tbl").read_text() == "T1 P1 Z40 D6 ;6 mm flat\nT7 P3 Z-1.5 D3 ;ball\n"
    again = make_controller(config_path, state_dir)
    try:
        assert [t.number for t in again.tool_table] == [1, 7] and again.tool_in_spindle == 7
    finally:
        again.shutdown()


def test_a_damaged_tool_table_is_set_aside_and_said_never_guessed(qapp, config_path: Path,
                                                                 state_dir: Path) -> None:
    (state_dir / "tools.tbl").write_text("T1 P1 Z40\nT1 Z3\n")
    (state_dir / "tool.json").write_text('{"in_spindle": 1}')
    ctl = make_controller(config_path, state_dir)
    try:
        assert len(ctl.tool_table) == 0 and ctl.tool_in_spindle == 0
        texts = [a.cause for a in ctl.alarms]
        assert any("tools.tbl:2: T1 is given twice" in t and "moved aside" in t for t in texts), texts
        assert list(state_dir.glob("tools.tbl.damaged-*"))
        assert not ctl.load_program("G43 H1\nG0 Z5\n", wait=True)   # no silent zero offset
    finally:
        ctl.shutdown()


def test_touch_off_sets_the_length_so_the_work_z_reads_the_surface(ctl: MachineController) -> None:
    assert ctl.set_tool(T1)
    assert ctl.set_work_offset("G54", (0.0, 0.0, -50.0))
    assert ctl.mdi("G53 G0 Z-20") and run_to_idle(ctl) is None
    assert ctl.touch_off_tool(1, 2.0)                               # the tip on a 2 mm block
    assert ctl.tool_table.get(1).length_mm == pytest.approx(-20.0 + 50.0 - 2.0)   # 28 mm
    assert not ctl.touch_off_tool(9)


def test_the_table_cannot_change_while_a_program_runs(ctl: MachineController) -> None:
    assert ctl.set_tool(T1)
    assert ctl.load_program("G1 X50 F600\nM30\n", wait=True) and ctl.cycle_start(wait=True)
    ctl.advance(0.2)
    for r in (ctl.set_tool(T1.with_offset("Z", 1.0)), ctl.remove_tool(1), ctl.set_tool_in_spindle(1),
              ctl.touch_off_tool(1)):
        assert not r and "while the machine is running" in r.reason
    assert ctl.tool_table.get(1) == T1
    run_to_idle(ctl)


def test_the_tool_in_the_spindle_cannot_be_removed_and_m61_in_mdi_sets_it(ctl: MachineController) -> None:
    assert ctl.set_tool(T1)
    assert ctl.mdi("M61 Q1") and ctl.tool_in_spindle == 1
    r = ctl.remove_tool(1)
    assert not r and "in the spindle" in r.reason
    assert ctl.mdi("M61 Q0") and ctl.remove_tool(1) and len(ctl.tool_table) == 0


def test_importing_a_tbl_replaces_the_table_or_nothing(ctl: MachineController, tmp_path: Path) -> None:
    good, bad = tmp_path / "good.tbl", tmp_path / "bad.tbl"
    good.write_text("T4 P4 Z12.5 D8 ;8 mm\nT5 P5 Z3 ;drill\n")
    bad.write_text("T6 P6 Z1\nT7 P7 K2\n")
    assert ctl.import_tool_table(str(good)) and [t.number for t in ctl.tool_table] == [4, 5]
    r = ctl.import_tool_table(str(bad))
    assert not r and "bad.tbl:2:7: K is not a tool table word" in r.reason
    assert [t.number for t in ctl.tool_table] == [4, 5]


def test_a_program_without_motion_is_refused_not_left_running(ctl: MachineController) -> None:
    assert ctl.set_tool(T1)
    r = ctl.load_program("T1 M6\nM30\n", wait=True)
    assert not r and "moves no axis" in r.reason and ctl.program_info is None
    assert ctl.state is MachineState.IDLE


def test_run_from_line_needs_the_tool_the_program_has_there(ctl: MachineController) -> None:
    assert ctl.set_tool(T1) and ctl.set_tool(Tool(2, 2, (("Z", 10.0),), 3.0, "ball"))
    assert ctl.set_tool_in_spindle(1)
    assert ctl.load_program("G0 X1\nT2 M6\nG43\nG1 X5 F600\nG1 Y5\nM30\n", wait=True)
    r = ctl.run_from_line(5, wait=True)
    assert not r and "line 5 needs T2 in the spindle (T1 is in it)" in r.reason and "M6 line 2" in r.reason
    assert ctl.state is MachineState.IDLE
    assert ctl.set_tool_in_spindle(2)
    assert ctl.run_from_line(5, wait=True)
    run_to_idle(ctl, 40)
    assert ctl.reference_position[:2] == pytest.approx((5.0, 5.0))


def test_the_restart_preview_is_the_way_run_from_line_takes(ctl: MachineController) -> None:
    assert ctl.load_program("G0 Z5\nG0 X10 Y0\nG1 Z-1 F300\nG1 X20\nM30\n", wait=True)
    assert ctl.mdi("G0 X30 Y30 Z-1") and run_to_idle(ctl) is None
    preview = ctl.restart_preview(4)
    assert not isinstance(preview, str)
    top = ctl.config.machine.axes[2].max_pos
    assert preview.line == 4 and preview.clearance_mm == top
    assert [tuple(p) for p in preview.path] == [(30.0, 30.0, -1.0), (30.0, 30.0, top), (10.0, 0.0, top),
                                       (10.0, 0.0, 5.0), (10.0, 0.0, -1.0)]
    assert isinstance(ctl.restart_preview(99), str)


def test_measuring_on_the_setter_needs_the_tool_in_the_spindle_and_a_setter(
        qapp, config_path, state_dir) -> None:
    ctl = make_controller(config_path, state_dir)
    try:
        assert ctl.set_tool(T1)
        r = ctl.measure_tool(1)
        assert not r and "T1 is not in the spindle" in r.reason
        assert not ctl.measure_tool(9)
        assert ctl.set_tool_in_spindle(1)
        assert ctl.mdi("G0 X10")
        r = ctl.measure_tool(1)                                # moving
        assert not r and "machine is" in r.reason
    finally:
        ctl.shutdown()
    text = config_path.read_text().replace("setter_x_mm = -230.0", "")
    config_path.write_text(text)
    with pytest.raises(ConfigError, match="setter_x_mm, setter_y_mm and setter_z_mm together"):
        make_controller(config_path, state_dir, connect=False)


def test_a_measurement_without_contact_leaves_the_length_as_it_was(qapp, config_path, state_dir) -> None:
    """The setter's surface below the simulated stylus' reach: the first probe ends without
    contact (an alarm), and the table keeps the length it had."""
    text = config_path.read_text().replace("sim_surface_mm = -50.0", "sim_surface_mm = -140.0")
    config_path.write_text(text)
    ctl = make_controller(config_path, state_dir)
    try:
        assert ctl.set_tool(T1) and ctl.set_tool_in_spindle(1)
        assert ctl.measure_tool(1)
        assert ctl.run_until(lambda: ctl.state is MachineState.ALARM, 60)
        assert ctl.run_until(lambda: ctl.stream.job is None, 10)
        assert ctl.tool_table.get(1).length_mm == 40.0
        assert any("the probe move ended without contact" in a.cause for a in ctl.active_alarms)
    finally:
        ctl.shutdown()


def test_a_tool_length_longer_than_the_z_travel_is_refused_with_why(ctl: MachineController) -> None:
    span = ctl.config.machine.axes[2].max_pos - ctl.config.machine.axes[2].min_pos
    r = ctl.set_tool(Tool(4, 4, (("Z", span + 1.0),), 6.0))
    assert not r and "longer than the Z travel" in r.reason and 4 not in ctl.tool_table
    assert ctl.set_tool(Tool(4, 4, (("Z", span - 1.0),), 6.0))
    assert ctl.set_tool_in_spindle(4)
    # touched off on a surface far below anything reachable: the length it gives is refused
    r = ctl.touch_off_tool(4, -10.0 * span)
    assert not r and "longer than the Z travel" in r.reason
    assert ctl.tool_table.get(4).length_mm == span - 1.0          # kept as it was


def test_touch_off_length_counts_g92_like_the_work_position(ctl: MachineController) -> None:
    assert ctl.set_tool(T1) and ctl.set_tool_in_spindle(1)
    assert ctl.mdi("G53 G0 Z-50") and run_to_idle(ctl) is None
    assert ctl.mdi("G92 Z3") and run_to_idle(ctl) is None    # this point reads Z3 (tool's 40 mm included)
    # the tip on a surface at work Z 0: the length is the machine Z less the work Z of the gauge line
    assert ctl.touch_off_tool(1, 0.0)
    g5x = ctl.work_offsets["G54"][2]
    g92 = ctl.g92_offset[2]
    assert ctl.tool_table.get(1).length_mm == pytest.approx(-50.0 - g5x - g92, abs=1e-6)
    # with that length the tip reads 0 here
    assert ctl.work_position[2] == pytest.approx(0.0, abs=1e-3)


def _measured(ctl: MachineController, number: int = 1) -> float:
    assert ctl.measure_tool(number)
    assert ctl.run_until(lambda: ctl.state is not MachineState.RUNNING and ctl.stream.job is None, 60)
    assert not ctl.active_alarms, [a.cause for a in ctl.active_alarms]
    return ctl.tool_table.get(number).length_mm


def test_the_setter_measures_fifty_times_in_a_row_without_a_failure(qapp, config_path: Path,
                                                                    state_dir: Path) -> None:
    # the clearance height just above the stylus' surface: 50 measurements in seconds
    text = config_path.read_text().replace("[controller]", "[controller]\nrestart_clearance_mm = -40.0", 1)
    config_path.write_text(text)
    ctl = make_controller(config_path, state_dir)
    try:
        assert ctl.set_tool(T1) and ctl.set_tool_in_spindle(1)
        lengths = [_measured(ctl) for _ in range(50)]
    finally:
        ctl.shutdown()
    # the simulated stylus touches at machine Z-50, the setter's gauge line is at Z-60
    assert lengths == pytest.approx([10.0] * 50, abs=2e-3)


def test_a_stop_that_comes_late_after_the_first_contact_still_measures(ctl: MachineController) -> None:
    """A busy computer: the motion is told of the contact only 4 mm past it (the latch itself
    holds the true contact, as the drive latches it). The move up starts from the contact,
    not from where the motion stopped, so the slow probe starts clear of the setter."""
    latch = ctl.drives.probe_latched
    k = ctl.axes.index("Z")

    def late() -> tuple[float, ...] | None:
        found = latch()
        if found is None:
            return None
        here = ctl.drives.snapshot().reference_position[k]
        return found if here <= found[k] - 4.0 else None      # drive units, Z going down

    ctl.drives.probe_latched = late  # type: ignore[method-assign]
    assert ctl.set_tool(T1) and ctl.set_tool_in_spindle(1)
    assert _measured(ctl) == pytest.approx(10.0, abs=2e-3)
    assert _measured(ctl) == pytest.approx(10.0, abs=2e-3)


def test_the_state_says_which_tool_is_measured_and_an_error_names_the_step(ctl: MachineController) -> None:
    states: list[tuple[str, str]] = []
    ctl.stateChanged.connect(lambda s, why: states.append((s.value, why)))
    assert ctl.set_tool(T1) and ctl.set_tool_in_spindle(1)
    assert ctl.measure_tool(1)
    assert ("running", "measuring tool T1") in states
    assert ctl.run_until(lambda: ctl.stream.job is None, 60)
    # the probe input reads "touching" when the fast probe starts: refused, named by its step
    ctl.drives.arm_probe = lambda *_a: False  # type: ignore[method-assign]
    assert ctl.measure_tool(1)
    assert ctl.run_until(lambda: ctl.state is MachineState.ALARM, 60)
    causes = [a.cause for a in ctl.active_alarms]
    assert any("G38.2 (the fast probe down to the setter): the probe already touches where the move starts"
               in c for c in causes), causes
    assert not any("(line " in c for c in causes), causes


def _measuring(config_path: Path, tolerance_mm: float) -> None:
    """[toolchange] measure = true (and the clearance just above the simulated stylus' surface,
    Z-50, for speed)."""
    text = config_path.read_text().replace("[controller]", "[controller]\nrestart_clearance_mm = -40.0", 1)
    config_path.write_text(text + f"\n[toolchange]\nmeasure = true\nbroken_tolerance_mm = {tolerance_mm}\n")


M6_PROGRAM = "G21 G90 G54\nT2 M6\nG43 H2\nG0 X5 Y5 Z5\nM30\n"


def test_m6_measures_the_new_tool_and_the_program_goes_on_with_its_length(
        qapp, config_path: Path, state_dir: Path) -> None:
    """After the operator's change, the new tool is measured on the setter (the shipped
    tool_measure.ngc, called after M6 as LinuxCNC's REMAP does), its length written, and
    the program's G43 H2 uses it: the simulated stylus touches at Z-50, the setter's gauge line
    is at Z-60, so any tool measures 10 mm."""
    _measuring(config_path, 0.5)
    ctl = make_controller(config_path, state_dir)
    try:
        assert ctl.set_tool(T1) and ctl.set_tool_in_spindle(1)
        assert ctl.set_tool(Tool(2, 2, (("Z", 10.3),), 8.0, "8 mm"))
        assert ctl.load_program(M6_PROGRAM, wait=True) and ctl.cycle_start(wait=True)
        assert ctl.run_until(lambda: ctl.state is MachineState.HOLD, 10)
        assert ctl.state_reason.endswith("; T2 (8 mm) is then measured on the tool setter"), ctl.state_reason
        assert ctl.cycle_start()                                    # T2 is in
        run_to_idle(ctl, 60.0)
        assert ctl.last_run is not None and ctl.last_run.completed, ctl.state_reason
        length = ctl.tool_table.get(2).length_mm
        assert length == pytest.approx(10.0, abs=2e-3)
        assert ctl.tool_in_spindle == 2
        # G43 H2 with the measured length: the tip at work Z5
        g5x = ctl.work_offsets["G54"][2]
        assert ctl.reference_position[2] == pytest.approx(5.0 + g5x + length, abs=1e-3)
        # it went to the setter: machine X, Y of the setter, down to the stylus' surface
        t = trace(ctl)["reference"]
        at_setter = np.flatnonzero((np.abs(t[:, 0] + 230.0) < 1e-3) & (np.abs(t[:, 1] + 180.0) < 1e-3))
        assert len(at_setter) and t[at_setter, 2].min() < -50.0 + 1e-3
    finally:
        ctl.shutdown()


def test_a_broken_tool_stops_the_program_and_keeps_the_table(qapp, config_path: Path,
                                                             state_dir: Path) -> None:
    """T2's table length 12 mm, measured 10 mm: more than the 0.5 mm tolerance, an alarm
    that says so; the table keeps 12 and nothing after the M6 runs."""
    _measuring(config_path, 0.5)
    ctl = make_controller(config_path, state_dir)
    try:
        assert ctl.set_tool(T1) and ctl.set_tool_in_spindle(1)
        assert ctl.set_tool(Tool(2, 2, (("Z", 12.0),), 8.0, "8 mm"))
        assert ctl.load_program(M6_PROGRAM, wait=True) and ctl.cycle_start(wait=True)
        assert ctl.run_until(lambda: ctl.state is MachineState.HOLD, 10)
        assert ctl.cycle_start()
        assert ctl.run_until(lambda: ctl.state is MachineState.ALARM, 60), ctl.state_reason
        assert ctl.run_until(lambda: ctl.stream.job is None, 10)
        (alarm,) = [a for a in ctl.active_alarms if "broken or wrong tool" in a.cause]
        assert "with the result, tool_measure.ngc line" in alarm.cause, alarm.cause
        measured = float(re.search(r"T2\.0+ measures (-?\d+\.\d+) mm", alarm.cause).group(1))
        assert measured == pytest.approx(10.0, abs=2e-3) and "the table says 12.0" in alarm.cause
        assert ctl.tool_table.get(2).length_mm == 12.0
        assert ctl.last_run is not None and not ctl.last_run.completed
        t = trace(ctl)["reference"]
        assert not np.any((np.abs(t[:, 0] - 5.0) < 1e-3) & (np.abs(t[:, 1] - 5.0) < 1e-3))  # never at X5 Y5
    finally:
        ctl.shutdown()


def test_without_measure_m6_reads_as_before(ctl: MachineController) -> None:
    """The default: no call after M6, the table's length as it is."""
    assert ctl.config.machine.after_tool_change == ""
    assert ctl.set_tool(T1) and ctl.set_tool_in_spindle(1)
    assert ctl.set_tool(Tool(2, 2, (("Z", 12.0),), 8.0, "8 mm"))
    assert ctl.load_program(M6_PROGRAM, wait=True)
    assert not ctl.program_info.program.probes


def test_the_measuring_routine_s_probe_moves_are_not_taken_for_cuts_with_the_spindle_stopped(
        qapp, config_path: Path, state_dir: Path) -> None:
    """With the tool measured after each M6, its G38.2 moves are feed moves made with the
    spindle stopped on purpose: no question about them; a real cut without M3 is still asked."""
    _measuring(config_path, 0.5)
    ctl = make_controller(config_path, state_dir)
    try:
        assert ctl.set_tool(T1) and ctl.set_tool_in_spindle(1)
        assert ctl.set_tool(Tool(2, 2, (("Z", 10.3),), 8.0, "8 mm"))
        assert ctl.load_program(M6_PROGRAM, wait=True)
        assert ctl.program_info is not None and ctl.program_info.warnings == ()
        assert ctl.load_program("G21 G90 G54\nT2 M6\nG43 H2\nG0 X5 Y5 Z5\nG1 X10 F100\nM30\n", wait=True)
        warnings = ctl.program_info.warnings
        assert [(w.line, "feed move with the spindle stopped" in w.message) for w in warnings] == [(5, True)]
    finally:
        ctl.shutdown()
