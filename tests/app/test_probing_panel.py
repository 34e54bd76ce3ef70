"""The probing wizards driven by touch on the real widgets (the Part zero page's Probe tab), on
the demo machine (the real controller, simulated drives and probe, a simulated part): the moves
drawn before the run, the offsets written, the stylus never deeper into the part than a stop's
overtravel, and a refusal said on the panel."""

from __future__ import annotations

import numpy as np
import pytest
from PySide6.QtCore import Qt

from app.machine.model import MachineState, ProbeWizard, ProbingRequest
from ethercat.sim_part import SimPart
from tests.machine.test_probing_wizards import MACHINE_CASES, PROBE, R, _Path

LEFT = Qt.MouseButton.LeftButton


def _idle(c) -> bool:
    return c.state is MachineState.IDLE and c.stream.job is None and c.worker.buffer_level() == 0


def _open_probe_tab(window, qtbot):
    assert window.show_page("part_zero")
    page = window.page("part_zero")
    bar = page.tabs.tabBar()
    qtbot.mouseClick(bar, LEFT, pos=bar.tabRect(1).center())
    assert page.tabs.currentWidget() is page.probing
    return page.probing


@pytest.mark.parametrize(("req", "part", "start", "truth"), MACHINE_CASES,
                         ids=[c[0].wizard.value for c in MACHINE_CASES])
def test_each_wizard_by_touch(demo_window, real_controller, dialogs, qtbot, req: ProbingRequest,
                              part: SimPart, start: tuple[float, float, float],
                              truth: dict[int, float]) -> None:
    c = real_controller
    assert c.set_tool(PROBE) and c.set_tool_in_spindle(PROBE.number)
    assert c.simulate_part(part)
    x, y, z = start
    for block in (f"G53 G0 Z{z + PROBE.length_mm:.4f}", f"G53 G0 X{x:.4f} Y{y:.4f}"):
        assert c.mdi(block)
        assert c.run_until(lambda: _idle(c), timeout_s=30)
    panel = _open_probe_tab(demo_window, qtbot)
    qtbot.mouseClick(panel.wizard_buttons[req.wizard], LEFT)
    if req.wizard in (ProbeWizard.EDGE, ProbeWizard.ANGLE):
        sign = req.x_dir if req.axis == "X" else req.y_dir
        qtbot.mouseClick(panel.move_buttons[f"{req.axis}{'+' if sign > 0 else '-'}"], LEFT)
    if req.wizard in (ProbeWizard.OUTSIDE_CORNER, ProbeWizard.INSIDE_CORNER):
        key = f"X{'+' if req.x_dir > 0 else '-'} Y{'+' if req.y_dir > 0 else '-'}"
        qtbot.mouseClick(panel.corner_buttons[key], LEFT)
    # the numbers typed on the keypad where they are not the defaults
    for key, value in (("diameter", req.diameter_mm), ("tolerance", req.tolerance_mm),
                       ("depth", req.depth_mm), ("along", req.along_mm), ("search", req.search_mm)):
        field = panel.fields[key]
        if value is not None and not field.isHidden() and field.value() != value:
            dialogs.answers.append(value)
            qtbot.mouseClick(field, LEFT)
            assert field.value() == value
    qtbot.mouseClick(panel.target_buttons["G55"], LEFT)
    assert c.probe_routine(panel.request()) == c.probe_routine(req)      # what the operator set
    assert panel.run_button.isEnabled(), panel.status.text()
    assert len(panel.preview.points) > 3 and panel.preview.probe_moves      # drawn before it runs
    path = _Path(c)
    before = c.work_offsets["G55"]
    qtbot.mouseClick(panel.run_button, LEFT)
    assert c.run_until(lambda: _idle(c), timeout_s=120), c.state_reason
    assert not c.active_alarms, [a.cause for a in c.active_alarms]
    for k, value in truth.items():
        got = c.work_rotation("G55") if k == 9 else c.work_offsets["G55"][k]
        assert got == pytest.approx(value, abs=0.01), (k, got)
    for k in range(3):
        if k not in truth:
            assert c.work_offsets["G55"][k] == before[k]
    text = panel.result.text()
    assert text.startswith("Found (machine): ") and text.endswith("written to G55")
    # the trace: the ball touched the part and stopped within the overtravel of a stop
    actual = path.actual()
    tip = actual - [0.0, 0.0, PROBE.length_mm - R]
    deepest = min(part.distance(*p) for p in tip[::5]) - R
    assert -0.3 < deepest < 0.0, deepest
    # the Part zero table shows what was written
    page = demo_window.page("part_zero")
    row = 1                                             # G55
    if 0 in truth:
        assert page.table.item(row, 0).text() == f"{c.work_offsets['G55'][0]:+.3f}"


def test_a_wizard_that_cannot_run_says_why_and_run_is_off(demo_window, real_controller, qtbot) -> None:
    c = real_controller
    assert c.set_tool_in_spindle(0)
    panel = _open_probe_tab(demo_window, qtbot)
    qtbot.mouseClick(panel.wizard_buttons[ProbeWizard.BORE], LEFT)
    assert not panel.run_button.isEnabled()
    assert panel.status.text() == ("Cannot run: no tool is in the spindle, not the probe T99: put the "
                                   "probe in and say so (In the spindle, or M61 Q99)")
    assert len(panel.preview.points) == 0
    # the probe put in: the reason goes, the moves are drawn
    assert c.set_tool(PROBE) and c.set_tool_in_spindle(PROBE.number)
    assert panel.run_button.isEnabled(), panel.status.text()
    assert len(panel.preview.points) > 3


def test_the_demo_s_end_mill_is_no_probe_the_z_surface_wizard_moves_nothing(
        demo_window, real_controller, qtbot) -> None:
    """The demo as it starts (T1, the 6 mm end mill, in the spindle): Part zero, Probe, Z
    surface, Run. Run stays off and says why, naming the probe; a touch on it moves nothing."""
    c = real_controller
    assert c.tool_in_spindle == 1 and c.config.probe.tool == 99
    panel = _open_probe_tab(demo_window, qtbot)
    qtbot.mouseClick(panel.wizard_buttons[ProbeWizard.Z_SURFACE], LEFT)
    assert not panel.run_button.isEnabled()
    assert "T1 is in the spindle, not the probe T99" in panel.status.text()
    path = _Path(c)
    before = tuple(c.machine_position)
    qtbot.mouseClick(panel.run_button, LEFT)
    c.run_until(lambda: False, timeout_s=1.0)
    assert c.state is MachineState.IDLE and tuple(c.machine_position) == before
    actual = path.actual()                    # the drives' positions over that second, every cycle
    assert len(actual) > 100 and float(np.abs(actual - np.array(before)).max()) == 0.0
