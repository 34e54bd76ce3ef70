"""Leadscrew compensation on the Diagnostics page, through the real widgets against the real
controller on simulated drives: the EtherCAT tab's row of a compensated axis shows the
correction its drive is sent, which follows the direction of the axis' last move."""

from __future__ import annotations

from pathlib import Path

import pytest

from resources import shipped_machine
from tests.app.conftest import window_on
from tests.machine.conftest import run_to_idle

X_KEYS = "following_error_window = 1.0\n"          # the end of X's table in the shipped mill


@pytest.fixture
def comp_window(qtbot, qapp, tmp_path: Path, dialogs):  # type: ignore[no-untyped-def]
    text = shipped_machine("xyz_mill").read_text(encoding="utf-8")
    text = text.replace(X_KEYS, X_KEYS + "backlash = 0.02\n", 1)
    window, c = window_on(qtbot, qapp, tmp_path, dialogs, text)
    yield window, c
    c.shutdown()


def test_the_ethercat_tab_shows_the_correction_a_compensated_axis_is_sent(qtbot, comp_window) -> None:
    window, c = comp_window
    diag = window.page("diagnostics")
    window.show_page("diagnostics")
    diag.tabs.setCurrentWidget(diag.bus)
    table = diag.bus.table
    for target, text in ((10.0, "X (compensation +0.0100)"), (2.0, "X (compensation -0.0100)")):
        assert c.mdi(f"G0 X{target:g}")
        run_to_idle(c)
        c.advance(0.3)
        qtbot.waitUntil(lambda text=text: table.item(0, 1) is not None and table.item(0, 1).text() == text,
                        timeout=5000)
    assert table.item(1, 1).text() == "Y"                     # an axis without compensation
