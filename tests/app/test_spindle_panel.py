"""The spindle's own drive on the Diagnostics page, through the real widgets against the real
controller on simulated drives: the commanded and read speeds drawn as the drive reads them,
the label saying when it is at speed; without a spindle drive the page says no speed is read."""

from __future__ import annotations

from pathlib import Path

import pytest

from resources import shipped_machine
from tests.app.conftest import window_on


@pytest.fixture
def spindle_window(qtbot, qapp, tmp_path: Path, dialogs):  # type: ignore[no-untyped-def]
    spindle = "\n[spindle]\ndrive = 8\naccel_rpm_s = 4000\n"
    window, c = window_on(qtbot, qapp, tmp_path, dialogs,
                          shipped_machine("xyz_mill").read_text(encoding="utf-8") + spindle)
    yield window, c
    c.shutdown()


def test_the_spindle_tab_draws_the_speeds_the_drive_is_sent_and_reads(qtbot, spindle_window) -> None:
    window, c = spindle_window
    diag = window.page("diagnostics")
    window.show_page("diagnostics")
    view = diag.spindle
    diag.tabs.setCurrentWidget(view)
    assert diag.tabs.tabText(diag.tabs.currentIndex()) == "Spindle"
    assert c.mdi("M3 S6000")
    c.advance(0.5)
    qtbot.wait(100)
    qtbot.waitUntil(lambda: "rpm read: not at speed" in view.text, timeout=5000)
    c.advance(2.0)
    qtbot.waitUntil(lambda: view.text.endswith("rpm read: at speed"), timeout=5000)
    snap = c.worker.snapshot()
    assert view.text == f"Spindle drive: 6000 rpm commanded, {snap.spindle_rpm_actual:.0f} rpm read: at speed"
    qtbot.wait(100)                                    # the page's timer draws
    t, read = view.read.getData()
    _t, commanded = view.commanded.getData()
    assert read[-1] == pytest.approx(snap.spindle_rpm_actual, abs=1.0) and commanded[-1] == 6000.0
    assert commanded.min() < 6000.0 and read.min() < 0.95 * 6000      # the ramp was drawn too
    assert (t[1:] >= t[:-1]).all()
    # the EtherCAT tab lists the spindle's drive after the axes' and the terminals, in its state
    table = diag.bus.table
    qtbot.waitUntil(lambda: table.item(table.rowCount() - 1, 4) is not None
                    and table.item(table.rowCount() - 1, 4).text() == "OPERATION_ENABLED", timeout=5000)
    last = table.rowCount() - 1
    assert (table.item(last, 0).text(), table.item(last, 1).text()) == ("8", "spindle")


def test_without_a_spindle_drive_the_tab_says_no_speed_is_read(demo_window) -> None:
    diag = demo_window.page("diagnostics")
    assert diag.spindle.text == "No spindle drive: the spindle is switched by output bits; no speed is read"
