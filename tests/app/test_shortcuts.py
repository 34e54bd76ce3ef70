"""Keyboard shortcuts as LinuxCNC's panels have them: jog while held, Esc stops, F1 toggles
the E-stop; never a jog while a text field has the focus; configurable in panel.json."""

from __future__ import annotations

import json
from pathlib import Path

from PySide6.QtCore import QEvent, Qt
from PySide6.QtGui import QKeyEvent
from PySide6.QtWidgets import QApplication, QLineEdit

from app.machine.model import MachineState
from app.shortcuts import parse_bindings


def _calls(fake_controller, name: str) -> list[tuple]:
    return [c for c in fake_controller.calls if c[0] == name]


def test_an_arrow_jogs_while_held_and_auto_repeat_is_one_jog(qtbot, fake_window, fake_controller) -> None:
    fake_window.setFocus()
    qtbot.keyPress(fake_window, Qt.Key.Key_Right)
    for _ in range(3):   # a held key repeats: still one jog
        QApplication.sendEvent(fake_window, QKeyEvent(QEvent.Type.KeyPress, Qt.Key.Key_Right,
                                                      Qt.KeyboardModifier.NoModifier, "", True))
    assert _calls(fake_controller, "jog_start") == [("jog_start", "X", 1)]
    qtbot.keyRelease(fake_window, Qt.Key.Key_Right)
    assert _calls(fake_controller, "jog_stop") == [("jog_stop", "X")]
    qtbot.keyPress(fake_window, Qt.Key.Key_PageDown)
    assert _calls(fake_controller, "jog_start")[-1] == ("jog_start", "Z", -1)
    qtbot.keyRelease(fake_window, Qt.Key.Key_PageDown)
    assert _calls(fake_controller, "jog_stop")[-1] == ("jog_stop", "Z")


def test_typing_in_a_text_field_never_jogs(qtbot, fake_window, fake_controller) -> None:
    field = fake_window.findChild(QLineEdit)
    assert field is not None
    field.setFocus()
    qtbot.keyPress(field, Qt.Key.Key_Left)
    qtbot.keyRelease(field, Qt.Key.Key_Left)
    assert _calls(fake_controller, "jog_start") == []


def test_esc_stops_and_f1_toggles_the_estop_with_confirmation(qtbot, fake_window, fake_controller,
                                                               dialogs) -> None:
    fake_controller._set_state(MachineState.RUNNING)
    qtbot.keyPress(fake_window, Qt.Key.Key_Escape)
    assert _calls(fake_controller, "stop") == [("stop",)]
    qtbot.keyPress(fake_window, Qt.Key.Key_F1)
    assert fake_controller.state is MachineState.ESTOP
    qtbot.keyPress(fake_window, Qt.Key.Key_F1)          # release asks first
    assert ("confirm", "Release the emergency stop and enable the drives?") in dialogs.asked
    assert fake_controller.state is MachineState.IDLE


def test_bindings_are_configurable_and_bad_entries_are_named() -> None:
    b = parse_bindings({"jog_z_plus": "Home", "stop": "", "jog_x_plus": "Ctrl+K", "fly": "F9"})
    assert b.keys[int(Qt.Key.Key_Home.value)] == "jog_z_plus"
    assert int(Qt.Key.Key_Escape.value) not in b.keys                   # unbound
    assert b.keys[int(Qt.Key.Key_Right.value)] == "jog_x_plus"           # bad key: default kept
    assert any("'jog_x_plus'" in p and "Ctrl+K" in p for p in b.problems)
    assert any("'fly'" in p and "no such action" in p for p in b.problems)
    clash = parse_bindings({"jog_y_plus": "Right"})
    assert any("already" in p for p in clash.problems)


def test_the_panel_reads_its_shortcuts_from_the_settings(qtbot, qapp, state_dir: Path, dialogs,
                                                         fake_controller) -> None:
    from app.context import PanelOptions
    from tests.app.conftest import make_window

    (state_dir / "panel.json").write_text(json.dumps({"shortcuts": {"jog_x_plus": "D"}}))
    window = make_window(qtbot, qapp, PanelOptions(state_dir=state_dir), dialogs, fake_controller)
    window.setFocus()
    qtbot.keyPress(window, Qt.Key.Key_Right)
    assert _calls(fake_controller, "jog_start") == []
    qtbot.keyPress(window, Qt.Key.Key_D)
    assert _calls(fake_controller, "jog_start") == [("jog_start", "X", 1)]
