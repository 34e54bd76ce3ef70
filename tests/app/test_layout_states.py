"""No control moves or is cut off as the machine changes state: every button of the header,
the navigation and the Auto page keeps its place and size in idle, running, hold, E-stop and
alarm, at 1280x800 and 1920x1080, in English and in Turkish."""

from __future__ import annotations

import pytest
from PySide6.QtCore import QRect
from PySide6.QtWidgets import QPushButton

from app.machine.model import HoldKind, MachineState


def _buttons(window) -> dict[str, QRect]:
    """Every visible button of the header, the navigation and the Auto page, by name, where it
    sits in the window."""
    out: dict[str, QRect] = {}
    roots = [window.header, window.page("auto"), *window._buttons.values()]
    for root in roots:
        for b in [root, *root.findChildren(QPushButton)]:
            if isinstance(b, QPushButton) and b.isVisibleTo(window):
                out[f"{b.objectName() or b.text()!r} ({id(b)})"] = QRect(b.mapTo(window, b.rect().topLeft()),
                                                                       b.size())
    return out


def _clipped(window) -> list[str]:
    """Buttons whose text is wider than the button (a line of it)."""
    cut = []
    for b in window.findChildren(QPushButton):
        if not b.isVisibleTo(window) or not b.text():
            continue
        wide = max(b.fontMetrics().horizontalAdvance(line) for line in b.text().split("\n"))
        if wide > b.width() - 4:
            cut.append(f"{b.text()!r}: text {wide} px in {b.width()} px")
    return cut


@pytest.mark.parametrize("size", [(1280, 800), (1920, 1080)])
@pytest.mark.parametrize("language", ["en", "tr"])
def test_no_button_moves_or_is_cut_in_any_state(fake_window, fake_controller, qtbot, size, language) -> None:
    fake_window.context.i18n.set_language(language)
    fake_window.resize(*size)
    fake_window.show_page("auto")
    qtbot.wait(20)
    idle = _buttons(fake_window)
    assert len(idle) > 15
    states = [
        (MachineState.RUNNING, "program", HoldKind.NONE),
        (MachineState.HOLD, "feed hold", HoldKind.FEED_HOLD),
        (MachineState.HOLD, "tool change", HoldKind.TOOL_CHANGE),
        (MachineState.ESTOP, "operator", HoldKind.NONE),
        (MachineState.ALARM, "following error", HoldKind.NONE),
    ]
    for state, reason, hold in states:
        fake_controller._set_state(state, reason, hold)
        qtbot.wait(20)
        now = _buttons(fake_window)
        moved = {k: (idle[k], now.get(k)) for k in idle if now.get(k) != idle[k]}
        assert not moved, (state, moved)
        cut = _clipped(fake_window)
        assert not cut, (state, language, size, cut)
    fake_controller._set_state(MachineState.IDLE, "ready", HoldKind.NONE)


def test_no_button_moves_while_the_real_controller_runs_holds_and_stops(demo_window, real_controller,
                                                                        qtbot) -> None:
    c = real_controller
    demo_window.show_page("auto")
    qtbot.wait(20)
    idle = _buttons(demo_window)
    auto = demo_window.page("auto")
    auto.buttons["start"].click()
    for step in ("running", "hold", "stopped"):
        if step == "running":
            c.advance(2.0)
        elif step == "hold":
            auto.buttons["hold"].click()
            c.advance(2.0)
        else:
            auto.buttons["stop"].click()
            c.run_until(lambda: c.state is MachineState.IDLE, 10)
        qtbot.wait(20)
        now = _buttons(demo_window)
        moved = {k: (idle[k], now.get(k)) for k in idle if now.get(k) != idle[k]}
        assert not moved, (step, moved)
        assert not _clipped(demo_window), (step, _clipped(demo_window))


def test_the_open_dialogs_rows_and_the_editors_scroll_arrows_are_touch_targets(qtbot, demo_window,
                                                                              tmp_path) -> None:
    """48 px at least: a gloved finger hits the row or the arrow it aims at."""
    from PySide6.QtWidgets import QStyle, QStyleOptionSlider

    from app.widgets.file_picker import FilePicker

    for i in range(30):
        (tmp_path / f"part{i:02d}.nc").write_text("G0 X1\nM30\n")
    picker = FilePicker("Open program", tmp_path, demo_window)
    qtbot.addWidget(picker)
    picker.resize(800, 600)
    picker.show()
    qtbot.waitExposed(picker)
    rows = [picker.list.visualItemRect(picker.list.item(r)).height() for r in range(3)]
    assert min(rows) >= 48, rows
    editor = demo_window.page("program").editor
    editor.setPlainText("\n".join(f"G1 X{i}" for i in range(500)))
    demo_window.show_page("program")
    bar = editor.verticalScrollBar()
    qtbot.waitUntil(bar.isVisible, timeout=5000)
    opt = QStyleOptionSlider()
    bar.initStyleOption(opt)
    style = bar.style()
    for control in (QStyle.SubControl.SC_ScrollBarSubLine, QStyle.SubControl.SC_ScrollBarAddLine):
        rect = style.subControlRect(QStyle.ComplexControl.CC_ScrollBar, opt, control, bar)
        assert rect.width() >= 48 and rect.height() >= 48, (control, rect)
