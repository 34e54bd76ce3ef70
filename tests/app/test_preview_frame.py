"""The preview in work coordinates: the path where the program puts it, the work zero, the
machine's travel, the live tool on the path with offsets active, the 3-D view, Clear."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from app.toolpath import build_toolpath
from app.widgets.preview_plot import VIEW_3D
from planner.core.machine import MachineSpec
from planner.core.program import MoveKind
from planner.gcode.interpreter import parse_program

PROGRAM = "G21 G90 G55\nG0 X10 Y5 Z2\nG1 Z-1 F300\nG1 X20\nM30\n"


def test_the_path_is_drawn_in_work_coordinates() -> None:
    machine = MachineSpec.default()
    machine = replace(machine, work_offsets={**machine.work_offsets, "G55": (-5.0, 100.0, 0.0)})
    path = build_toolpath(parse_program(PROGRAM, machine=machine))
    pts = path.all.points
    assert pts[:, 0].max() == pytest.approx(20.0) and pts[:, 1].max() == pytest.approx(5.0)
    frame = path.frame_of(path.move_count - 1)
    assert frame is not None and frame.g5x == (-5.0, 100.0, 0.0)


def test_work_zero_travel_and_the_live_tool(fake_window, fake_controller) -> None:
    fake_controller.set_work_offset("G54", (-5.0, 0.0, 0.0))
    fake_controller.load_program("G21 G90\nG0 X10 Y0\nG1 X20 F300\nM30\n", wait=True)
    preview = fake_window.page("preview")
    plot = preview.plot
    x, _y = plot.envelope_item.getData()
    axes = fake_controller.config.machine.axes
    assert x.min() == pytest.approx(axes[0].min_pos + 5.0) and x.max() == pytest.approx(axes[0].max_pos + 5.0)
    assert len(x) == 24                                         # the 12 edges of the travel box
    zx, zy = plot.zero_item.getData()
    assert zx.min() < 0 < zx.max() and zy.min() < 0 < zy.max()  # the cross through the work zero
    assert "G54" in preview.note.text()
    fake_controller.positionChanged.emit((5.0, 0.0, 0.0), (10.0, 0.0, 0.0))   # machine X5 = work X10
    tx, _ = plot.tool_item.getData()
    assert tx[0] == pytest.approx(10.0)


def test_the_3d_view_turns_and_picks(fake_window, fake_controller) -> None:
    fake_controller.load_program("G21 G90\nG0 X10 Y0 Z5\nG1 Z0 F300\nG1 Y10\nM30\n", wait=True)
    preview = fake_window.page("preview")
    plot = preview.plot
    preview.set_plane(VIEW_3D)
    assert preview.turn_button.isEnabled() and plot.plane == VIEW_3D
    pts = np.array([[1.0, 2.0, 3.0]])
    plot.azimuth_deg, plot.elevation_deg = 0.0, 90.0            # from the top: (X, Y)
    assert np.allclose(np.ravel(plot.project(pts)), (1.0, 2.0))
    plot.elevation_deg = 0.0                                    # from the side: (X, Z)
    assert np.allclose(np.ravel(plot.project(pts)), (1.0, 3.0))
    preview.tilt_button.click()
    assert plot.elevation_deg == 15.0
    before = plot.items[MoveKind.LINE].getData()
    preview.turn_button.click()
    assert plot.azimuth_deg == 45.0
    after = plot.items[MoveKind.LINE].getData()
    assert not np.allclose(before[0], after[0])                 # redrawn turned
    u, v = plot.project(np.array([[10.0, 10.0, 0.0]]))         # the end of G1 Y10 (line 4)
    index = plot.pick(float(u[0]), float(v[0]), 0.5)
    assert index >= 0 and int(plot.path.move_lines[index]) == 4
    preview.set_plane("XY")
    assert not preview.turn_button.isEnabled()


def test_clear_empties_the_executed_part(fake_window, fake_controller) -> None:
    fake_controller.load_program("G21 G90\nG0 X10 Y0\nG1 X20 F300\nG1 Y10\nM30\n", wait=True)
    preview = fake_window.page("preview")
    fake_controller.lineChanged.emit(4)
    x, _ = preview.plot.done_item.getData()
    assert x is not None and len(x) > 0
    preview.clear_button.click()
    x, _ = preview.plot.done_item.getData()
    assert x is None or len(x) == 0
