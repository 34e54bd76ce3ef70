"""A gantry on the panel, through the real widgets against the real controller on simulated
drives: the DRO shows one Y; the Diagnostics page's EtherCAT tab lists both of Y's drives, the
second with its own slave position, state and the pair's skew; a skew alarm reaches the
operator's alarm list with the gantry named."""

from __future__ import annotations

from pathlib import Path

import pytest

from resources import shipped_machine
from tests.app.conftest import window_on


@pytest.fixture
def gantry_window(qtbot, qapp, tmp_path: Path, dialogs):  # type: ignore[no-untyped-def]
    window, c = window_on(qtbot, qapp, tmp_path, dialogs,
                          shipped_machine("gantry_mill").read_text(encoding="utf-8"))
    yield window, c
    c.shutdown()


def test_the_dro_shows_one_y_and_diagnostics_both_drives(qtbot, gantry_window) -> None:
    window, c = gantry_window
    dro = window.header.dro
    assert dro.axes == ("X", "Y", "Z")
    assert [label.text()[0] for label in dro.axis_labels] == ["X", "Y", "Z"]
    diag = window.page("diagnostics")
    window.show_page("diagnostics")
    diag.tabs.setCurrentWidget(diag.bus)
    c.advance(0.1)
    table = diag.bus.table
    qtbot.waitUntil(lambda: table.item(3, 4) is not None and table.item(3, 4).text() == "OPERATION_ENABLED",
                    timeout=5000)
    rows = [(table.item(r, 0).text(), table.item(r, 1).text()) for r in range(4)]
    assert rows[:3] == [("0", "X"), ("1", "Y"), ("2", "Z")]
    assert rows[3][0] == "8" and rows[3][1].startswith("Y2 (gantry Y, skew ")
    # the second side jams while Y moves: the alarm names the gantry, the machine stops
    assert c.mdi("G91 G1 Y-40 F3000")
    c.advance(0.4)
    c.worker.inject("jam", 3)
    c.advance(0.3)
    qtbot.waitUntil(lambda: c.state.name == "ALARM", timeout=5000)
    causes = [a.cause for a in c.alarms]
    assert any(t.startswith("gantry Y: its drives Y and Y2 are ") for t in causes), causes
