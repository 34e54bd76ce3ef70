"""The header (DRO, state, E-STOP) never moves and never leaves the screen: not with the
on-screen keyboard open, not when an alarm appears."""

from __future__ import annotations

import pytest
from PySide6.QtCore import QRect


def _geometry(window, widget) -> QRect:
    return QRect(widget.mapTo(window, widget.rect().topLeft()), widget.size())


@pytest.mark.parametrize("page_name, button", [("program", "keyboard"), ("manual", "keyboard")])
def test_the_keyboard_fits_beside_the_header(fake_window, qtbot, page_name: str, button: str) -> None:
    fake_window.show_page(page_name)
    qtbot.wait(10)
    estop_before = _geometry(fake_window, fake_window.header.estop_button)
    page = fake_window.page(page_name)
    toggle = page.buttons["keyboard"] if page_name == "program" else page.keyboard_button
    toggle.click()
    qtbot.wait(10)
    assert page.keyboard.isVisible()
    assert (fake_window.width(), fake_window.height()) == (1280, 800)
    screen = QRect(0, 0, 1280, 800)
    assert screen.contains(_geometry(fake_window, page.keyboard))
    assert _geometry(fake_window, fake_window.header.estop_button) == estop_before


def test_an_alarm_does_not_move_the_controls(fake_window, fake_controller, qtbot) -> None:
    fake_window.show_page("auto")
    qtbot.wait(10)
    nav = fake_window._buttons["manual"]
    before = _geometry(fake_window, nav)
    page_before = _geometry(fake_window, fake_window._stack)
    fake_controller.raise_alarm("following error 1.2 mm over window 1.0 mm")
    qtbot.wait(10)
    assert fake_window.header.alarm_banner.isVisibleTo(fake_window)
    assert _geometry(fake_window, nav) == before
    assert _geometry(fake_window, fake_window._stack) == page_before


def test_the_end_of_a_run_and_a_prompt_do_not_grow_the_auto_page(fake_window, fake_controller, qtbot) -> None:
    from app.machine.model import HoldKind, MachineState, Prompt, RunSummary

    fake_window.show_page("auto")
    fake_controller.prompt = Prompt(HoldKind.TOOL_CHANGE, 3, 2, "tool change (M06, line 3): insert tool T2 "
                                    "(6 mm flat end mill, a rather long description) and press cycle start")
    fake_controller._set_state(MachineState.HOLD, "tool change", HoldKind.TOOL_CHANGE)
    fake_controller.programFinished.emit(RunSummary("p", False, 754.0, 750.0, 6, reason="stopped by the "
                                                    "operator after a long and winding explanation"))
    qtbot.wait(10)
    assert (fake_window.width(), fake_window.height()) == (1280, 800)
