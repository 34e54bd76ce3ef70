"""The sample geometry in C (planner/geometry/_kernels.c: positions along moves and their
distance from the programmed contour) agrees with the NumPy forms, which stay the reference
(and the fallback where no compiler built the module), on every kind of move: lines, arcs and
helices in the three planes, spirals, arcs in turned frames, arcs of a large radius, blends;
programs at scales 0.001 to 1000."""

from __future__ import annotations

import os

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import planner.geometry.movetable as movetable
from planner.geometry.movetable import MoveTable, contour_error, contour_error_numpy
from planner.motion.blending import blend_program
from planner.motion.plan import plan_program
from tests.planner.motion_programs import paper_machine, parse, programs

if movetable._kernels is None:
    if os.environ.get("CI"):
        raise AssertionError("planner.geometry._kernels is not built: `pip install -e .` compiles it (gcc)")
    pytest.skip("planner.geometry._kernels is not built here (no compiler?): NumPy runs",
                allow_module_level=True)

from planner.geometry import _kernels  # noqa: E402


def _table(text: str, blend: bool = False) -> MoveTable:
    m = paper_machine()
    program = parse(text, m)
    if blend:
        program = blend_program(program, m, only_where_quicker=False)
    return plan_program(program, m).segment.table


def _compare(table: MoveTable, seed: int, scale: float) -> None:
    """Positions and contour errors of random samples (before, inside and past each move)
    from both forms: equal to rounding of the coordinates' size."""
    rng = np.random.default_rng(seed)
    n = len(table)
    assert n > 0
    row = rng.integers(0, n, 4000)
    u = table.length[row] * rng.uniform(-0.1, 1.1, row.size)
    u[::7] = table.length[row[::7]]                      # exact ends
    size = 1.0 + float(np.max(np.abs(table.start))) + float(np.max(np.abs(table.end)))
    ours = table.positions(row, u)
    ref = table.positions_numpy(row, u)
    np.testing.assert_allclose(ours, ref, rtol=0.0, atol=1e-12 * size)
    # points near the path (a sample's error) and a little off it
    q = ref + rng.normal(0.0, 1e-3 * scale, ref.shape) * (rng.uniform(size=(row.size, 1)) < 0.5)
    u_in = np.clip(u, 0.0, table.length[row])
    np.testing.assert_allclose(contour_error(table, row, q, u_in), contour_error_numpy(table, row, q, u_in),
                               rtol=1e-9, atol=1e-11 * size)


@settings(max_examples=60, deadline=None)
@given(programs(max_blocks=14), st.integers(0, 2**31))
def test_the_compiled_geometry_is_the_numpy_geometry(text, seed):
    table = _table(text)
    assume(len(table) > 0)
    _compare(table, seed, 1.0)


@settings(max_examples=40, deadline=None)
@given(st.sampled_from([0.001, 1.0, 1000.0]), st.data())
def test_at_every_scale_and_in_turned_frames(scale, data):
    text = data.draw(programs(max_blocks=10, scale=scale, rotated=data.draw(st.booleans())))
    table = _table(text)
    assume(len(table) > 0)
    _compare(table, data.draw(st.integers(0, 2**31)), scale)


@pytest.mark.parametrize("text, kinds", [
    # a spiral (end radius 10.01 about a centre 10 from the start)
    ("G21 G90 G17 F1200\nG0 X0 Y0 Z0\nG2 X20.01 Y0 I10 J0\nM2\n", "spiral"),
    # an arc of 5 m radius (positions from the start point's radius vector)
    ("G21 G90 G17 F1200\nG0 X0 Y0 Z0\nG2 X100 Y0 R5000\nM2\n", "far"),
    # a helix in G18 and a turned frame (G10 L2 R turns the work offset about Z)
    ("G21 G90 F1200\nG10 L2 P1 R30\nG54 G0 X0 Y0 Z0\nG18 G2 X10 Z0 Y4 I5 K0\nM2\n", "turned"),
    # corners blended by clothoid pairs
    ("G21 G90 G17 G64 P0.05 F3000\nG0 X0 Y0 Z0\nG1 X10\nY10\nX20 Y12\nX30 Z-1\nM2\n", "blend"),
])
def test_the_rows_left_to_numpy_are_computed_there(text, kinds):
    table = _table(text, blend=kinds == "blend")
    special = {"spiral": table.spiral, "far": table.r0 > 1000.0, "turned": table.turn != 0.0,
               "blend": table.is_blend}[kinds]
    assert special.any()              # the case is there
    _compare(table, 7, 1.0)


def test_strided_columns_are_read_as_they_are():
    """A table's column that repeats one row is a broadcast view (stride 0): read in place."""
    table = _table("G21 G90 G17 F1200\nG0 X0 Y0 Z0\nG1 X10\nG2 X20 Y0 R5\nG1 X30 Y5 Z1\nM2\n")
    cols = {name: getattr(table, name) for name in MoveTable.__slots__}
    cols["turn"] = np.broadcast_to(np.zeros(1), (len(table),))
    cols["is_blend"] = np.broadcast_to(np.zeros(1, dtype=bool), (len(table),))
    strided = MoveTable(**cols)
    assert strided.turn.strides == (0,)
    _compare(strided, 3, 1.0)


def test_bad_arguments_are_refused():
    table = _table("G21 G90 G17 F1200\nG0 X0 Y0 Z0\nG1 X10\nM2\n")
    args = [table.start, table.delta, table.length, table.is_arc, table.is_blend, table.turn, table.first,
            table.second, table.cx, table.cy, table.r0, table.r1, table.theta0, table.sweep]
    q, u, out = np.zeros((2, table.n_axes)), np.zeros(2), np.zeros(2)
    with pytest.raises(IndexError, match="outside the table"):
        _kernels.contour_error(*args, np.array([0, len(table)], dtype=np.int64), q, u, out)
    with pytest.raises(TypeError, match="row must be"):
        _kernels.contour_error(*args, np.array([0, 0], dtype=np.int32), q, u, out)
    with pytest.raises(ValueError, match="shapes do not agree"):
        _kernels.contour_error(*args, np.array([0, 0], dtype=np.int64), q, u, np.zeros(3))
