"""Small widgets: DRO formatting, keypad, numeric field, on-screen keyboard, editor, overrides."""

from __future__ import annotations

import math

import pytest
from PySide6.QtCore import Qt

from app.format import format_duration, format_speed, format_value
from app.widgets.code_editor import CodeEditor
from app.widgets.dro import DroWidget, format_position
from app.widgets.keyboard import OnScreenKeyboard
from app.widgets.keypad import NumericKeypad
from app.widgets.numeric_field import NumericField
from app.widgets.override_control import OverrideControl


@pytest.mark.parametrize(("value", "text"), [
    (0.0, "+0.000"), (-0.0001, "+0.000"), (1.23456, "+1.235"), (-250.0, "-250.000"),
    (12345.6789, "+12345.679"), (math.nan, "---.---"),
])
def test_format_position(value: float, text: str) -> None:
    assert format_position(value) == text


@pytest.mark.parametrize(("value", "wrapped", "text"), [
    (12.3456, False, "+12.346°"), (-90.0, False, "-90.000°"), (-90.0, True, "+270.000°"),
    (359.9999, True, "+0.000°"),
])
def test_a_rotary_position_reads_in_degrees(value: float, wrapped: bool, text: str) -> None:
    assert format_position(value, rotary=True, wrapped=wrapped) == text


def test_jog_steps_say_their_unit(qtbot) -> None:
    """Millimetres on a mill, degrees on a rotary table, both on the paper's Y-Z-C-A machine."""
    from app.i18n import I18n
    from app.widgets.jog_panel import JogPanel

    for axes, rotary, unit in ((("X", "Y", "Z"), (False, False, False), "mm"), (("C",), (True,), "°"),
                               (("Y", "Z", "C", "A"), (False, False, True, True), "mm/°")):
        panel = JogPanel(axes, I18n(), rotary=rotary)
        qtbot.addWidget(panel)
        assert panel.mode_buttons[0.001].text() == "0.001" and panel.mode_buttons[1.0].text() == "1"
        assert panel.unit_label.text() == unit


@pytest.mark.parametrize(("seconds", "text"), [
    (0, "0:00"), (59.6, "1:00"), (125, "2:05"), (3600 + 61, "1:01:01"), (math.nan, "--:--"), (-1, "--:--"),
])
def test_format_duration(seconds: float, text: str) -> None:
    assert format_duration(seconds) == text


@pytest.mark.parametrize(("value", "text"), [(5.52e-05, "5.520e-05"), (0.0032, "0.0032"), (0, "0"),
                                             (8.61e-04, "8.610e-04"), (12.5, "12.5")])
def test_format_value(value: float, text: str) -> None:
    assert format_value(value) == text


def test_format_speed() -> None:
    assert format_speed(15.0) == "900 mm/min"


def test_dro_shows_machine_and_work(qtbot) -> None:
    dro = DroWidget(("X", "Y", "Z"))
    qtbot.addWidget(dro)
    dro.set_positions((1.0, 2.0, -3.0), (0.5, 2.0, -13.0))
    assert dro.machine_text("Z") == "-3.000" and dro.work_text("Z") == "-13.000"
    assert dro.work_text("X") == "+0.500"
    dro.set_homed((True, False, True))
    assert dro.axis_labels[0].text().startswith("X") and "?" in dro.axis_labels[1].text()


def test_a_count_keypad_refuses_a_fraction_and_says_so(qtbot) -> None:
    """A parts target of 2.5 is refused with why, not stored as 2 without a word."""
    pad = NumericKeypad("Parts to make", 0.0, 0.0, 1_000_000.0, 0)
    qtbot.addWidget(pad)
    pad.press("C")
    for key in ("2", ".", "5"):
        pad.press(key)
    assert not pad.try_accept()
    assert pad.message.text() == "A whole number: 2.5 has a fraction"
    pad.press("⌫")
    pad.press("⌫")
    assert pad.display.text() == "2" and pad.try_accept() and pad.value() == 2.0


def test_keypad_enters_and_validates(qtbot) -> None:
    pad = NumericKeypad("Feed", 100.0, 0.0, 150.0, 1)
    qtbot.addWidget(pad)
    for key in ("1", "2", ".", "5"):
        pad.press(key)
    assert pad.value() == pytest.approx(12.5)
    pad.press("±")
    assert not pad.try_accept()  # -12.5 is out of range
    assert "Out of range" in pad.message.text()
    pad.press("±")
    pad.press("⌫")
    assert pad.display.text() == "12."
    assert pad.try_accept()
    for key in ("7", "8", "9", "4", "5", "6", "1", "2", "3", "0", "C", "OK", "Cancel"):
        assert pad.buttons[key].minimumHeight() >= 48


def test_numeric_field_opens_keypad_on_tap(qtbot) -> None:
    asked = []

    def ask(parent, title, value, lo, hi, decimals):
        asked.append((title, value, lo, hi))
        return 42.0

    field = NumericField("Vmax", 30.0, 0.0, 100.0, 1, "mm/s", ask=ask)
    qtbot.addWidget(field)
    with qtbot.waitSignal(field.valueChanged):
        qtbot.mouseClick(field, Qt.MouseButton.LeftButton)
    assert asked == [("Vmax", 30.0, 0.0, 100.0)]
    assert field.value() == 42.0 and field.text() == "42.0 mm/s"


def test_on_screen_keyboard_types_into_the_editor(qtbot) -> None:
    editor = CodeEditor()
    keyboard = OnScreenKeyboard()
    qtbot.addWidget(editor)
    qtbot.addWidget(keyboard)
    keyboard.set_target(editor)
    for key in ("G", "0", "1", "Space", "X", "1", "0", "Enter", "M", "3", "0", "⌫", "2"):
        keyboard.press(key)
    assert editor.toPlainText() == "G01 X10\nM32"
    assert all(b.minimumHeight() >= 48 and b.minimumWidth() >= 48 for b in keyboard.buttons.values())


def test_editor_errors_goto_and_find(qtbot) -> None:
    editor = CodeEditor()
    qtbot.addWidget(editor)
    editor.setPlainText("G21\nG01 X1 F100\nG02 X5 R1\nG01 X0\n")
    editor.set_errors({3: "arc radius too small"})
    assert editor.errors == {3: "arc radius too small"}
    assert editor.go_to_line(4) and editor.current_line() == 4
    assert editor.find_text("x1") and editor.current_line() == 2  # wraps around, case-insensitive
    editor.set_run_line(3)
    assert editor.run_line == 3 and editor.current_line() == 3
    assert not editor.go_to_line(99)


def test_override_control_does_not_echo(qtbot) -> None:
    control = OverrideControl("Feed")
    qtbot.addWidget(control)
    seen = []
    control.changed.connect(seen.append)
    control.set_value(80)
    assert seen == [] and control.value() == 80
    control.buttons["+10"].click()
    control.buttons["100%"].click()
    assert seen == [90.0, 100.0]


def test_highlighting_tokens_and_large_programs(qtbot) -> None:
    from app.widgets.gcode_highlighter import tokens

    kinds = [k for _s, _n, k in tokens("N10 G02 X1.5 Y-2 I.5 F600 (cut)")]
    assert kinds == ["number", "arc", "axis", "axis", "arcword", "feed", "comment"]
    assert [k for _s, _n, k in tokens("G1 G00 G17 M03")] == ["line", "rapid", "gcode", "mcode"]
    editor = CodeEditor()
    qtbot.addWidget(editor)
    editor.load_text("G01 X1\n" * 10)
    assert editor.highlighting
    editor.load_text("G01 X1\n" * 6000)
    assert not editor.highlighting and editor.blockCount() == 6001


def test_text_dialog_types_a_password_by_touch(qtbot) -> None:
    from app.widgets.text_dialog import TextDialog

    dialog = TextDialog("Service level", "Service password:", password=True)
    qtbot.addWidget(dialog)
    for key in ("Aa", "A", "B", "Aa", "C", "1"):
        dialog.keyboard.press(key)
    assert dialog.text() == "abC1"
    assert dialog.field.echoMode() == dialog.field.EchoMode.Password


def test_file_picker_lists_folders_and_gcode(qtbot, tmp_path) -> None:
    from app.widgets.file_picker import FilePicker

    (tmp_path / "jobs").mkdir()
    (tmp_path / "jobs" / "part.ngc").write_text("G0 X0\n")
    (tmp_path / "notes.pdf").write_text("x")
    (tmp_path / "a.nc").write_text("G0 X0\n")
    picker = FilePicker("Open", tmp_path)
    qtbot.addWidget(picker)
    assert picker.entries() == ["jobs/", "a.nc"]
    picker.choose("jobs/")
    assert picker.entries() == ["part.ngc"]
    picker.choose("part.ngc")
    assert picker.selected == (tmp_path / "jobs" / "part.ngc").resolve()


@pytest.mark.parametrize("kind, text", [("single_block", "Single block"), ("tool_change", "Tool change"),
                                        ("program_stop", "Program stop (M0)"), ("feed_hold", "Feed hold")])
def test_the_header_names_the_hold(fake_window, fake_controller, kind: str, text: str) -> None:
    from app.machine.model import HoldKind, MachineState

    fake_controller._set_state(MachineState.HOLD, "", HoldKind(kind))
    assert fake_window.header.state_label.text() == text


@pytest.mark.parametrize("options", [
    ["Resume at line 12", "Start from the beginning", "Cancel"],
    ["12. satırda devam et", "Baştan başlat", "İptal"],
    ["T2 6 mm flat", "T3 10 mm ball nose", "T99 probe", "Cancel"],
])
def test_a_choice_shows_each_button_s_whole_text(qtbot, qapp, options: list[str]) -> None:
    """With the panel's style at 1280x800, every button of a choice is as wide as its text: the
    box grows to them ("Resume at line 12" was cut to "esume at line 1")."""
    from app.application import apply_theme
    from app.dialogs import choice_box

    apply_theme(qapp)
    box, buttons = choice_box(None, "Cycle start", "The program stopped at line 12 (reset).", options)
    qtbot.addWidget(box)
    box.show()
    qapp.processEvents()
    for button in buttons:
        needed = button.fontMetrics().horizontalAdvance(button.text())
        assert button.contentsRect().width() >= needed, button.text()
    box.close()
