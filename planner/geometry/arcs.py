"""Arc centre, radius and sweep in a plane's (first, second) frame, as LinuxCNC 2.9 reads them.

All functions work on plain floats (no NumPy) because they run once per G02/G03 block.
Frame: (first, second) = XY for G17, ZX for G18, YZ for G19; angles counter-clockwise seen
from the positive normal axis; G02 = clockwise = negative sweep.

Rules (LinuxCNC interp_arc.cc, figures in ../shared/gcode/README.md):
- R form: an error when the half chord exceeds |R| by more than ``R_TOLERANCE_MM``;
  within that the arc is snapped to an exact half circle. R < 0 selects the arc over
  180 degrees. start = end is an error.
- I/J/K form: start and end radius may differ by at most the absolute spiral tolerance
  (2 * 0.01 mm * sqrt 2 in G21; 2 * 0.001 inch * sqrt 2 in G20, in program units as
  LinuxCNC applies it), or by at most 0.1 % of the radius if that is larger, up to 100
  times the absolute tolerance; inside that the arc is a spiral. start = end is a full
  circle. A radius below ``R_TOLERANCE_MM`` is a zero-radius arc.

``paper_center_and_angles`` is the paper's own method (Eq. 1-9, Table 1), kept separate
for the agreement test.
"""

from __future__ import annotations

import math

__all__ = [
    "ArcError",
    "R_TOLERANCE_MM",
    "SPIRAL_ABS_TOLERANCE_MM",
    "SPIRAL_ABS_TOLERANCE_INCH",
    "SPIRAL_REL_TOLERANCE",
    "center_from_radius",
    "check_center_radii",
    "sweep_angle",
    "paper_center_and_angles",
    "PaperSingular",
]

MM_PER_INCH = 25.4
R_TOLERANCE_MM = 0.00005 * MM_PER_INCH  # LinuxCNC TOLERANCE_INCH = 0.00005 in = 0.00127 mm
SPIRAL_ABS_TOLERANCE_MM = 2 * 0.01 * math.sqrt(2.0)  # 0.02828 mm (G21)
SPIRAL_ABS_TOLERANCE_INCH = 2 * 0.001 * math.sqrt(2.0)  # 0.002828 in (G20)
SPIRAL_REL_TOLERANCE = 0.001  # 0.1 %
_TINY = 1e-12  # LinuxCNC's TINY: half chord / |R| above 1 - TINY is a half circle
TWO_PI = 2.0 * math.pi
FULL_CIRCLE_MM = 1e-9  # start and end closer than this in the plane: a full circle (centre form)


class ArcError(Exception):
    """An arc the rules reject; the interpreter turns it into a located ProgramError."""


def center_from_radius(
    x0: float, y0: float, x1: float, y1: float, radius: float, clockwise: bool
) -> tuple[float, float]:
    """Centre of the R-form arc from (x0, y0) to (x1, y1): vector form, no singular case.

    Chord midpoint plus or minus sqrt(R^2 - h^2) along the chord normal (h = half chord).
    For G02 with R > 0 (arc at most 180 deg) the centre lies right of the chord P0 -> P1;
    R < 0 or G03 flips the side (both flip: back to the right).
    """
    dx = x1 - x0
    dy = y1 - y0
    if dx == 0.0 and dy == 0.0:
        raise ArcError("R-form arc with start point = end point (use I/J/K for a full circle)")
    abs_r = abs(radius)
    if abs_r == 0.0:
        raise ArcError("zero-radius arc (R0)")
    chord = math.hypot(dx, dy)
    half = 0.5 * chord
    if half - abs_r > R_TOLERANCE_MM:
        raise ArcError(f"arc radius {abs_r:.3f} mm too small to reach end point (half chord {half:.3f} mm)")
    if half / abs_r > 1.0 - _TINY:
        offset = 0.0  # snapped to an exact half circle (LinuxCNC: within tolerance)
    else:
        offset = math.sqrt((abs_r - half) * (abs_r + half))
    mx = x0 + 0.5 * dx
    my = y0 + 0.5 * dy
    if clockwise == (radius > 0.0):  # right of the chord: normal (dy, -dx)
        return mx + offset * dy / chord, my - offset * dx / chord
    return mx - offset * dy / chord, my + offset * dx / chord


def check_center_radii(
    x0: float, y0: float, x1: float, y1: float, cx: float, cy: float, inch: bool, letters: tuple[str, str]
) -> tuple[float, float]:
    """Start and end radius of a centre-form arc; raises ArcError outside LinuxCNC's tolerance.

    Coordinates in mm; the tolerances are applied in program units like LinuxCNC does, and
    the message reports program units (in for G20).
    """
    r0 = math.hypot(x0 - cx, y0 - cy)
    r1 = math.hypot(x1 - cx, y1 - cy)
    if r0 < R_TOLERANCE_MM or r1 < R_TOLERANCE_MM:
        raise ArcError(f"zero-radius arc (radius to start {r0:.4f} mm, to end {r1:.4f} mm)")
    scale = MM_PER_INCH if inch else 1.0
    abs_tol = (SPIRAL_ABS_TOLERANCE_INCH if inch else SPIRAL_ABS_TOLERANCE_MM) * scale
    abs_err = abs(r0 - r1)
    rel_err = abs_err / max(r0, r1)
    if abs_err > 100.0 * abs_tol or (rel_err > SPIRAL_REL_TOLERANCE and abs_err > abs_tol):
        a, b = letters
        u = "in" if inch else "mm"  # reported in program units, like LinuxCNC
        k = 1.0 / scale
        raise ArcError(
            "radius to end of arc differs from radius to start: "
            f"start=({a}{x0 * k:.4f},{b}{y0 * k:.4f}) center=({a}{cx * k:.4f},{b}{cy * k:.4f}) "
            f"end=({a}{x1 * k:.4f},{b}{y1 * k:.4f}) r1={r0 * k:.4f} {u} r2={r1 * k:.4f} {u} "
            f"abs_err={abs_err * k:.4g} {u} rel_err={100.0 * rel_err:.4f}%"
        )
    return r0, r1


def sweep_angle(
    x0: float, y0: float, x1: float, y1: float, cx: float, cy: float, clockwise: bool, turns: int
) -> tuple[float, float]:
    """(start angle, signed sweep) in rad: principal angle in (0, 2 pi] plus 2 pi (turns - 1).

    start = end gives a full circle (LinuxCNC's rule for the centre form); "equal" here means
    within FULL_CIRCLE_MM, the interpreter's zero-length threshold, so that a rounding-size
    chord never becomes an arc of a few nanometres.
    """
    a0 = math.atan2(y0 - cy, x0 - cx)
    if abs(x1 - x0) <= FULL_CIRCLE_MM and abs(y1 - y0) <= FULL_CIRCLE_MM:
        d = TWO_PI
    else:
        # Angle between the two radius vectors, from cross and dot (accurate at any size).
        ux, uy = x0 - cx, y0 - cy
        vx, vy = x1 - cx, y1 - cy
        d = math.atan2(ux * vy - uy * vx, ux * vx + uy * vy)  # (-pi, pi], + counter-clockwise
        if clockwise:
            d = -d
        if d <= 0.0:
            d += TWO_PI
    d += TWO_PI * (turns - 1)
    return a0, (-d if clockwise else d)


# --------------------------------------------------------------------------- the paper

class PaperSingular(ArcError):
    """A case where the paper's printed formulas divide by zero (see paper_center_and_angles)."""


def paper_center_and_angles(
    x0: float, y0: float, x1: float, y1: float, r: float, g: int
) -> tuple[float, float, float, float]:
    """The paper's centre and angle selection (section 2.1, Eq. 1-9 and Table 1), R > 0 only.

    Returns (xc, yc, theta0_deg, theta_deg) in the paper's parametrisation:
    Eq. 12 (G02): x = -R cos(a) + xc, y = R sin(a) + yc;  Eq. 13 (G03): x = R cos(a) + xc,
    y = R sin(a) + yc; a from theta0 to theta0 + theta (degrees).

    Printing errors corrected (METHOD.md section 2): Eq. 1 has a stray minus sign; Eq. 6 is
    gamma = x0^2 + y0^2 - x1^2 - y1^2; Eq. 10-11 are replaced by theta = 2 asin(rho / 2R).
    Eq. 8's branch condition is printed as (x0 > xc) but with Eq. 12 it must be (x0 < xc)
    (otherwise a start point right of the centre maps to the left): corrected here.
    Fig. 3 (the state diagram that picks the centre) is not in the text; per Table 1
    region the centre on the right of the chord (G02) / left (G03) is taken, which is
    the rule METHOD.md states. Between the two centres of Eq. 1-2, c1 has the smaller x.

    Singular cases (raise PaperSingular): y0 == y1 (Eq. 4-5 divide by y0 - y1); x0 == xc
    (Eq. 8-9 divide by x0 - xc); start == end (rho = 0 in Eq. 1-2); no Table 1 region.
    Not covered by the paper: R < 0 (arcs over 180 degrees) and turns.
    """
    if r <= 0.0:
        raise PaperSingular("the paper's method covers R > 0 only (arcs up to 180 degrees)")
    rho = math.sqrt(x0 * x0 - 2 * x0 * x1 + x1 * x1 + y0 * y0 - 2 * y0 * y1 + y1 * y1)
    if rho == 0.0:
        raise PaperSingular("start = end: rho = 0 in Eq. 1-2")
    if y0 == y1:
        raise PaperSingular("chord parallel to the first axis: Eq. 4-5 divide by y0 - y1 = 0")
    phi_sq = 4 * r * r - x0 * x0 + 2 * x0 * x1 - x1 * x1 - y0 * y0 + 2 * y0 * y1 - y1 * y1  # Eq. 3
    phi = math.sqrt(max(phi_sq, 0.0))
    xc1 = ((x0 + x1) * rho - abs(y0 - y1) * phi) / (2 * rho)  # Eq. 1 (stray minus removed)
    xc2 = ((x0 + x1) * rho + abs(y0 - y1) * phi) / (2 * rho)  # Eq. 2
    gamma = x0 * x0 + y0 * y0 - x1 * x1 - y1 * y1  # Eq. 6 (corrected)
    yc1 = -(2 * (x0 - x1) * xc1 - gamma) / (2 * (y0 - y1))  # Eq. 4
    yc2 = -(2 * (x0 - x1) * xc2 - gamma) / (2 * (y0 - y1))  # Eq. 5

    # Table 1: regions by the end point relative to the start point.
    if g == 2:
        if x1 > x0 and y1 >= y0:
            region = 1
        elif x1 >= x0 and y0 > y1:
            region = 2
        elif x0 > x1 and y0 >= y1:
            region = 3
        elif x0 >= x1 and y1 > y0:
            region = 4
        else:
            raise PaperSingular("no Table 1 region")
        # Right of the chord: regions 1 and 4 move up (centre has the larger x), 2 and 3 down.
        xc, yc = (xc2, yc2) if region in (1, 4) else (xc1, yc1)
    elif g == 3:
        if x1 < x0 and y1 >= y0:
            region = 1
        elif x1 <= x0 and y0 > y1:
            region = 2
        elif x0 < x1 and y0 >= y1:
            region = 3
        elif x0 <= x1 and y1 > y0:
            region = 4
        else:
            raise PaperSingular("no Table 1 region")
        # Left of the chord: regions 1 and 4 move up (centre has the smaller x), 2 and 3 down.
        xc, yc = (xc1, yc1) if region in (1, 4) else (xc2, yc2)
    else:
        raise ValueError("g must be 2 or 3")

    if x0 == xc:
        raise PaperSingular("start point straight above/below the centre: Eq. 8-9 divide by x0 - xc = 0")
    if g == 2:  # Eq. 8 (condition corrected to x0 < xc)
        t = math.degrees(math.atan(-(y0 - yc) / (x0 - xc)))
        theta0 = t if x0 < xc else 180.0 + t
    else:  # Eq. 9
        t = math.degrees(math.atan((y0 - yc) / (x0 - xc)))
        theta0 = t if x0 > xc else 180.0 + t
    theta = math.degrees(2.0 * math.asin(min(1.0, rho / (2.0 * r))))  # replaces Eq. 10-11
    return xc, yc, theta0, theta
