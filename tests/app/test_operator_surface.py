"""What the operator sees and touches agrees with what the machine does: the real widgets on the
real controller (simulated drives, manual clock), checked against the machine's positions and
its trace, not only against what a label says.

- the Work DRO reads the tool tip (the tool length offset in force included) and says what it
  includes;
- touch-off with a tool in the spindle sets the system so that the tip reads the value, and a
  program going there lands at the touched point; values outside the travel are refused;
- after Stop, and after E-stop and reset, cycle start never starts the program again from line 1
  by itself: the operator chooses to resume where it stopped or to start from the beginning;
- after a power loss the panel says which program and line were running, and demo mode keeps
  the axes unhomed.
"""

from __future__ import annotations

import time

import numpy as np
import pytest

from app.context import PanelOptions
from app.machine.model import MachineState
from app.machine.session.connection import PERSIST_EVERY_S
from planner.core.tools import Tool
from tests.app.conftest import make_window

LONG = "G21 G90 G17\nG0 X0 Y0 Z5\nG1 Z-1 F300\nG1 X20 F600\nG1 Y20\nG1 X0\nG1 Y0\nG0 Z5\nM30\n"


def _lines_after(qtbot, c, press) -> list[int]:
    """The lines the controller shows from ``press`` until the run ends."""
    lines: list[int] = []
    c.lineChanged.connect(lambda line: lines.append(int(line)))
    press()
    # checked again first in the worker thread (the machine moved since it was loaded): it
    # starts by itself when the check is done
    qtbot.waitUntil(lambda: c.state is MachineState.RUNNING, timeout=30_000)
    assert c.run_until(lambda: c.state is MachineState.IDLE, 60)
    return [line for line in lines if line > 0]


def test_the_work_dro_reads_the_tool_tip_with_the_tool_length_offset(qtbot, demo_window,
                                                                    real_controller) -> None:
    c = real_controller
    assert c.set_tool(Tool(2, 2, (("Z", -12.5),), 3.0, "3 mm ball")) and c.set_tool_in_spindle(2)
    assert c.load_program("G21 G90\nT2 M6\nG43 H2\nG0 X0 Y0 Z5\nG1 Z-1 F300\nG4 P2\nG0 Z5\nM2\n",
                          name="tlo.nc", wait=True)
    demo_window.page("auto").buttons["start"].click()
    assert c.run_until(lambda: abs(c.reference_position[2] + 13.5) < 1e-9, 30)   # in the dwell at Z-1
    c.advance(0.2)
    dro = demo_window.header.dro
    # the tip at Z-1 in program coordinates; the machine carries the tool's -12.5 mm
    assert dro.work_text("Z") == "-1.000" and dro.machine_text("Z") == "-13.500"
    qtbot.waitUntil(lambda: "length -12.500 mm" in dro.frame_label.text(), timeout=5_000)   # it says so
    assert c.run_until(lambda: c.state is MachineState.IDLE, 30)
    assert dro.work_text("Z") == "+5.000" and dro.machine_text("Z") == "-7.500"
    assert c.machine_position[2] == pytest.approx(-7.5, abs=1e-3)


def test_touch_off_z_with_a_tool_sets_the_system_for_its_tip(demo_window, real_controller, dialogs) -> None:
    c = real_controller
    assert c.set_tool(Tool(1, 1, (("Z", 10.0),), 6.0, "6 mm flat")) and c.set_tool_in_spindle(1)
    assert c.mdi("G53 G0 Z-50") and c.run_until(lambda: c.state is MachineState.IDLE, 20)
    page = demo_window.page("part_zero")
    dialogs.answers.append(0.0)
    page.touch_buttons["Z"].click()
    c.advance(0.1)
    # the tip reads 0 here: G54 Z is the machine Z less the tool's length (LinuxCNC's G10 L20)
    assert c.work_offsets["G54"][2] == pytest.approx(-60.0, abs=1e-3)
    assert demo_window.header.dro.work_text("Z") == "+0.000"
    # a program that goes to Z0 with the tool's length (G43 H1) lands where the tip touched
    assert c.mdi("G0 Z20") and c.run_until(lambda: c.state is MachineState.IDLE, 20)
    assert c.mdi("G43 H1 G0 Z0") and c.run_until(lambda: c.state is MachineState.IDLE, 20)
    assert c.machine_position[2] == pytest.approx(-50.0, abs=1e-3)


def test_touch_off_refuses_a_zero_outside_the_travel_and_says_why(demo_window, real_controller,
                                                                  dialogs) -> None:
    c = real_controller
    before = dict(c.work_offsets)
    refused: list[str] = []
    c.commandRefused.connect(lambda _action, why: refused.append(why))
    dialogs.answers.append(1e9)
    demo_window.page("part_zero").touch_buttons["X"].click()
    assert c.work_offsets == before
    assert refused and "outside the travel" in refused[-1]
    r = c.touch_off("Z", float("nan"))
    assert not r and "not a number" in r.reason
    assert c.touch_off("X", -0.0)
    assert str(c.work_offsets["G54"][0]) != "-0.0"


def _stop_part_way(demo_window, c) -> int:
    assert c.load_program(LONG, name="long.nc", wait=True)
    auto = demo_window.page("auto")
    auto.buttons["start"].click()
    assert c.run_until(lambda: c.current_line >= 5, 30)
    c.advance(0.5)
    auto.buttons["stop"].click()
    assert c.run_until(lambda: c.state is MachineState.IDLE, 10)
    assert c.resume_line >= 5
    return c.resume_line


def test_cycle_start_after_stop_asks_and_resumes_where_it_stopped(qtbot, demo_window, real_controller,
                                                                  dialogs) -> None:
    c = real_controller
    stopped = _stop_part_way(demo_window, c)
    here = np.array(c.reference_position)
    auto = demo_window.page("auto")
    dialogs.answers.append(-1)                       # asked: the operator cancels
    auto.buttons["start"].click()
    c.advance(0.5)
    assert dialogs.asked[-1][0] == "choose" and f"stopped at line {stopped}" in dialogs.asked[-1][1]
    assert c.state is MachineState.IDLE and np.array_equal(c.reference_position, here)   # nothing moved
    dialogs.answers.append(0)                        # resume at the stop point
    lines = _lines_after(qtbot, c, auto.buttons["start"].click)
    assert lines and min(lines) >= stopped            # never back to line 1
    assert c.last_run is not None and c.last_run.completed
    np.testing.assert_allclose(c.reference_position, (0.0, 0.0, 5.0), atol=1e-9)


def test_cycle_start_after_stop_starts_from_the_beginning_only_when_chosen(qtbot, demo_window,
                                                                           real_controller, dialogs) -> None:
    c = real_controller
    _stop_part_way(demo_window, c)
    dialogs.answers.append(1)                        # start from the beginning
    lines = _lines_after(qtbot, c, demo_window.page("auto").buttons["start"].click)
    assert lines[0] <= 3 and c.last_run.completed


def test_after_estop_and_reset_cycle_start_asks_too(demo_window, real_controller, dialogs) -> None:
    c = real_controller
    assert c.load_program(LONG, name="long.nc", wait=True)
    auto = demo_window.page("auto")
    auto.buttons["start"].click()
    assert c.run_until(lambda: c.current_line >= 5, 30)
    demo_window.header.estop_button.click()
    assert c.state is MachineState.ESTOP
    assert c.estop_release() and c.reset()
    assert c.run_until(lambda: c.state is MachineState.IDLE, 10), c.state_reason
    line = c.resume_line
    assert line >= 5
    dialogs.answers.append(-1)
    auto.buttons["start"].click()
    assert dialogs.asked[-1][0] == "choose" and f"line {line}" in dialogs.asked[-1][1]
    c.advance(0.5)
    assert c.state is MachineState.IDLE


def test_run_from_line_opens_at_the_line_where_it_stopped(demo_window, real_controller, dialogs) -> None:
    c = real_controller
    stopped = _stop_part_way(demo_window, c)
    seen: list[float] = []

    def ask_number(parent, title, value, minimum=-1e9, maximum=1e9, decimals=3):
        seen.append(value)
        return None

    dialogs.ask_number = ask_number  # type: ignore[method-assign]
    demo_window.page("auto").run_from.click()
    assert seen == [float(stopped)]


def test_after_run_from_line_only_what_ran_is_drawn_as_executed(qtbot, demo_window, real_controller) -> None:
    c = real_controller
    assert c.load_program(LONG, name="long.nc", wait=True)
    qtbot.waitUntil(lambda: demo_window.page("auto").backplot.path is not None, timeout=10_000)
    assert c.run_from_line(5, wait=True)                 # G1 Y20: from X20 Y0 at Z-1
    assert c.run_until(lambda: c.state is MachineState.IDLE and c.last_run is not None, 60)
    demo_window.page("auto")._on_line(8)
    plot = demo_window.page("auto").backplot
    x, y = plot.done_item.getData()
    assert x is not None and len(x) >= 2
    # the executed part begins where line 5 begins: not at the program's start (X0 Y0), and the
    # rapid from there, the plunge and the cut along X that the run never made are not in it
    assert (x[0], y[0]) == pytest.approx((20.0, 0.0))
    assert c.run_first_move == int(plot.path.move_lines.tolist().index(5))
    assert c.cycle_start(wait=True, from_start=True)
    assert c.run_until(lambda: c.state is MachineState.IDLE, 60)
    x, y = plot.done_item.getData()
    assert c.run_first_move == 0 and (x[0], y[0]) == pytest.approx((0.0, 0.0))


def test_after_a_power_loss_the_panel_says_what_was_running_and_demo_does_not_home(
        qtbot, qapp, state_dir, tmp_path, dialogs) -> None:
    import shutil

    from app.machine.controller import MachineController

    first = MachineController(None, state_dir=state_dir, worker_mode="manual")
    try:
        assert first.connect_bus() and first.set_machine_zero_here()
        assert first.mdi("G0 X-30 Y-40") and first.run_until(lambda: first.state is MachineState.IDLE, 20)
        assert first.load_program(LONG, name="long.nc", wait=True) and first.cycle_start(wait=True)
        assert first.run_until(lambda: first.current_line >= 5, 30)
        time.sleep(PERSIST_EVERY_S)              # saved every so often (real time) while moving
        first.advance(0.1)
        line = first.current_line
        where = np.array(first.machine_position)
        # the power goes: the state folder as it is now, without a shutdown (its lock dies with
        # the process), is what the next control starts from
        after = tmp_path / "after_power_loss"
        shutil.copytree(state_dir, after)
        second = MachineController(None, state_dir=after, worker_mode="manual")
        try:
            assert second.interrupted is not None and second.interrupted[1] == line
            window = make_window(qtbot, qapp, PanelOptions(demo=True, state_dir=after), dialogs, second)
            qtbot.waitUntil(lambda: second.state is MachineState.IDLE, timeout=10_000)
            assert not any(second.homed)                                     # never homed by itself
            assert np.allclose(second.machine_position, where, atol=1.5)     # where it was (saved), not 0
            assert np.linalg.norm(second.machine_position) > 10.0
            assert any("long.nc was running at line" in a.cause for a in second.active_alarms)
            window.close()
        finally:
            second.shutdown()
    finally:
        first.shutdown()


def test_connect_is_a_button_and_a_disabled_cycle_start_says_why(qtbot, qapp, state_dir, dialogs,
                                                                 real_controller) -> None:
    c = real_controller
    window = make_window(qtbot, qapp, PanelOptions(state_dir=state_dir), dialogs, c)
    assert c.state is MachineState.DISCONNECTED
    auto = window.page("auto")
    assert not auto.buttons["start"].isEnabled()
    assert "Cycle start:" in auto.info_label.text() and auto.buttons["start"].toolTip()
    button = window.page("diagnostics").connect_button
    assert button.text() == "Connect to the drives" and button.minimumHeight() >= 48
    button.click()                                       # confirmed (the scripted default)
    assert c.state is MachineState.IDLE
    assert dialogs.asked[-1] == ("confirm", "Connect to the drives and enable them?")
    c.advance(0.1)
    qtbot.waitUntil(lambda: button.text() == "Disconnect the drives", timeout=5_000)


def test_a_feed_move_with_the_spindle_stopped_after_m6_is_confirmed_first(demo_window, real_controller,
                                                                          dialogs) -> None:
    c = real_controller
    assert c.set_tool(Tool(2, 2, (("Z", 0.0),), 3.0, "3 mm ball"))
    assert c.load_program("G21 G90\nM3 S8000\nG0 X0 Y0 Z5\nT2 M6\nG1 Z-1 F300\nM3 S6000\nG1 X5\nM30\n",
                          name="m6.nc", wait=True)
    (warning,) = c.program_info.warnings
    assert warning.line == 5 and "M6 at line 4" in warning.message
    dialogs.answers.append(False)                          # asked: the operator says no
    demo_window.page("auto").buttons["start"].click()
    assert dialogs.asked[-1][0] == "confirm" and "Line 5" in dialogs.asked[-1][1]
    c.advance(0.5)
    assert c.state is MachineState.IDLE                    # nothing started
    # the same program with its M3 before the cut: nothing to confirm
    assert c.load_program("G21 G90\nM3 S8000\nG0 X0 Y0 Z5\nT2 M6\nM3 S6000\nG1 Z-1 F300\nM30\n",
                          name="m6.nc", wait=True)
    assert c.program_info.warnings == ()


def test_zero_feed_override_reads_held_and_counts_no_time_left(demo_window, real_controller) -> None:
    c = real_controller
    assert c.load_program(LONG, name="long.nc", wait=True)
    auto = demo_window.page("auto")
    auto.buttons["start"].click()
    assert c.run_until(lambda: c.current_line >= 4, 30)
    auto.feed.buttons["-10"].click()                     # down to 0 % by the operator's taps
    while c.feed_override_pct > 0.0:
        auto.feed.buttons["-10"].click()
    c.advance(1.0)
    here = np.array(c.reference_position)
    c.advance(1.0)
    assert np.array_equal(here, c.reference_position)     # nothing moves
    assert demo_window.header.state_label.text() == "Held by feed override 0 %"
    assert "Remaining --:--" in auto.info_label.text()
    assert c.set_feed_override(100)
    assert demo_window.header.state_label.text() == "Running"


def test_the_estop_banner_says_it_once(demo_window, real_controller) -> None:
    demo_window.header.estop_button.click()
    assert real_controller.state is MachineState.ESTOP
    text = demo_window.header.alarm_banner.text()
    assert text == "ALARM: operator: E-stop pressed", text


def test_the_demo_on_the_papers_machine_runs_its_tyre_mould_sample_to_the_end(qtbot, qapp, tmp_path,
                                                                              dialogs) -> None:
    from app.machine.controller import MachineController
    from resources import shipped_machine

    state = tmp_path / "paper_state"
    config = tmp_path / "paper.toml"
    config.write_text(shipped_machine("paper_yzca").read_text())
    c = MachineController(config, state_dir=state, worker_mode="manual")
    try:
        window = make_window(qtbot, qapp, PanelOptions(demo=True, state_dir=state, config_path=config),
                             dialogs, c)
        qtbot.waitUntil(lambda: c.program_info is not None, timeout=20_000)
        assert c.program_info.name == "tyre_mould.nc"
        window.page("auto").buttons["start"].click()
        assert c.run_until(lambda: c.state is MachineState.IDLE and c.last_run is not None, 300)
        run = c.last_run
        assert run.completed, run
        assert run.limits and max(run.limits[k] for k in ("axis_v", "axis_a", "axis_j", "tangential_v",
                                                          "tangential_a", "tangential_j")) <= 1.0 + 1e-6
        # the rotary work runs at its own speed: the run takes what the check planned
        assert run.cycle_time_s == pytest.approx(c.program_info.cycle_time_s, rel=0.02)
        window.close()
    finally:
        c.shutdown()


def test_part_zero_shows_and_edits_all_nine_systems_and_their_rotation(demo_window, real_controller,
                                                                      dialogs) -> None:
    """G59.1-G59.3 and the XY rotation are the operator's too: edited on the page, selected,
    kept over a restart, and a program run in G59.2 goes where they say."""
    c = real_controller
    page = demo_window.page("part_zero")
    names = [page.table.verticalHeaderItem(r).text() for r in range(page.table.rowCount())]
    assert names == ["G54", "G55", "G56", "G57", "G58", "G59", "G59.1", "G59.2", "G59.3"]
    assert page.table.horizontalHeaderItem(3).text() == "XY rotation (°)"
    row = names.index("G59.2")
    for col, value in enumerate((-100.0, -50.0, -20.0)):
        dialogs.answers.append(value)
        page.edit_cell(row, col)
    dialogs.answers.append(90.0)
    page.edit_cell(row, 3)
    assert c.work_offsets["G59.2"] == (-100.0, -50.0, -20.0) and c.work_rotation("G59.2") == 90.0
    assert page.table.item(row, 3).text() == "+90.000"
    page.select_buttons["G59.2"].click()
    assert c.active_offset == "G59.2"
    assert c.mdi("G0 X10 Y0 Z0")
    assert c.run_until(lambda: c.state is MachineState.IDLE and c.stream.job is None, 30)
    # X10 in a system turned 90 degrees about its zero (-100, -50): machine X-100, Y-40
    assert np.allclose(c.machine_position, (-100.0, -40.0, -20.0), atol=2e-3)
    assert np.allclose(c.work_position, (10.0, 0.0, 0.0), atol=2e-3)


def test_a_g59_1_set_by_a_program_in_an_older_state_folder_is_kept(qapp, tmp_path) -> None:
    """A state folder whose table holds G54-G59 only, and a G10 L2 P7 in its parameters: the
    G59.1 the program set is what the machine has, never a zero from the configuration."""
    import json

    from app.machine.controller import MachineController

    state = tmp_path / "state"
    first = MachineController(None, state_dir=state, worker_mode="manual")
    try:
        assert first.connect_bus() and first.set_machine_zero_here()
        assert first.mdi("G10 L2 P7 X-5 Y-6 Z-7 R12")
        assert first.run_until(lambda: first.stream.job is None, 10)
    finally:
        first.shutdown()
    table = json.loads((state / "offsets.json").read_text())
    assert table["G59.1"] == [-5.0, -6.0, -7.0]
    (state / "offsets.json").write_text(json.dumps({k: v for k, v in table.items() if "." not in k}))
    again = MachineController(None, state_dir=state, worker_mode="manual")
    try:
        assert again.work_offsets["G59.1"] == (-5.0, -6.0, -7.0)
        assert again.work_rotation("G59.1") == 12.0
    finally:
        again.shutdown()


def test_an_error_shows_its_column_and_a_program_with_errors_is_saved_only_when_confirmed(
        qtbot, demo_window, dialogs, tmp_path) -> None:
    program = demo_window.page("program")
    path = tmp_path / "part.nc"
    path.write_text("G21 G90\nG0 X0\nM30\n")
    program.open_file(path)
    program.editor.setPlainText("G21 G90\nG0 X0 Q5\nM30\n")
    qtbot.waitUntil(lambda: 2 in program.editor.errors, timeout=20_000)
    assert program.editor.errors[2].startswith("column 7: ")
    program.editor.go_to_line(2)
    assert program.error_label.text().startswith("Line 2: column 7: ")
    marks = [s for s in program.editor.extraSelections() if s.cursor.hasSelection()]
    assert [(m.cursor.selectionStart(), m.cursor.selectedText()) for m in marks] == [(len("G21 G90\n") + 6,
                                                                                      "Q5")]
    dialogs.answers.append(False)
    assert program.save() is False
    assert dialogs.asked[-1][0] == "confirm" and "1 error(s), the first at line 2" in dialogs.asked[-1][1]
    assert path.read_text() == "G21 G90\nG0 X0\nM30\n"                # refused: the file as it was
    dialogs.answers.append(True)
    assert program.save() is True and "Q5" in path.read_text()


def test_the_auto_page_says_when_the_loaded_programs_file_was_saved_with_changes(
        qtbot, demo_window, real_controller, tmp_path) -> None:
    c = real_controller
    path = tmp_path / "part.nc"
    path.write_text("G21 G90\nG0 X1\nM30\n")
    assert c.load_program(path, wait=True)
    auto, program = demo_window.page("auto"), demo_window.page("program")
    qtbot.waitUntil(lambda: program.doc.path == path.resolve(), timeout=10_000)
    demo_window.show_page("auto")
    assert not auto.stale_note.isVisible()
    demo_window.show_page("program")
    program.editor.setPlainText("G21 G90\nG0 X2\nM30\n")
    qtbot.waitUntil(lambda: not program.checker.busy, timeout=20_000)
    assert program.save()
    demo_window.show_page("auto")
    assert auto.stale_note.isVisible() and auto.reload_button.isVisible()
    assert "part.nc was saved with changes since it was loaded" in auto.stale_note.text()
    assert c.program_info is not None and "X1" in c.program_info.text     # the machine's is unchanged
    auto.reload_button.click()
    qtbot.waitUntil(lambda: c.program_info is not None and "X2" in c.program_info.text, timeout=20_000)
    qtbot.waitUntil(lambda: not auto.stale_note.isVisible(), timeout=10_000)


def test_an_alarm_tapped_shows_its_whole_text_in_the_operators_language(demo_window, real_controller) -> None:
    from app.machine.model import Severity

    c = real_controller
    cause = ("OPC UA: cannot listen on opc.tcp://0.0.0.0:4840/: Address already in use "
             "([opcua] port = 4840); the machine runs on without its OPC UA server")
    c.alarm_log.raise_alarm("opcua", cause, Severity.WARNING, "opcua_failed")
    page = demo_window.page("alarms")
    demo_window.show_page("alarms")
    row = [page.table.item(r, 2).text() for r in range(page.table.rowCount())].index(cause)
    rect = page.table.visualItemRect(page.table.item(row, 2))
    assert page.table.fontMetrics().horizontalAdvance(cause) > rect.width()     # cut in its column
    page.table.cellClicked.emit(row, 2)
    assert page.detail.text().endswith(f"OPC UA (warning, active): {cause}")
    demo_window.context.i18n.set_language("tr")
    try:
        page.table.cellClicked.emit(row, 2)
        assert "OPC UA (uyarı, etkin): " in page.detail.text()
        assert page.table.item(row, 3).text() == "uyarı"
    finally:
        demo_window.context.i18n.set_language("en")   # the translator is installed application-wide


def test_the_dro_shows_the_distance_to_go_of_the_move_being_run_by_a_tap(qtbot, demo_window,
                                                                         real_controller) -> None:
    from PySide6.QtCore import Qt

    c = real_controller
    dro = demo_window.header.dro
    assert dro.second_button.text() == "Machine"
    assert c.mdi("G1 X30 F600")                               # 3 s at 10 mm/s from X0
    assert c.run_until(lambda: c.reference_position[0] > 10.0, 10)
    qtbot.mouseClick(dro.second_button, Qt.MouseButton.LeftButton)
    assert dro.second_button.text() == "To go"
    here = c.reference_position[0]
    demo_window.header._on_position(c.machine_position, c.work_position)
    left = float(dro.machine_text("X"))
    assert left == pytest.approx(30.0 - here, abs=0.01) and 0.0 < left < 20.0
    assert float(dro.machine_text("Y")) == 0.0
    assert c.run_until(lambda: c.state is MachineState.IDLE and c.stream.job is None, 10)
    demo_window.header._on_position(c.machine_position, c.work_position)
    assert float(dro.machine_text("X")) == 0.0                # at rest: nothing to go
    qtbot.mouseClick(dro.machine_labels[1], Qt.MouseButton.LeftButton)      # a value of the row too
    assert dro.second_button.text() == "Machine"
    assert float(dro.machine_text("X")) == pytest.approx(30.0, abs=1e-3)


def test_a_program_a_power_loss_cut_asks_to_resume_at_its_line_when_loaded_again(
        qtbot, qapp, state_dir, tmp_path, dialogs) -> None:
    """Killed mid-run, restarted, homed, the program loaded again: Cycle start asks (resume at
    the line it was cut at, or from the beginning), nothing moves until the operator chooses,
    and the run log holds the run that was cut."""
    import shutil

    from app.machine.controller import MachineController

    first = MachineController(None, state_dir=state_dir, worker_mode="manual")
    try:
        assert first.connect_bus() and first.set_machine_zero_here()
        assert first.load_program(LONG, name="long.nc", wait=True) and first.cycle_start(wait=True)
        assert first.run_until(lambda: first.current_line >= 5, 30)
        time.sleep(PERSIST_EVERY_S)              # saved every so often (real time) while moving
        first.advance(0.1)
        line = first.current_line
        after = tmp_path / "after_kill"
        shutil.copytree(state_dir, after)
    finally:
        first.shutdown()
    second = MachineController(None, state_dir=after, worker_mode="manual")
    try:
        window = make_window(qtbot, qapp, PanelOptions(state_dir=after), dialogs, second)
        assert second.connect_bus() and second.set_machine_zero_here()
        (cut,) = [r for r in second.runs() if not r.completed]
        assert cut.program == "long.nc" and cut.last_line == line and cut.result.startswith(
            f"interrupted at line {line}")
        assert second.load_program(LONG, name="long.nc", wait=True)
        qapp.processEvents()
        assert second.resume_line == line
        start = window.page("auto").buttons["start"]
        where = np.array(second.machine_position)
        dialogs.answers.append(2)                                     # Cancel
        start.click()
        kind, text = dialogs.asked[-1]
        assert kind == "choose" and f"stopped at line {line}" in text and "power loss" in text
        second.advance(0.5)
        assert second.state is MachineState.IDLE and np.allclose(second.machine_position, where)
        dialogs.answers.append(0)                                     # Resume at the line
        lines = _lines_after(qtbot, second, start.click)
        assert second.last_run.completed
        assert lines and min(lines) >= line                           # it went on from there, not from line 1
        window.close()
    finally:
        second.shutdown()


def test_while_another_program_is_checked_auto_shows_nothing_of_the_one_before(
        qtbot, demo_window, real_controller) -> None:
    """Opening another program: while it is checked, the Auto page shows its name, no text, no
    path and no line of the program before (not "Line 6" of a file that is gone)."""
    c = real_controller
    auto = demo_window.page("auto")
    assert c.load_program(LONG, name="first.nc", wait=True)
    qtbot.waitUntil(lambda: auto.program_label.text() == "first.nc", timeout=10_000)
    auto._on_line(6)
    assert "Line 6" in auto.info_label.text() and auto.editor.toPlainText() == LONG
    seen: dict[str, object] = {}

    def checking(loading: bool, _name: str) -> None:
        if loading and not seen:
            seen.update(label=auto.program_label.text(), text=auto.editor.toPlainText(),
                        info=auto.info_label.text(), path=auto.backplot.path)

    c.loadingChanged.connect(checking)
    other = LONG.replace("X20", "X30")
    assert c.load_program(other, name="second.nc")
    qtbot.waitUntil(lambda: c.program_info is not None and c.program_info.name == "second.nc", timeout=20_000)
    assert seen["label"] == "second.nc" and seen["text"] == "" and seen["path"] is None
    assert "Line 0" in str(seen["info"])
    qtbot.waitUntil(lambda: auto.editor.toPlainText() == other, timeout=10_000)


def test_the_production_log_shows_a_run_as_soon_as_it_ends(qtbot, demo_window, real_controller) -> None:
    """The run log is written before the panel hears that the run ended: the Production table
    has the run at once (not one run behind until something else refreshes it)."""
    c = real_controller
    production = demo_window.page("diagnostics").production
    rows = production.table.rowCount()
    assert c.load_program(LONG, name="logged.nc", wait=True) and c.cycle_start(wait=True)
    assert c.run_until(lambda: c.state is MachineState.IDLE and c.last_run is not None, 60)
    assert production.table.rowCount() == rows + 1
    assert production.table.item(0, 1).text() == "logged.nc"           # newest first


def test_a_refusal_does_not_stay_in_the_status_line_once_something_was_done(demo_window,
                                                                            real_controller) -> None:
    """Refused, then done: the status line says nothing of the old refusal (a later message stays)."""
    c = real_controller
    assert not c.set_feed_override(500.0)
    assert demo_window._message.text().startswith("Refused: feed override must be 0-200 %")
    assert c.set_feed_override(80.0)                         # done: the refusal is past
    assert demo_window._message.text() == ""
    assert not c.set_feed_override(-1.0)
    assert demo_window._message.text().startswith("Refused:")
    assert c.mdi("G91 G0 X1")                                 # the machine moves: past too
    assert demo_window._message.text() == ""


def test_a_long_message_never_squeezes_the_alarm_banner(qtbot, demo_window, real_controller) -> None:
    """At 1280x800, a long status message beside a long alarm: the banner keeps its width and
    shows "ALARM: ..." cut with "…" (its whole text in the tooltip), the message wraps in its share."""
    demo_window.resize(1280, 800)
    c = real_controller
    c.estop()
    demo_window.show_message("a very long message " * 12)
    qtbot.wait(50)
    banner = demo_window.header.alarm_banner
    assert banner.width() >= 320
    shown = banner.text()
    assert shown.startswith("ALARM: operator: E-stop")
    assert banner.fontMetrics().horizontalAdvance(shown) <= banner.contentsRect().width()
    assert banner.toolTip() == banner.full_text and banner.full_text.startswith(shown.rstrip("…"))
