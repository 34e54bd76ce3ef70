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


def test_a_vfd_spindle_shows_the_speed_commanded_and_the_volts_sent(qtbot, qapp, tmp_path: Path,
                                                                    dialogs) -> None:  # type: ignore[no-untyped-def]
    """A spindle on a VFD's analog input: the tab says what the analog output is sent (S x
    override over the speed at 10 V), the volts the bus carries on that channel."""
    from ethercat.terminals import ANALOG_FULL_SCALE, analog_channels

    vfd = ('\n[[bus.terminals]]\nposition = 8\ntype = "EL4002"\nname = "spindle speed"\n'
           '\n[spindle]\nanalog_out = "8:1"\nanalog_rpm_at_10v = 20000.0\n')
    window, c = window_on(qtbot, qapp, tmp_path, dialogs,
                          shipped_machine("xyz_mill").read_text(encoding="utf-8") + vfd)
    try:
        view = window.page("diagnostics").spindle
        assert view.text == ("Spindle on a VFD (analog output 8:1): 0 rpm commanded, 0.00 V sent; "
                             "no speed is read")
        assert c.mdi("M3 S6000") and c.set_spindle_override(120)
        c.advance(0.2)
        qtbot.waitUntil(lambda: "7200 rpm" in view.text, timeout=5000)
        assert view.text == ("Spindle on a VFD (analog output 8:1): 7200 rpm commanded, 3.60 V sent; "
                             "no speed is read")
        k = [t.position for t in c.config.wiring.terminals].index(8)
        word = c.worker.snapshot().terminal_outputs[k]
        assert analog_channels(word, 2)[1] * 10.0 / ANALOG_FULL_SCALE == pytest.approx(3.60, abs=0.01)
        assert c.mdi("M5")
        qtbot.waitUntil(lambda: "0.00 V sent" in view.text, timeout=5000)
    finally:
        c.shutdown()
