"""The paper's own centre and angle selection (Eq. 1-9, Table 1) agrees with the vector form.

Agreement on every quadrant (direction of the chord), both directions and all three
planes, except where the paper's formulas are singular. The singular cases, named:
  1. chord parallel to the first axis (y0 == y1): Eq. 4-5 divide by y0 - y1;
  2. start point straight above/below the centre (x0 == xc): Eq. 8-9 divide by x0 - xc;
  3. start == end: rho = 0 in Eq. 1-2;
  4. R < 0 (arcs over 180 degrees): not covered by the paper.
The vector form (planner.geometry.arcs.center_from_radius) handles all of them.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from planner.gcode.interpreter import parse_program
from planner.geometry.arcs import PaperSingular, center_from_radius, paper_center_and_angles

PLANES = {"G17": ("X", "Y", "Z"), "G18": ("Z", "X", "Y"), "G19": ("Y", "Z", "X")}
# 8 chord directions that avoid the singular ones (0 and 180 deg: chord parallel to the first axis)
DIRECTIONS_DEG = [22.5, 67.5, 90.0, 157.5, 202.5, 270.0, 292.5, 337.5]  # every quadrant + vertical
FACTORS = [1.0, 1.0001, 1.5, 10.0]  # |R| / half chord (1.0: half circle)


def ours(plane: str, g: int, p0, p1, r: float):
    first, second, normal = PLANES[plane]
    text = (
        f"G0 {first}{p0[0]:.17f} {second}{p0[1]:.17f}\n{plane} G1 F60\n"
        f"G{g} {first}{p1[0]:.17f} {second}{p1[1]:.17f} R{r:.17f}\n"
    )
    arc = parse_program(text).moves[-1].arc
    return arc


def to_paper_angles(g: int, start_angle_rad: float, sweep_rad: float) -> tuple[float, float]:
    """Our (angle of the start point, signed sweep) in the paper's Eq. 12/13 parametrisation."""
    a = math.degrees(start_angle_rad)
    if g == 2:  # Eq. 12: x - xc = -R cos(alpha), y - yc = R sin(alpha): alpha = 180 - angle
        a = 180.0 - a
    return a % 360.0, abs(math.degrees(sweep_rad))


@pytest.mark.parametrize("plane", sorted(PLANES))
@pytest.mark.parametrize("g", [2, 3])
@pytest.mark.parametrize("direction", DIRECTIONS_DEG)
@pytest.mark.parametrize("factor", FACTORS)
def test_paper_agrees_with_vector_form(plane, g, direction, factor):
    p0 = (1.25, -0.75)
    chord = 7.0
    phi = math.radians(direction)
    p1 = (p0[0] + chord * math.cos(phi), p0[1] + chord * math.sin(phi))
    r = chord / 2 * factor
    arc = ours(plane, g, p0, p1, r)
    xc, yc, theta0, theta = paper_center_and_angles(p0[0], p0[1], p1[0], p1[1], r, g)
    # Not singular but ill-conditioned: at a half circle Eq. 3 takes the square root of a
    # difference of squares that is zero up to rounding, so the paper's centre is only good
    # to about sqrt(machine epsilon) * R there (the vector form snaps it exactly).
    tol = 1e-9 if factor > 1.0 else 1e-7 * r
    tol_deg = 1e-7 if factor > 1.0 else 1e-4  # asin at 1 has the same sqrt(eps) loss
    assert (xc, yc) == pytest.approx(arc.center, abs=tol)
    a0, sweep = to_paper_angles(g, arc.start_angle_rad, arc.sweep_rad)
    assert theta == pytest.approx(sweep, abs=tol_deg)
    assert (theta0 - a0 + 180.0) % 360.0 - 180.0 == pytest.approx(0.0, abs=tol_deg)
    # and the paper's Eq. 12/13 trace the same points as our evaluation
    move = parse_program(
        f"G0 {PLANES[plane][0]}{p0[0]:.17f} {PLANES[plane][1]}{p0[1]:.17f}\n{plane} G1 F60\n"
        f"G{g} {PLANES[plane][0]}{p1[0]:.17f} {PLANES[plane][1]}{p1[1]:.17f} R{r:.17f}"
    ).moves[-1]
    alpha = np.radians(np.linspace(theta0, theta0 + theta, 9))
    sx = -1.0 if g == 2 else 1.0
    paper_pts = np.column_stack([sx * r * np.cos(alpha) + xc, r * np.sin(alpha) + yc])
    pos, _, _ = move.evaluate(np.linspace(0.0, move.length_mm, 9))
    np.testing.assert_allclose(pos[:, [arc.first_axis, arc.second_axis]], paper_pts, atol=max(tol, 1e-9) * 10)


def test_singular_chord_parallel_to_first_axis():
    with pytest.raises(PaperSingular, match="Eq. 4-5"):
        paper_center_and_angles(0.0, 0.0, 10.0, 0.0, 7.0, 2)
    # the vector form has no singular case
    assert center_from_radius(0.0, 0.0, 10.0, 0.0, 7.0, True) == pytest.approx((5.0, -math.sqrt(24)))


def test_singular_start_above_centre():
    # start (0, 5), end (5, 0), R 5: G02 centre (0, 0) is straight below the start
    with pytest.raises(PaperSingular, match="Eq. 8-9"):
        paper_center_and_angles(0.0, 5.0, 5.0, 0.0, 5.0, 2)
    assert center_from_radius(0.0, 5.0, 5.0, 0.0, 5.0, True) == pytest.approx((0.0, 0.0), abs=1e-12)


def test_singular_start_equals_end_and_negative_r():
    with pytest.raises(PaperSingular, match="rho = 0"):
        paper_center_and_angles(1.0, 1.0, 1.0, 1.0, 5.0, 3)
    with pytest.raises(PaperSingular, match="R > 0 only"):
        paper_center_and_angles(0.0, 0.0, 3.0, 4.0, -5.0, 3)


def test_printing_error_eq8_condition():
    """Eq. 8 as printed (x0 > xc) does not reproduce the start point with Eq. 12."""
    x0, y0, x1, y1, r = 0.0, 0.0, 3.0, -2.0, 5.0
    xc, yc, theta0, _ = paper_center_and_angles(x0, y0, x1, y1, r, 2)
    # corrected: Eq. 12 at alpha = theta0 gives the start point
    a = math.radians(theta0)
    assert (-r * math.cos(a) + xc, r * math.sin(a) + yc) == pytest.approx((x0, y0), abs=1e-12)
    # as printed: the other branch
    t = math.degrees(math.atan(-(y0 - yc) / (x0 - xc)))
    printed = t if x0 > xc else 180.0 + t
    b = math.radians(printed)
    assert (-r * math.cos(b) + xc, r * math.sin(b) + yc) != pytest.approx((x0, y0), abs=1e-6)


def test_table2_naive_g18_mapping_flips_direction():
    """Table 2 maps G18 to (x, y) = (X, Z); RS274/NGC's G18 frame is (Z, X). Used naively,
    the paper's G02 centre in (X, Z) is the centre of our G03 (seen from +Y), and vice versa."""
    start = {"X": 1.0, "Z": 2.0}
    end = {"X": 4.0, "Z": 6.5}
    r = 4.0
    xc, zc, _, _ = paper_center_and_angles(start["X"], start["Z"], end["X"], end["Z"], r, 2)
    g02 = ours("G18", 2, (start["Z"], start["X"]), (end["Z"], end["X"]), r)
    g03 = ours("G18", 3, (start["Z"], start["X"]), (end["Z"], end["X"]), r)
    assert (zc, xc) == pytest.approx(g03.center, abs=1e-9)
    assert (zc, xc) != pytest.approx(g02.center, abs=1e-3)
