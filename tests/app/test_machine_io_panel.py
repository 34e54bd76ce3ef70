"""The machine's signals on the panel, through the real widgets against the real controller on
simulated drives: the Signals tab, the header's E-stop chain and door, the coolant buttons, the
E-stop release refused while the chain is open, the homing method named on Machine zero."""

from __future__ import annotations

import pytest
from PySide6.QtWidgets import QPushButton


def _advance(qtbot, c, seconds: float = 0.3) -> None:
    c.advance(seconds)
    qtbot.wait(250)            # the header reads the signals 5 times a second


def test_the_signals_tab_lists_every_signal_where_it_is_wired_and_marks_the_open_door(
        qtbot, demo_window, real_controller) -> None:
    c = real_controller
    diag = demo_window.page("diagnostics")
    demo_window.show_page("diagnostics")
    diag.tabs.setCurrentWidget(diag.signals)
    qtbot.waitUntil(lambda: diag.signals.table.rowCount() > 10, timeout=5000)
    rows = {diag.signals.table.item(r, 0).text(): r for r in range(diag.signals.table.rowCount())}
    door = rows["door_closed"]
    assert diag.signals.table.item(door, 2).text() == "machine inputs (slave 4) channel 1"
    assert diag.signals.table.item(door, 3).text() == "on"
    assert c.simulate_input("door_closed", False)
    _advance(qtbot, c)
    qtbot.waitUntil(lambda: diag.signals.table.item(door, 3).text() == "off", timeout=5000)
    assert diag.signals.table.item(door, 3).background().color().name() == "#7a3b1d"
    assert diag.signals.table.item(rows["estop_chain_ok"], 3).background().color().name() != "#7a3b1d"
    # the EtherCAT tab lists the terminals with the drives
    table = diag.bus.table
    named = [table.item(r, 1).text() for r in range(table.rowCount())]
    assert "machine inputs (EL1008)" in named and "coupler (EK1100)" in named


def test_the_header_shows_the_chain_and_the_door_and_release_is_refused_while_the_chain_is_open(
        qtbot, demo_window, real_controller, dialogs) -> None:
    c = real_controller
    header = demo_window.header
    qtbot.waitUntil(lambda: header.safety_text == "chain and door closed", timeout=5000)
    assert c.simulate_input("estop_chain_ok", False)
    _advance(qtbot, c)
    qtbot.waitUntil(lambda: header.safety_text == "E-STOP CHAIN OPEN", timeout=5000)
    assert header.bus_label.text() == "Bus SIM: connected\nE-STOP CHAIN OPEN"
    assert header.bus_label.fontMetrics().horizontalAdvance("E-STOP CHAIN OPEN") < header.bus_label.width()
    assert c.state.value == "estop"
    assert header.estop_button.text() == "RELEASE\nE-STOP"
    refused: list[tuple[str, str]] = []
    c.commandRefused.connect(lambda action, why: refused.append((action, why)))
    dialogs.answers.append(True)
    header.estop_button.click()                 # release, confirmed: refused, saying why
    assert c.state.value == "estop"
    assert refused and "the E-stop chain is open" in refused[-1][1]
    assert c.simulate_input("estop_chain_ok", None)
    _advance(qtbot, c)
    dialogs.answers.append(True)
    header.estop_button.click()
    assert c.state.value == "idle"
    qtbot.waitUntil(lambda: header.safety_text == "chain and door closed", timeout=5000)


def test_the_coolant_buttons_switch_the_outputs_and_follow_a_programs_m8(qtbot, demo_window,
                                                                        real_controller) -> None:
    c = real_controller
    manual = demo_window.page("manual")
    demo_window.show_page("manual")
    flood: QPushButton = manual.coolant_buttons["flood"]
    assert manual.coolant_box.isVisible() and flood.isVisible()
    flood.click()
    _advance(qtbot, c, 0.05)
    assert c.coolant == (True, False)
    assert c.worker.snapshot().terminal_outputs[3] & 1
    flood.click()
    _advance(qtbot, c, 0.05)
    assert c.coolant == (False, False) and not c.worker.snapshot().terminal_outputs[3] & 1
    assert c.load_program("G21 G90\nM8\nG1 X20 F600\nM30\n", name="m8.nc", wait=True)
    assert c.cycle_start(wait=True)
    assert c.run_until(lambda: c.coolant[0], 2)
    qtbot.waitUntil(flood.isChecked, timeout=5000)   # the button follows the program
    assert c.run_until(lambda: c.state.value == "idle", 10)
    qtbot.waitUntil(lambda: not flood.isChecked(), timeout=5000)   # off at the program's end


def test_machine_zero_names_homing_to_the_switches(demo_window) -> None:
    page = demo_window.page("machine_zero")
    assert "to the home switches" in page.method_label.text()


def test_the_new_texts_fit_in_english_and_turkish(qtbot, demo_window, real_controller) -> None:
    """At 1280x800 the header's chain and door line fits its button, the coolant buttons and the
    Signals tab's headers show whole, in both languages."""
    c = real_controller
    header, manual = demo_window.header, demo_window.page("manual")
    demo_window.show_page("manual")
    try:
        for language in ("en", "tr"):
            demo_window.context.i18n.set_language(language)
            for open_ in (False, True):
                assert c.simulate_input("estop_chain_ok", None if not open_ else False)
                assert c.simulate_input("door_closed", None if not open_ else False)
                _advance(qtbot, c)
                qtbot.waitUntil(lambda: bool(header.safety_text), timeout=5000)
                fm = header.bus_label.fontMetrics()
                for line in header.bus_label.text().split("\n"):
                    assert fm.horizontalAdvance(line) <= header.bus_label.width() - 8, (language, line)
            for button in manual.coolant_buttons.values():
                assert button.fontMetrics().horizontalAdvance(button.text()) <= button.width() - 8, \
                    (language, button.text())
    finally:
        demo_window.context.i18n.set_language("en")


def test_the_handwheel_box_gives_the_wheel_an_axis_and_lights_while_it_moves_it(
        qtbot, demo_window, real_controller) -> None:
    """On the Manual page: X and x100 touched, the lamp lit and the DRO following the wheel's
    detents; E-stop puts the wheel off (the Off button checked, the lamp dark) and its counts
    then move nothing; a jog from the page while the wheel stands takes X and gives it back."""
    c = real_controller
    manual = demo_window.page("manual")
    demo_window.show_page("manual")
    box = manual.handwheel
    assert box.isVisible() and box.axis_buttons[""].isChecked()
    assert box.lamp.text() == "Off: choose an axis (0.001 a detent)"
    box.axis_buttons["X"].click()
    box.step_buttons[2].click()
    _advance(qtbot, c, 0.1)
    qtbot.waitUntil(lambda: box.lamp.text() == "Live: a detent moves X by 0.1", timeout=5000)
    x0 = c.machine_position[0]
    c.turn_handwheel(4 * 7)
    _advance(qtbot, c, 1.5)
    assert c.machine_position[0] == pytest.approx(x0 + 0.7, abs=1e-3)
    dro = demo_window.header.dro
    qtbot.waitUntil(lambda: dro.machine_text("X").strip().endswith(f"{x0 + 0.7:.3f}"), timeout=5000)
    manual.jog.jogStep.emit("Y", 1.0, 1)               # the page's jog: X is taken, then given back
    assert c.run_until(lambda: c.state.value == "idle", 5)
    _advance(qtbot, c, 0.2)
    qtbot.waitUntil(lambda: box.lamp.text() == "Live: a detent moves X by 0.1", timeout=5000)
    assert c.machine_position[1] == pytest.approx(1.0, abs=1e-3)
    demo_window.header.estop_button.click()
    _advance(qtbot, c, 0.2)
    qtbot.waitUntil(lambda: box.axis_buttons[""].isChecked(), timeout=5000)
    assert box.lamp.text() == "Off: choose an axis (0.1 a detent)" and c.state.value == "estop"
    x1 = c.reference_position[0]
    c.turn_handwheel(40)
    _advance(qtbot, c, 1.0)
    assert c.reference_position[0] == x1
