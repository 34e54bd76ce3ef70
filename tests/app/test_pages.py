"""Every page on the fake controller: buttons reach the controller, signals reach the widgets."""

from __future__ import annotations

from pathlib import Path

import pytest
from PySide6.QtCore import QRect
from PySide6.QtWidgets import QAbstractButton

from app.pages import PAGE_NAMES
from app.paths import DEMO_PROGRAM
from app.service_access import IDLE_LOCK_S
from app.widgets.preview_plot import ARC_COLOR, LINE_COLOR, RAPID_COLOR
from planner.core.program import MoveKind

BAD_PROGRAM = "G21 G17 G90\nG01 X10 F100\nG02 X20 Y0 R2\nG01 X0\n"  # line 3: radius too small


@pytest.mark.parametrize(("size", "language"), [((1280, 800), "en"), ((1920, 1080), "en"),
                                                ((1280, 800), "tr")])
def test_every_page_fits_and_has_touch_sized_buttons(fake_window, qtbot, dialogs, size, language) -> None:
    window = fake_window
    window.set_language(language)
    window.resize(*size)
    dialogs.answers.extend(["1234"] * 2)  # service password for the service pages
    for name in PAGE_NAMES:
        window.show_page(name)
        qtbot.wait(5)
        assert (window.width(), window.height()) == size, f"{name}: window grew (clipping)"
        page = window._stack.currentWidget()
        bounds = QRect(0, 0, window.width(), window.height())
        for button in page.findChildren(QAbstractButton):
            if not button.isVisibleTo(window) or button.parent() is None:
                continue
            if button.objectName().startswith(("qt_scrollarea", "qt_tableview")):
                continue
            assert button.height() >= 48, f"{name}: {button.text()!r} is {button.height()} px high"
            top_left = button.mapTo(window, button.rect().topLeft())
            if name != "parameters":  # the parameters form scrolls (kinetic)
                assert bounds.contains(QRect(top_left, button.size())), f"{name}: {button.text()!r} clipped"


def test_preview_draws_arcs_turquoise_and_lines_green(fake_window, fake_controller, qtbot) -> None:
    fake_controller.load_program(DEMO_PROGRAM, wait=True)
    preview = fake_window.page("preview")
    items = preview.plot.items
    assert items[MoveKind.ARC].opts["pen"].color() == ARC_COLOR
    assert items[MoveKind.LINE].opts["pen"].color() == LINE_COLOR
    assert items[MoveKind.RAPID].opts["pen"].color() == RAPID_COLOR
    path = preview.plot.path
    # pocket.nc: 6 G03 (helical entry + rings), 4 G01, 4 G00
    assert (path.kinds[MoveKind.ARC].count, path.kinds[MoveKind.LINE].count,
            path.kinds[MoveKind.RAPID].count) == (6, 4, 4)
    x, _y = items[MoveKind.ARC].getData()
    assert len(x) == len(path.kinds[MoveKind.ARC].points)
    preview.set_plane("XZ")
    _x, z = items[MoveKind.ARC].getData()
    assert z.min() == pytest.approx(-1.0)
    # tap a segment: its source line is shown
    preview.plot.moveTapped.emit(int(path.move_lines.searchsorted(14)), 14)
    assert preview.line_label.text().startswith("Line 14") and "G03 X5 Y0 I-5 J0" in preview.line_label.text()


def test_preview_live_tool_and_executed_part(fake_window, fake_controller) -> None:
    fake_controller.load_program(DEMO_PROGRAM, wait=True)
    preview = fake_window.page("preview")
    fake_controller.positionChanged.emit((2.0, 0.0, 0.0), (2.0, 0.0, 0.0))
    x, y = preview.plot.tool_item.getData()
    assert (x[0], y[0]) == (2.0, 0.0)
    fake_controller.lineChanged.emit(14)  # G03 X5 Y0 I-5 J0, the tool a quarter round
    fake_controller.positionChanged.emit((0.0, 5.0, -1.0), (0.0, 5.0, -1.0))
    x, _ = preview.plot.done_item.getData()
    assert len(x) > 0 and max(x) == pytest.approx(5.0)   # up to the end of line 13
    cx, cy = preview.plot.current_item.getData()
    assert (cx[0], cy[0]) == pytest.approx((5.0, 0.0)) and (cx[-1], cy[-1]) == (0.0, 5.0)
    assert min(cx) >= -1e-9  # only the first quarter of the ring


def test_tapped_line_opens_in_the_program_editor(fake_window, fake_controller) -> None:
    fake_controller.load_program(DEMO_PROGRAM, wait=True)
    preview = fake_window.page("preview")
    fake_window.show_page("preview")
    preview.plot.moveTapped.emit(7, 14)
    preview.show_line_button.click()
    assert fake_window.current_page_name == "program"
    assert fake_window.page("program").editor.current_line() == 14


def test_program_page_offers_autosave_recovery(fake_window, dialogs, tmp_path: Path) -> None:
    page = fake_window.page("program")
    target = tmp_path / "part.nc"
    target.write_text("G00 X0\n")
    page.open_file(target)
    page.editor.appendPlainText("G01 X5 F100")
    page.doc.autosave()  # what the 5 s timer does; then the panel "crashes"
    dialogs.answers.append(True)  # recover
    page.open_file(target)
    assert "G01 X5 F100" in page.editor.toPlainText() and page.doc.modified


def test_invalid_program_marked_at_its_line_and_start_refused(fake_window, fake_controller, qtbot) -> None:
    program = fake_window.page("program")
    program.set_text(BAD_PROGRAM)
    qtbot.waitUntil(lambda: 3 in program.editor.errors, timeout=5000)
    assert "radius" in program.editor.errors[3]
    program.load_into_machine()
    assert fake_controller.program_info is None
    auto = fake_window.page("auto")
    assert auto.editor.errors.keys() == {3}
    # the panel's own rule: the program shown has errors, so Cycle start is off and a press
    # never reaches the controller (which would run whatever it had loaded before)
    started: list[bool] = []
    fake_controller.cycle_start = lambda: started.append(True)
    assert not auto.buttons["start"].isEnabled()
    auto.cycle_start()
    assert started == []
    assert "program has errors (line 3)" in auto.info_label.text()


def test_program_page_save_and_discard_prompt(fake_window, dialogs, tmp_path: Path) -> None:
    page = fake_window.page("program")
    target = fake_window.context.folders.default / "new.nc"
    page.set_text("G00 X1\n")
    page._on_text_changed()
    assert page.doc.modified
    dialogs.answers.append(-1)  # Cancel
    assert not page.can_close()
    dialogs.answers.append(0)  # Save -> Save as
    dialogs.answers.append("new")   # a name, saved in the program folder
    assert page.can_close()
    assert target.read_text() == "G00 X1\n" and not page.doc.modified


def test_auto_page_buttons(fake_window, fake_controller, dialogs) -> None:
    auto = fake_window.page("auto")
    fake_controller.load_program(DEMO_PROGRAM, wait=True)
    assert auto.buttons["start"].isEnabled()
    auto.buttons["start"].click()
    auto.buttons["hold"].click()
    auto.buttons["start"].click()  # in hold: resume
    auto.feed.buttons["-10"].click()
    auto.single_block.click()
    dialogs.answers.extend([9.0, True])
    auto.run_from.click()
    names = [c[0] for c in fake_controller.calls]
    assert names[-7:] == ["cycle_start", "feed_hold", "resume", "set_feed_override", "set_single_block",
                          "restart_preview", "run_from_line"]
    assert fake_controller.calls[-1] == ("run_from_line", 9)
    fake_controller.lineChanged.emit(12)
    assert auto.editor.run_line == 12
    fake_controller.progressChanged.emit(0.5, 65.0)
    assert "1:05" in auto.info_label.text() and auto.progress.value() == 500


def test_manual_jog_spindle_mdi(fake_window, fake_controller, state_dir) -> None:
    manual = fake_window.page("manual")
    fake_window.show_page("manual")
    manual.jog.speed.buttons["-10"].click()
    button = manual.jog.buttons[("X", 1)]
    button.pressed.emit()
    assert fake_controller.jog_speed_fraction == pytest.approx(0.9)
    button.released.emit()
    manual.jog.set_step(0.1)
    manual.jog.buttons[("Z", -1)].pressed.emit()
    manual.spindle_buttons["cw"].click()
    manual.mdi_line.setText("G01 X1 F100")
    manual.send_mdi()
    assert ("jog_start", "X", 1) in fake_controller.calls and ("jog_stop", "X") in fake_controller.calls
    assert ("jog_increment", "Z", 0.1, -1) in fake_controller.calls
    assert ("mdi", "G01 X1 F100") in fake_controller.calls
    assert "CW" in manual.spindle_label.text()
    assert manual.history.item(0).text() == "G01 X1 F100"
    assert "G01 X1 F100" in (state_dir / "panel.json").read_text()
    # safe release: leaving the page while holding a jog button stops the jog
    manual.jog.set_step(0.0)
    manual.jog.buttons[("Y", 1)].pressed.emit()
    fake_window.show_page("auto")
    assert fake_controller.calls[-1] == ("jog_stop", None)


def test_machine_zero_confirms_homing(fake_window, fake_controller, dialogs) -> None:
    page = fake_window.page("machine_zero")
    dialogs.answers.append(False)
    page.home_buttons["X"].click()
    assert ("home_axis", "X") not in fake_controller.calls
    page.home_all_button.click()
    assert ("home_all",) in fake_controller.calls
    assert [lab.text() for lab in page.homed_labels] == ["yes"] * 3


def test_part_zero_table_and_touch_off(fake_window, fake_controller, dialogs) -> None:
    page = fake_window.page("part_zero")
    dialogs.answers.append(12.5)
    page.edit_cell(1, 0)  # G55 X
    assert fake_controller.work_offsets["G55"][0] == 12.5
    assert page.table.item(1, 0).text() == "+12.500"
    page.select_buttons["G55"].click()
    dialogs.answers.append(0.0)
    page.touch_buttons["Z"].click()
    assert fake_controller.calls[-1] == ("touch_off", "Z", 0.0, "G55")


def test_part_zero_shows_what_a_program_left_and_clears_g92(fake_window, fake_controller) -> None:
    page = fake_window.page("part_zero")
    assert page.extra_label.text() == "G92 offset: off" and not page.clear_g92_button.isEnabled()
    fake_controller.g92_offset = (1.5, -2.0, 0.0)
    fake_controller.xy_rotation_deg = 30.0
    fake_controller.offsetsChanged.emit(dict(fake_controller.work_offsets), "G54")
    assert "X+1.500 Y-2.000 Z+0.000" in page.extra_label.text()
    assert "XY rotation of G54: 30 degrees" in page.extra_label.text()
    page.clear_g92_button.click()
    assert fake_controller.calls[-1] == ("clear_g92",)
    assert page.extra_label.text().startswith("G92 offset: off")


def test_service_password_protects_service_pages(fake_window, dialogs) -> None:
    now = [1_000_000.0]
    fake_window.context.access.clock = lambda: now[0]
    dialogs.answers.append("wrong")
    assert not fake_window.show_page("parameters")
    assert fake_window._gates["parameters"].locked
    assert "wrong password; next try in 1 s" in fake_window._message.text()
    dialogs.answers.append("1234")              # too soon: refused without being checked
    assert not fake_window.show_page("axes")
    assert "wait 1 s before the next try" in fake_window._message.text()
    now[0] += 1.0
    dialogs.answers.append("1234")
    assert fake_window.show_page("axes")
    assert not fake_window._gates["axes"].locked and not fake_window._gates["parameters"].locked
    fake_window.page("parameters").lock()
    assert fake_window._gates["axes"].locked


def test_leaving_the_service_pages_or_idling_locks_them(fake_window, dialogs) -> None:
    now = [1_000_000.0]
    access = fake_window.context.access
    access.clock = lambda: now[0]
    dialogs.answers.append("1234")
    assert fake_window.show_page("parameters")
    assert fake_window.show_page("axes")         # between service pages: still unlocked
    fake_window.show_page("auto")
    assert not access.unlocked and fake_window._gates["axes"].locked
    dialogs.answers.append("1234")
    assert fake_window.show_page("axes")
    now[0] += IDLE_LOCK_S - 1
    fake_window._check_idle()
    assert access.unlocked
    now[0] += 1
    fake_window._check_idle()
    assert not access.unlocked and fake_window._gates["axes"].locked
    assert "without input" in fake_window._message.text()


def test_parameters_apply_goes_through_the_controller(fake_window, fake_controller, dialogs) -> None:
    page = fake_window.page("parameters")
    page.fields["v_max_mm_s"].setValue(25.0, emit=True)
    assert page.apply_bar.apply_button.isEnabled()
    page.mode_buttons["paper"].click()
    assert page.apply()
    assert fake_controller.config.machine.limits.v_max_mm_s == 25.0
    assert fake_controller.config.machine.planner.mode == "paper"
    dialogs.answers.append("enp2s0")
    page.adapter.click()
    assert page.pending.bus.adapter == "enp2s0" and page.adapter.text() == "enp2s0"
    page.fields["a_max_mm_s2"].setValue(-5.0, emit=True)
    assert "a_max_mm_s2" in page.apply_bar.message.text() and not page.apply_bar.apply_button.isEnabled()


def test_parameters_page_sets_the_corner_tolerance(fake_window, fake_controller, dialogs) -> None:
    page = fake_window.page("parameters")
    assert page.blend_field.value() == fake_controller.config.machine.planner.blend_tolerance_mm
    page.blend_field.setValue(0.02, emit=True)
    assert page.apply_bar.apply_button.isEnabled()
    assert page.apply()
    assert fake_controller.config.machine.planner.blend_tolerance_mm == 0.02
    page.revert()
    assert page.blend_field.value() == 0.02


def test_parameters_page_sets_the_corner_velocity_step(fake_window, fake_controller, dialogs,
                                                       tmp_path) -> None:
    """0 by default (joints within the jerk limit); a step typed in is applied, written to the
    file as ``[planner] corner_velocity_step_mm_s`` and read back; out of range is refused."""
    from app.machine.config import config_to_toml, load_config

    page = fake_window.page("parameters")
    assert page.corner_step_field.value() == 0.0
    page.corner_step_field.setValue(0.5, emit=True)
    assert page.apply_bar.apply_button.isEnabled()
    assert page.apply()
    assert fake_controller.config.machine.planner.corner_velocity_step_mm_s == 0.5
    path = tmp_path / "machine.toml"
    path.write_text(config_to_toml(fake_controller.config), encoding="utf-8")
    assert "corner_velocity_step_mm_s = 0.5" in path.read_text(encoding="utf-8")
    assert load_config(path).machine.planner.corner_velocity_step_mm_s == 0.5
    page.revert()
    assert page.corner_step_field.value() == 0.5
    page.corner_step_field.setValue(-1.0, emit=True)
    assert "corner_velocity_step_mm_s" in page.apply_bar.message.text()
    assert not page.apply_bar.apply_button.isEnabled()


def test_axes_page_edits_and_validates(fake_window, fake_controller, dialogs) -> None:
    page = fake_window.page("axes")
    dialogs.answers.append(-300.0)
    page.edit_cell(0, 4)  # X min
    assert page.pending.machine.axes[0].min_pos == -300.0
    page.edit_cell(1, 1)  # Y direction toggles
    assert page.pending.machine.axes[1].direction == -1
    dialogs.answers.append(500.0)
    page.edit_cell(0, 4)  # min 500 > max 250: invalid
    assert "min" in page.apply_bar.message.text()
    page.revert()
    assert page.pending is fake_controller.config


def test_alarms_banner_and_acknowledge(fake_window, fake_controller) -> None:
    fake_controller.raise_alarm("following error 1.2 mm over window 1.0 mm")
    header = fake_window.header
    assert header.alarm_banner.isVisibleTo(fake_window)
    assert "following error" in header.alarm_banner.text()
    header.alarm_banner.click()
    assert fake_window.current_page_name == "alarms"
    page = fake_window.page("alarms")
    assert page.table.rowCount() == 1
    page.table.selectRow(0)
    page.ack_button.click()
    assert not header.alarm_banner.isVisibleTo(fake_window)
    assert page.table.rowCount() == 0
    page.show_history.click()
    assert page.table.rowCount() == 1


def test_estop_button_and_state(fake_window, fake_controller, dialogs) -> None:
    header = fake_window.header
    header.estop_button.click()
    assert fake_controller.state.value == "estop"
    assert header.state_label.text() == "E-stop"
    header.estop_button.click()  # release, confirmed
    assert fake_controller.state.value == "idle"


def test_diagnostics_profile_and_bus(fake_window, fake_controller, qtbot) -> None:
    page = fake_window.page("diagnostics")
    fake_controller.load_program(DEMO_PROGRAM, wait=True)
    qtbot.wait(50)
    # planned when the page is shown, not beside the preview's work at every load
    assert page.profile is None and not page._planning.busy
    assert fake_window.show_page("diagnostics")
    qtbot.waitUntil(lambda: page.profile is not None, timeout=10000)
    p = page.profile
    assert p.cycle_time_s > 1.0 and len(p.t) > 1000
    assert abs(p.a).max() <= p.limits[1] * 1.01
    assert len(page.profile_plots.curves["v"].xData) == len(p.t)
    assert page.bus.table.rowCount() == 3 + 5       # three drives, a coupler and four terminals
    for i in range(5):
        fake_controller.trackingSample.emit(i / 30, (float(i) + 0.1, 0.0, 0.0), (float(i), 0.0, 0.0))
    page.tracking.redraw()
    curve = page.tracking.actual[0]
    assert list(curve.yData) == [0.0, 1.0, 2.0, 3.0, 4.0]  # the data, before clip-to-view
    assert page.tracking.reference[0].yData[1] == pytest.approx(1.1)


def test_preview_on_the_paper_yzca_machine(qtbot, qapp, state_dir, dialogs) -> None:
    """Y-Z-C-A machine (paper): the preview starts in the YZ plane; planes without axes are off."""
    from app.context import PanelOptions
    from app.machine.config import load_config
    from resources import shipped_machine
    from tests.app.conftest import make_window
    from tests.app.fake_controller import FakeController

    controller = FakeController(load_config(shipped_machine("paper_yzca")))
    window = make_window(qtbot, qapp, PanelOptions(state_dir=state_dir), dialogs, controller)
    program = "G21 G19 G90\nG00 Y10 Z0\nG02 Y20 Z0 R5 F600\nG01 C90\nM30\n"
    assert controller.load_program(program, name="yz.nc", wait=True)
    preview = window.page("preview")
    assert preview.plot.plane == "YZ" and not preview.plane_buttons["XY"].isEnabled()
    _y, z = preview.plot.items[MoveKind.ARC].getData()
    assert z.max() == pytest.approx(5.0)
    assert [label.text()[0] for label in window.header.dro.axis_labels] == ["Y", "Z", "C", "A"]
    # the Auto page's backplot in the same plane; rotary values and jog steps in degrees
    assert window.page("auto").backplot.plane == "YZ"
    dro = window.header.dro
    assert [w.text().endswith("°") for w in dro.work_labels] == [False, False, True, True]
    assert window.page("manual").jog.unit_label.text() == "mm/°"


def test_block_delete_is_switched_on_the_program_page_and_shown_on_the_auto_page(
        fake_window, fake_controller) -> None:
    program, auto = fake_window.page("program"), fake_window.page("auto")
    assert not program.block_delete.isChecked() and "/ lines skipped" not in auto.info_label.text()
    program.block_delete.click()
    assert fake_controller.calls[-1] == ("set_block_delete", True) and program.block_delete.isChecked()
    assert "/ lines skipped" in auto.info_label.text().split("\n")[0]
    fake_controller.modesChanged.emit(False, False, False)     # refused, or switched elsewhere
    assert not program.block_delete.isChecked() and "/ lines skipped" not in auto.info_label.text()
    assert program.block_delete.text() == "Block delete (/)"


def test_auto_page_shows_spindle_feed_tool_modal_codes_and_the_prompt(fake_window, fake_controller) -> None:
    from app.machine.model import HoldKind, MachineState, Prompt, RunSummary, SpindleState
    from planner.core.tools import Tool

    auto = fake_window.page("auto")
    fake_controller.load_program("G21 G90 G17 G55\nM3 S8000\nG0 X1\nG1 X5 F900\nG91 G1 X1 F300\nM30\n",
                                 wait=True)
    fake_controller.set_tool(Tool(2, 2, (("Z", 1.0),), 6.0, "6 mm flat"))
    fake_controller.set_tool_in_spindle(2)
    fake_controller.spindle = SpindleState(1, 8000.0)
    fake_controller.spindleChanged.emit(fake_controller.spindle)
    fake_controller.lineChanged.emit(4)
    text = auto.machine_label.text()
    assert "Spindle CW 8000 rpm" in text and "Tool T2 (6 mm flat)" in text
    assert "Feed F900 programmed" in text
    assert auto.modal_label.text() == "G17 G21 G90 G94 G55 G40 G49 G64"
    fake_controller.lineChanged.emit(5)
    assert "Feed F300 programmed" in auto.machine_label.text() and "G91" in auto.modal_label.text()
    fake_controller.prompt = Prompt(HoldKind.TOOL_CHANGE, 3, 2, "tool change (M06, line 3): insert tool T2 "
                                    "(6 mm flat) and press cycle start")
    fake_controller._set_state(MachineState.HOLD, "tool change", HoldKind.TOOL_CHANGE)
    assert auto.prompt_label.isVisibleTo(fake_window)
    assert auto.prompt_label.text().startswith("Tool change (M06, line 3): insert tool T2 (6 mm flat)")
    fake_controller._set_state(MachineState.IDLE)
    assert not auto.prompt_label.isVisibleTo(fake_window)
    fake_controller.programFinished.emit(RunSummary("p", True, 754.0, 750.0, 6))
    assert "Program finished in 12:34" in auto.info_label.text() and auto.progress.value() == 1000
    fake_controller.programErrors.emit(())                      # a refused load: no stale progress
    assert auto.progress.value() == 0 and "finished" not in auto.info_label.text()


def test_auto_page_shows_what_the_feed_override_does_where_it_is_not_what_it_is_set_to(
        fake_window, fake_controller) -> None:
    auto = fake_window.page("auto")
    fake_controller.set_feed_override(150)
    assert auto.feed.value_label.text() == "150 %"
    fake_controller.feedOverrideNote.emit("runs 100 %: program")      # a tap, M49
    assert auto.feed.value_label.text() == "150 % (runs 100 %: program)"
    auto.feed.buttons["+10"].click()                                # the knob still moves
    assert auto.feed.value_label.text() == "160 % (runs 100 %: program)"
    fake_controller.feedOverrideNote.emit("")
    assert auto.feed.value_label.text() == "160 %"


def test_auto_page_backplot_follows_the_run(fake_window, fake_controller) -> None:
    auto = fake_window.page("auto")
    fake_controller.load_program(DEMO_PROGRAM, wait=True)
    assert auto.backplot.path is not None and auto.backplot.path is fake_window.context.program.toolpath
    fake_controller.lineChanged.emit(14)
    x, _ = auto.backplot.done_item.getData()
    assert x is not None and len(x) > 0
    fake_controller.positionChanged.emit((9.0, 9.0, 9.0), (2.0, 3.0, -1.0))
    tx, ty = auto.backplot.tool_item.getData()
    assert (tx[0], ty[0]) == (2.0, 3.0)                     # work coordinates, like the path


def test_open_loads_the_program_into_the_machine(fake_window, fake_controller, dialogs) -> None:
    """What the editor shows after Open is what the machine has, not the previous program."""
    folder = Path(fake_window.context.folders.default)
    prog = folder / "part.nc"
    prog.write_text("G21 G90\nG0 X1\nG1 X2 F100\nM30\n")
    page = fake_window.page("program")
    dialogs.answers.append(str(prog))
    page.buttons["open"].click()
    assert fake_controller.calls[-1][0] == "load_program"
    assert fake_controller.program_info is not None and fake_controller.program_info.name == "part.nc"


def test_run_from_line_shows_the_way_before_asking(fake_window, fake_controller, dialogs,
                                                   monkeypatch) -> None:
    auto = fake_window.page("auto")
    fake_controller.load_program(DEMO_PROGRAM, wait=True)
    seen: list[object] = []

    def confirm(parent, title, text) -> bool:
        seen.append(auto.backplot.approach_item.getData())
        return False                                         # the operator says no

    monkeypatch.setattr(dialogs, "confirm", confirm)
    dialogs.answers.append(9.0)
    auto.run_from.click()
    (x, _y), = seen
    assert x is not None and len(x) == 2                     # drawn while the question is asked
    assert fake_controller.calls[-1] == ("restart_preview", 9)    # not run
    x, _ = auto.backplot.approach_item.getData()
    assert x is None or len(x) == 0                          # and removed afterwards


def test_the_production_tab_counts_parts_sets_a_target_and_exports_the_log(fake_window, fake_controller,
                                                                          dialogs, tmp_path) -> None:
    from app.machine.program.joblog import RunRecord

    view = fake_window.page("diagnostics").production
    fake_controller.part_count = 3
    fake_controller.run_log = [RunRecord("a.nc", "/p/a.nc", 1_800_000_000.0, 1_800_000_060.0, "completed",
                                         True,
                                         6, 58.5, (), 3),
                               RunRecord("a.nc", "/p/a.nc", 1_800_000_100.0, 1_800_000_120.0,
                                         "stopped by the operator", False, 4, 20.0,
                                         ("operator: E-stop pressed",), 0)]
    dialogs.answers.append(10)
    view.target_button.click()
    assert fake_controller.part_target == 10 and view.count_label.text() == "Parts: 3 of 10"
    assert view.table.rowCount() == 2
    assert [view.table.item(0, c).text() for c in (1, 2, 3, 5, 6)] == [
        "a.nc", "stopped by the operator", "4", "", "operator: E-stop pressed"]
    assert view.table.item(1, 2).text() == "completed" and view.table.item(1, 5).text() == "3"
    dialogs.answers.append(True)
    view.reset_button.click()
    assert fake_controller.calls[-1] == ("reset_part_count",) and view.count_label.text() == "Parts: 0 of 10"
    view.export_button.click()
    assert fake_controller.calls[-1][0] == "export_runs" and dialogs.asked[-1][0] == "inform"


def test_the_status_line_is_said_again_in_the_language_switched_to(fake_window, fake_controller) -> None:
    fake_window.context.i18n.set_language("tr")
    fake_controller.commandRefused.emit("cycle_start", "axes not homed")
    assert fake_window._message.text() == "Reddedildi: eksenler referanslanmadı"
    fake_window.context.i18n.set_language("en")
    assert fake_window._message.text() == "Refused: axes not homed"
