"""Main flows on the real controller with simulated drives (manual clock: fast, deterministic)."""

from __future__ import annotations

import pytest
from PySide6.QtWidgets import QLabel

from app.context import PanelOptions
from tests.app.conftest import make_window

SHORT = "G21 G90 G17\nG00 X1 Y1\nG01 X5 Y2 F1200\nG02 X7 Y4 R2\nM30\n"
LONG_LINE = "G21 G90 G17\nG01 X40 F600\nM30\n"   # 4 s at 10 mm/s
BAD = "G21 G90 G17\nG01 X5 F600\nG02 X20 Y0 R2\nM30\n"  # line 3: radius too small


def state(controller) -> str:
    return controller.state.value


def test_demo_starts_connected_unhomed_and_homes_to_its_switches(qtbot, qapp, state_dir, dialogs,
                                                                  real_controller) -> None:
    """The demo machine has home switches: it starts connected with the pocket loaded and not
    homed (cycle start says so); Home all on Machine zero homes Z, then X and Y together, to
    their switches, the page naming the step, and the axes end at their home positions."""
    c = real_controller
    window = make_window(qtbot, qapp, PanelOptions(demo=True, state_dir=state_dir), dialogs, c)
    qtbot.waitUntil(lambda: c.program_info is not None, timeout=20000)
    assert state(c) == "idle" and not any(c.homed)
    assert c.program_info.name == "pocket.nc"
    assert "not homed" in c.refusal("cycle_start")
    assert not window.page("auto").buttons["start"].isEnabled()
    page = window.page("machine_zero")
    steps: list[str] = []
    c.stateChanged.connect(lambda _s, _r: steps.append(page.step_label.text()))
    page.home_all_button.click()
    assert state(c) == "homing"
    assert c.run_until(lambda: state(c) == "idle" and all(c.homed), timeout_s=120)
    z_first = [t for t in steps if "searching the switch" in t]
    assert z_first[0].startswith("homing Z") and any("X searching" in t and "Y searching" in t for t in steps)
    assert any("latching" in t for t in steps)
    assert c.machine_position == pytest.approx((0.0, 0.0, 0.0), abs=1e-9)
    assert window.page("auto").buttons["start"].isEnabled()
    assert "pocket" in window.page("program").title.text()
    assert window.page("preview").plot.path.all.count == len(c.program_info.program.moves)


def test_run_program_to_the_end(demo_window, real_controller) -> None:
    c = real_controller
    assert c.load_program(SHORT, name="short.nc", wait=True)
    auto = demo_window.page("auto")
    auto.buttons["start"].click()
    assert state(c) == "running"
    assert c.run_until(lambda: state(c) == "idle", timeout_s=30)
    dro = demo_window.header.dro
    assert dro.machine_text("X") == "+7.000" and dro.machine_text("Y") == "+4.000"
    assert dro.work_text("X") == "+7.000"
    assert demo_window.header.state_label.text() == "Idle"
    assert auto.progress.value() == 1000
    preview = demo_window.page("preview").plot
    x, y = preview.tool_item.getData()
    assert (x[0], y[0]) == pytest.approx((7.0, 4.0), abs=1e-3)
    diagnostics = demo_window.page("diagnostics")
    assert len(diagnostics.tracking.buffer) > 5  # live reference/actual samples arrived
    table = diagnostics.tracking.table
    assert table.item(0, 0).text() not in ("---", "")  # RMSE of X after the run (Table 4)
    assert diagnostics.bus.table.rowCount() == 3 + 5   # three drives, a coupler and four terminals


def test_feed_hold_and_resume(demo_window, real_controller) -> None:
    c = real_controller
    assert c.load_program(LONG_LINE, name="line.nc", wait=True)
    auto = demo_window.page("auto")
    auto.buttons["start"].click()
    c.advance(1.0)
    auto.buttons["hold"].click()
    assert c.run_until(lambda: state(c) == "hold", timeout_s=5)
    c.advance(1.5)  # the jerk-limited stop along the path (the controller's hold budget)
    held_x, held_ref = c.machine_position[0], c.reference_position[0]
    c.advance(1.0)
    assert c.reference_position[0] == pytest.approx(held_ref, abs=1e-9)  # stays on hold
    assert c.machine_position[0] == pytest.approx(held_x, abs=0.01)  # the servo only settles
    assert 5.0 < held_x < 35.0
    assert demo_window.header.state_label.text() == "Feed hold"
    auto.buttons["start"].click()  # cycle start in hold resumes
    assert state(c) == "running"
    assert c.run_until(lambda: state(c) == "idle", timeout_s=30)
    assert c.reference_position[0] == pytest.approx(40.0, abs=1e-9)  # same end as without the hold
    assert c.machine_position[0] == pytest.approx(40.0, abs=1e-3)  # encoder counts 0.1 um


def test_invalid_program_error_at_its_line_and_start_refused(demo_window, real_controller, qtbot) -> None:
    c = real_controller
    program = demo_window.page("program")
    program.set_text(BAD)
    with qtbot.waitSignal(c.programErrors, timeout=20_000):  # checked in the controller's worker thread
        program.load_into_machine()
    assert set(program.editor.errors) == {3}
    assert "radius" in program.editor.errors[3]
    assert "Line 3" in program.error_label.text() or "line 3" in program.error_label.text()
    auto = demo_window.page("auto")
    assert auto.editor.errors.keys() == {3} and "G02 X20 Y0 R2" in auto.editor.toPlainText()
    assert not auto.buttons["start"].isEnabled()
    auto.cycle_start()  # even if pressed: refused, nothing moves
    c.advance(0.5)
    assert state(c) == "idle" and "refused" in auto.info_label.text()


def test_set_part_zero_by_touch_off(demo_window, real_controller, dialogs) -> None:
    c = real_controller
    c.jog_increment("X", 1.0, 1)
    assert c.run_until(lambda: state(c) == "idle" and c.machine_position[0] > 0.999, timeout_s=10)
    page = demo_window.page("part_zero")
    dialogs.answers.append(0.0)
    page.touch_buttons["X"].click()
    c.advance(0.1)
    assert c.work_offsets["G54"][0] == pytest.approx(1.0, abs=1e-6)
    assert page.table.item(0, 0).text() == "+1.000"
    assert demo_window.header.dro.work_text("X") == "+0.000"
    assert demo_window.header.dro.machine_text("X") == "+1.000"


def test_parameter_change_persists_across_restart(qtbot, qapp, state_dir, dialogs, demo_window,
                                                   real_controller) -> None:
    dialogs.answers.append("1234")
    assert demo_window.show_page("parameters")
    page = demo_window.page("parameters")
    page.fields["v_max_mm_s"].setValue(22.5, emit=True)
    page.mode_buttons["paper"].click()
    assert page.apply()
    assert real_controller.config.machine.limits.v_max_mm_s == 22.5
    demo_window.close()
    real_controller.shutdown()

    from app.machine.controller import MachineController

    again = MachineController(None, state_dir=state_dir, worker_mode="manual")
    try:
        window = make_window(qtbot, qapp, PanelOptions(state_dir=state_dir), dialogs, again)
        assert again.config.machine.limits.v_max_mm_s == 22.5
        assert again.config.machine.planner.mode == "paper"
        assert window.page("parameters").fields["v_max_mm_s"].value() == 22.5
    finally:
        again.shutdown()


@pytest.mark.parametrize("block, reason", [
    ("#[[10**300*10**300]-[10**300*10**300]]=5", "parameter number #nan out of range"),
    ("M3 S999999", "over the spindle's maximum of 24000 rpm"),
])
def test_mdi_line_on_the_real_controller_refuses_with_the_reason(demo_window, real_controller, block: str,
                                                                 reason: str) -> None:
    """A NaN parameter number once raised out of the MDI line's send; a speed over the maximum
    was capped silently. Both are refused, the reason is on screen, the line stays for editing."""
    page = demo_window.page("manual")
    page.mdi_line.setText(block)
    page.send_mdi()
    assert reason in demo_window._message.text()
    assert page.mdi_line.text() == block
    assert real_controller.state.value == "idle" and not real_controller.spindle.on


def test_probing_from_the_mdi_line_shows_the_probe_and_where_it_touched(demo_window, real_controller) -> None:
    """The demo's simulated stylus touches at machine Z -50: the Diagnostics page shows the
    input free, then touching after a G38.2 typed on the Manual page; the message says where."""
    c = real_controller
    probe = demo_window.page("diagnostics").bus.probe
    page = demo_window.page("manual")
    # only the probe probes: the demo's T99 put in (its length aside: G49 in the probing block)
    page.mdi_line.setText("M61 Q99")
    page.send_mdi()
    assert c.tool_in_spindle == 99
    page.mdi_line.setText("G49 G0 Z-45")
    page.send_mdi()
    assert c.run_until(lambda: state(c) == "idle" and c.worker.buffer_level() == 0, timeout_s=20)
    c.advance(0.1)
    assert probe.text() == "Probe input: free"
    page.mdi_line.setText("G49 G38.2 Z-60 F120")
    page.send_mdi()
    assert c.run_until(lambda: state(c) == "idle" and c.worker.buffer_level() == 0, timeout_s=20)
    c.advance(0.1)
    assert probe.text() == "Probe input: touching"
    assert "G38.2 (line 1): contact at X" in demo_window._message.text() + " ".join(
        a.cause for a in c.alarms)
    assert -50.1 < c.machine_position[2] <= -50.0


def test_measuring_the_tool_in_the_spindle_on_the_setter(demo_window, real_controller, dialogs) -> None:
    """The demo's tool setter (machine X-230 Y-180, a tool of length 0 would touch at Z-60) under
    the simulated stylus at Z-50: the tool measures 10 mm, the table shows it, the spindle ends
    up at the clearance height."""
    from planner.core.tools import Tool

    c = real_controller
    assert c.set_tool(Tool(4, 4, (("Z", 33.0),), 6.0, "drill")) and c.set_tool_in_spindle(4)
    page = demo_window.page("tools")
    row = [t.number for t in c.tool_table].index(4)
    page.table.selectRow(row)
    page.buttons["measure"].click()
    shown: set[str] = set()
    label = demo_window.findChild(QLabel, "machineState")
    assert c.run_until(lambda: (shown.add(label.text()),
                                state(c) == "idle" and c.worker.buffer_level() == 0)[1],
                       timeout_s=60)
    assert "Measuring tool T4" in shown                # the header says what runs, not "Running"
    # the contact is latched at the first sample past the surface: within one sample's travel
    # at the slow probe's feed (a tenth of max_feed_mm_min)
    one_sample_mm = c.config.probe.max_feed_mm_min / 10.0 / 60.0 * c.config.machine.planner.ts_s
    assert c.tool_table.get(4).length_mm == pytest.approx(10.0, abs=one_sample_mm)
    assert page.table.item(row, 2).text() == f"{c.tool_table.get(4).length_mm:.3f}"
    assert c.machine_position[2] == pytest.approx(c.config.machine.axes[2].max_pos)
    assert "T4 measured on the tool setter: length " in demo_window._message.text()


def test_after_a_probe_the_preview_draws_the_path_the_machine_takes(demo_window, real_controller) -> None:
    """Checked with the contact assumed at Z-70, the move after the probe goes to Z-65 on the
    preview; once the stylus touched at Z-50 the program is read again, and the preview and
    the backplot draw that move to Z-45."""
    c = real_controller
    text = "G21 G90\nG0 X10 Y5 Z-40\nG38.2 Z-70 F300\nG0 Z[#5063 + 5]\nG1 X30 F600\nM2\n"
    assert c.load_program(text, name="probe.nc", wait=True)
    model = demo_window.context.program
    assert c.run_until(lambda: model.program is not None and model.info is c.program_info, timeout_s=10)
    assert model.program.moves[2].end[2] == pytest.approx(-65.0)
    preview = demo_window.page("preview").plot
    assert c.cycle_start(wait=True)
    assert c.run_until(lambda: state(c) == "idle" and c.worker.buffer_level() == 0, timeout_s=60)
    assert model.program.moves[2].end[2] == pytest.approx(-45.0, abs=0.01)
    assert preview.path is model.toolpath and demo_window.page("auto").backplot.path is model.toolpath
    assert c.program_info.program.moves[2].end[2] == pytest.approx(-65.0)   # the check's own stays


def test_home_is_off_in_e_stop_and_says_why_before_any_question(demo_window, real_controller, dialogs,
                                                               qtbot) -> None:
    """In E-stop nothing may move: Home and Home all are disabled with the reason in their
    tooltip, so no one is asked "The axes may move" to be refused after; released, they are on."""
    from PySide6.QtCore import Qt

    c = real_controller
    assert demo_window.show_page("machine_zero")
    page = demo_window.page("machine_zero")
    assert page.home_all_button.isEnabled()
    c.estop()
    c.advance(0.1)
    assert state(c) == "estop"
    buttons = [*page.home_buttons.values(), page.home_all_button]
    assert not any(b.isEnabled() for b in buttons)
    assert all(b.toolTip().startswith("Home: machine is e-stop") for b in buttons), buttons[0].toolTip()
    homed = tuple(c.homed)
    qtbot.mouseClick(page.home_all_button, Qt.MouseButton.LeftButton)
    assert dialogs.asked == [] and tuple(c.homed) == homed
    assert c.estop_release()
    c.advance(0.2)
    assert state(c) == "idle"
    assert all(b.isEnabled() and b.toolTip() == "" for b in buttons)


def test_the_dro_at_an_m6_stop_shows_the_tip_of_the_tool_still_in_the_spindle(demo_window, real_controller,
                                                                              tmp_path) -> None:
    """T1 (length 0) in, then M6 T2 (length -12.5) and G43 H2 after it: stopped at the M6, the
    Work Z is where T1's tip is (20), not where T2's would be (32.5); once T2 is in and its G43
    run, the tip of T2 again."""
    from resources import PROGRAMS

    c = real_controller
    assert c.import_tool_table(PROGRAMS / "demo_tools.tbl") and c.set_tool_in_spindle(1)
    program = tmp_path / "two_tools.ngc"
    program.write_text("G21 G90\nT1 M6\nG43 H1\nG0 X0 Y0 Z20\nT2 M6\nG43 H2\nG0 Z20\nM30\n")
    assert c.load_program(program, wait=True) and c.cycle_start(wait=True)
    assert c.run_until(lambda: c.prompt is not None and c.prompt.tool == 2, timeout_s=60)
    c.advance(0.3)
    dro = demo_window.header.dro
    assert c.tool_in_spindle == 1 and c.machine_position[2] == pytest.approx(20.0, abs=1e-3)
    assert dro.work_text("Z") == "+20.000"                     # T1's tip, not +32.500
    assert c.cycle_start(wait=True)                            # T2 put in
    assert c.run_until(lambda: state(c) == "idle" and c.last_run is not None, timeout_s=60)
    c.advance(0.3)
    assert c.machine_position[2] == pytest.approx(7.5, abs=1e-3)   # G43 H2: Z20 at T2's tip
    assert dro.work_text("Z") == "+20.000"
