"""Cutter radius compensation (G41, G42, G41.1, G42.1, G40) as LinuxCNC 2.9 computes it:
LinuxCNC's own compensation tests (tests/data/linuxcnc_interp, its canonical output) call by
call, its refusals, and properties of the offset path (never nearer the programmed path than
the tool radius, touching it at every programmed end) at scales 0.001 to 1000."""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from planner.core.errors import ProgramError
from planner.core.program import MoveKind, Program
from planner.core.tools import ToolTable, parse_tbl, read_tbl
from planner.gcode.canon import canon_records
from planner.gcode.interpreter import parse_program
from planner.motion.plan import plan_program
from tests.planner.motion_programs import paper_machine
from tools.linuxcnc_oracle import canon_calls, project_motion

DATA = Path(__file__).resolve().parents[1] / "data" / "linuxcnc_interp"


def linuxcnc_motion(expected: Path) -> list[tuple]:
    """LinuxCNC's traverses, feeds and arcs (end, centre, turn, normal end) in mm, without the
    zero-length moves it writes (a Program has none)."""
    out: list[tuple] = []
    last: tuple | None = (0.0, 0.0, 0.0)
    for name, args, scale in canon_calls(expected.read_text()):
        if name in ("STRAIGHT_TRAVERSE", "STRAIGHT_FEED"):
            end = tuple(float(v) * scale for v in args[:3])
            if end != last:
                out.append((name.lower(), end))
            last = end
        elif name == "ARC_FEED":
            v = [float(a) for a in args[:6]]
            out.append(("arc_feed", (v[0] * scale, v[1] * scale, v[2] * scale, v[3] * scale, v[4],
                                     v[5] * scale)))
            last = (v[0] * scale, v[1] * scale, v[5] * scale)
    return out


def table_in_program_units(path: Path, program: str) -> ToolTable:
    """LinuxCNC's stand-alone interpreter (which made `expected`) reads the table in the
    program's units: these inch tests have a 1.0 inch tool as D1.0."""
    table = read_tbl(path)
    k = 25.4 if "g20" in program.lower() else 1.0
    return ToolTable({t.number: replace(t, diameter_mm=t.diameter_mm * k,
                                        offsets_mm=tuple((a, v * k) for a, v in t.offsets_mm))
                      for t in table})


REFERENCES = [
    (DATA / "ccomp" / name / "test.ngc", DATA / "ccomp" / name / "expected",
     DATA / "ccomp" / name / "test.tbl")
    for name in ("mill-g90g91g92", "mill-line-arc-entry", "mill-zchanges")
] + [(DATA / "inverse-time-with-comp" / "inverse.ngc", DATA / "inverse-time-with-comp" / "expected", None)]


@pytest.mark.parametrize("ngc,expected,tbl", REFERENCES, ids=[r[0].parent.name for r in REFERENCES])
def test_linuxcnc_compensation_tests_read_call_by_call(ngc: Path, expected: Path, tbl: Path | None) -> None:
    text = ngc.read_text()
    tools = table_in_program_units(tbl, text) if tbl else None
    want = linuxcnc_motion(expected)
    got = project_motion(parse_program(text, name=ngc.name, tools=tools))
    assert [c[0] for c in got] == [c[0] for c in want]
    # LinuxCNC prints 4 decimals of an inch (0.00254 mm)
    for g, w in zip(got, want):
        np.testing.assert_allclose(g[1], w[1], atol=0.0026, err_msg=f"{g} != {w}")


def test_reference_data_is_present() -> None:
    assert all(p.exists() for ref in REFERENCES for p in ref if p is not None)
    assert len(linuxcnc_motion(REFERENCES[1][1])) == 20


@pytest.mark.parametrize("name,line,words", [
    ("ccomp-arcexit.ngc", 7, "must be a straight line, not an arc"),
    ("ccomp-gouging.ngc", 7,
     "straight feed in a concave corner cannot be reached by the tool without gouging"),
])
def test_linuxcnc_bad_compensation_programs_are_refused_where_linuxcnc_refuses(name: str, line: int,
                                                                              words: str) -> None:
    path = DATA / "bad" / name
    with pytest.raises(ProgramError) as ei:
        parse_program(path.read_text(), name=name)
    (err,) = ei.value.errors
    assert (err.line, err.col) == (line, 1) and words in err.message
    # LinuxCNC's own file names the error in its first line
    assert path.read_text().splitlines()[0].lstrip(";").lower().split()[0] in err.message.lower()


# ------------------------------------------------------------------ the rules around it
TOOLS = parse_tbl("T1 P1 Z10 D10 ;10 mm end mill\nT2 P2 Z20 D4\n")
ON = "G21 G17 G90 F600 T1 M6 G43\nG0 X-20 Y-20 Z5\nG41 G1 X0 Y0\n"


@pytest.mark.parametrize("tail,col,words", [
    ("G43 H2\n", 1, "cannot change the tool length offset with cutter compensation on (G41)"),
    ("G49\n", 1, "cannot change the tool length offset"),
    ("G55\n", 1, "cannot change the coordinate system"),
    ("G61\n", 1, "cannot change the path control mode"),
    ("G64 P0.01\n", 1, "cannot change the path control mode"),
    ("G98\n", 1, "cannot change the canned cycle retract mode"),
    ("G92 X0\n", 1, "cannot change the axis offsets (G52, G92)"),
    ("G52 X1\n", 1, "cannot change the axis offsets"),
    ("G92.1\n", 1, "cannot change the axis offsets"),
    ("G28\n", 1, "cannot use G28"),
    ("G30.1\n", 1, "cannot store the G28/G30 position"),
    ("T2 M6\n", 4, "cannot change tools"),
    ("G18\n", 1, "cannot change the plane"),
    ("G53 G0 X0\n", 1, "cannot use G53 with cutter compensation on"),
    ("G81 X1 Y1 Z-1 R1\n", 1, "cannot use canned cycles with cutter compensation on"),
    ("G42 X10\n", 1, "cannot turn cutter compensation on with G42 while it is on (G41)"),
    ("G10 L2 P0 X1\n", 1, "with cutter compensation on"),
])
def test_what_linuxcnc_refuses_while_compensation_is_on(tail: str, col: int, words: str) -> None:
    with pytest.raises(ProgramError) as ei:
        parse_program(ON + tail, tools=TOOLS)
    (err,) = ei.value.errors
    assert (err.line, err.col) == (4, col) and words in err.message, err


def test_the_same_codes_are_accepted_once_compensation_is_off() -> None:
    ok = ON + "G1 X50\nG40 G1 X60 Y-10\nG43 H2\nG55\nG61\nG98\nG92 X0\nG92.1\nG18\nG17\nT2 M6\n"
    assert parse_program(ok, tools=TOOLS).moves


@pytest.mark.parametrize("text,line,col,words", [
    ("G21 F600\nG19 G41.1 D2\n", 2, 5,
     "cutter compensation works in the XY (G17) or XZ (G18) plane, not in G19"),
    ("G21 F600\nG41.1\n", 2, 1, "G41.1 needs a D word"),
    ("G21 F600\nG41 D1.5\n", 2, 5, "D to be a tool number"),
    ("G21 F600\nG41 D9 G1 X10\n", 2, 5, "tool T9 is not in the tool table"),
    ("G21 F600\nG42.1 D4 L3 G1 X10\n", 2, 10, "lathe tool orientations are not supported"),
    ("G21 F600\nG10 L2 P1 R30\nG18 G41.1 D2\n", 3, 5,
     "cutter compensation in G18 with the XY plane rotated (G10 L2 R) is not supported"),
    ("G21 F600\nG41.1 D20 G1 X5\n", 2, 1,
     "entry move (5.0000 mm in the plane) is not longer than the tool radius"),
    ("G21 F600\nG41.1 D20 G1 Z-1\n", 2, 1, "entry move (0.0000 mm in the plane)"),
    ("G21 F600\nG41.1 D2 G1 X10\nG3 X11 R0.6\n", 3, 1,
     "tool radius (1.0000 mm) not less than the arc radius"),
    ("G21 F600\nG41.1 D2 G3 X10 R0.5\n", 2, 17, "tool radius (1.0000 mm) not less than the arc radius"),
    ("G21 F600\nG41.1 D2 G1 X10\nG40\nG2 X20 I5\n", 4, 1, "must be a straight line, not an arc"),
    # a slot narrower than the tool: the sides are shorter than the cut-back
    ("G21 F600\nG41.1 D10 G1 X20\nY1\nX0\n", 4, 1, "cannot be reached by the tool without gouging"),
])
def test_compensation_refusals_name_line_column_and_reason(text: str, line: int, col: int,
                                                           words: str) -> None:
    with pytest.raises(ProgramError) as ei:
        parse_program(text, tools=TOOLS)
    err = ei.value.errors[0]
    assert (err.line, err.col) == (line, col) and words in err.message, err


def test_negative_diameter_swaps_the_side_and_d_is_a_diameter() -> None:
    left = parse_program("G21 F600\nG41.1 D-4 G1 X10\nG40 X20\n")
    right = parse_program("G21 F600\nG42.1 D4 G1 X10\nG40 X20\n")
    assert [m.end.tolist() for m in left.moves] == [m.end.tolist() for m in right.moves]
    assert right.moves[0].end[1] == pytest.approx(-2.0)


def test_exit_move_goes_from_the_offset_point_to_the_programmed_point_in_g91_too() -> None:
    prog = parse_program("G21 F600\nG41.1 D4 G1 X10\nG91 G40 X5\n")
    assert prog.moves[0].end.tolist() == pytest.approx([10.0, 2.0, 0.0])
    assert prog.moves[1].end.tolist() == pytest.approx([15.0, 0.0, 0.0])   # counted from X10 Y0


def test_a_z_move_while_compensating_keeps_the_tool_where_it_is() -> None:
    prog = parse_program("G21 F600\nG41.1 D4 G1 X10\nZ-2\nY10\nG40 X0\n")
    ends = [m.end.tolist() for m in prog.moves]
    assert ends[1] == pytest.approx([8.0, 2.0, -2.0])                 # cut back at the corner
    assert ends[0] == pytest.approx([8.0, 2.0, 0.0])


def test_offsets_move_the_compensated_path_as_a_whole() -> None:
    """The same profile in G54 with an offset and a rotation reads the same in program
    coordinates, and lands on the machine turned and shifted as the work offset says."""
    body = "G21 F600\nG41.1 D6 G1 X0 Y0\nX40\nG3 X40 Y20 R10\nG1 X0\nY0\nG40 X-10\n"
    plain = parse_program("G0 X-10 Y-10\n" + body)
    turned = parse_program("G10 L2 P1 X100 Y50 R30\nG54\nG0 X-10 Y-10\n" + body)
    assert len(plain.moves) == len(turned.moves) == 8
    assert np.allclose([r["args"][:3] for r in canon_records(plain)],
                       [r["args"][:3] for r in canon_records(turned)], atol=1e-9)
    c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
    for a, b in zip(plain.moves, turned.moves):
        x, y = a.end[0], a.end[1]
        assert b.end[:2].tolist() == pytest.approx([100 + c * x - s * y, 50 + s * x + c * y])


def test_m0_makes_the_queued_move_final_as_linuxcnc_does() -> None:
    prog = parse_program("G21 F600\nG41.1 D4 G1 X10\nM0\nY10\nG40 X0\n")
    assert prog.moves[0].end.tolist() == pytest.approx([10.0, 2.0, 0.0])   # not cut back


def test_compensated_programs_plan_within_the_machine_limits() -> None:
    m = paper_machine()
    text = ("G21 G17 F1500\nG0 X-10 Y-10\nG41.1 D6 G1 X0 Y0\nX40\nG3 X40 Y20 R10\nG1 X20 Y10\nX0 Y20\n"
            "G2 X0 Y0 R10\nG40 G1 X-10 Y-10\nG42.1 D6 G1 X0 Y0\nG2 X0 Y0 I10\nG40 G1 X-10 Y-10\n")
    prog = parse_program(text, machine=m)
    plan = plan_program(prog, m, mode="lookahead")
    rep = plan.limit_report()
    assert rep.violations == {} and not rep.nan and rep.end_error_mm == 0.0


def test_fast_paths_give_the_same_reading_with_compensation() -> None:
    from planner.gcode import interpreter

    text = "G21 F600\nG0 X-5 Y-5\nG41.1 D2\nG1 X0 Y0\nX10\nY10\nG3 X0 Y10 R5\nG1 Y0\nG40 X-5\n"
    fast = parse_program(text)
    interpreter.Interpreter.use_fast = False
    try:
        slow = parse_program(text)
    finally:
        interpreter.Interpreter.use_fast = True
    assert [m.end.tolist() for m in fast.moves] == [m.end.tolist() for m in slow.moves]
    assert any(m.arc is not None and abs(m.arc.radius_start_mm - 1.0) < 1e-9 for m in fast.moves)


# ------------------------------------------------------------------ properties of the offset path
def _samples(program: Program, n: int = 24) -> np.ndarray:
    pts = []
    for m in program.moves:
        if m.kind is MoveKind.RAPID:
            continue
        if m.arc is None:
            t = np.linspace(0.0, 1.0, n)[:, None]
            pts.append(m.start[:2] + t * (m.end[:2] - m.start[:2]))
        else:
            a = m.arc
            ang = a.start_angle_rad + np.linspace(0.0, a.sweep_rad, n)
            rad = np.linspace(a.radius_start_mm, a.radius_end_mm, n)
            pts.append(np.column_stack([a.center[0] + rad * np.cos(ang), a.center[1] + rad * np.sin(ang)]))
    return np.vstack(pts)


def _distance_to_polygon(points: np.ndarray, corners: np.ndarray) -> np.ndarray:
    best = np.full(len(points), np.inf)
    for p, q in zip(corners, np.roll(corners, -1, axis=0)):
        d = q - p
        t = np.clip(((points - p) @ d) / (d @ d), 0.0, 1.0)
        best = np.minimum(best, np.linalg.norm(points - (p + t[:, None] * d), axis=1))
    return best


@st.composite
def convex_polygons(draw):
    """Corners on a circle of radius 1, gaps of 20-120 degrees: inner angles of 60 degrees and more."""
    gaps = []
    while sum(gaps) < 360.0 - 20.0:
        gaps.append(draw(st.floats(20.0, 120.0)))
    rest = 360.0 - sum(gaps[:-1])
    gaps = gaps[:-1] if rest > 120.0 else gaps[:-1] + [rest]
    if rest > 120.0:
        gaps += [rest / 2.0, rest / 2.0]
    start = draw(st.floats(0.0, 360.0))
    angles = np.radians(start + np.concatenate([[0.0], np.cumsum(gaps)[:-1]]))
    return np.column_stack([np.cos(angles), np.sin(angles)])


@settings(max_examples=60, deadline=None)
@given(convex_polygons(), st.sampled_from([0.001, 1.0, 1000.0]), st.floats(0.002, 0.03),
       st.sampled_from(["G41.1", "G42.1"]))
def test_offset_path_keeps_the_tool_radius_from_a_convex_profile(corners, scale, tool_ratio, code) -> None:
    """Counter-clockwise round a convex profile, G42 cuts outside (convex corners rounded by
    arcs) and G41 inside (concave corners cut back). Either way no point of the tool centre's
    path comes nearer the profile than the tool radius, and every programmed corner's
    neighbourhood is reached: the path's corners are a radius from the profile."""
    pts = corners * 50.0 * scale
    r = tool_ratio * 50.0 * scale
    lead = pts[0] + (pts[0] - pts[1]) * 0.5 + (pts[0] - pts[-1]) * 0.5   # outside, before corner 0
    text = [f"G21 G17 G90 F600\nG0 X{lead[0]:.9f} Y{lead[1]:.9f}",
            f"{code} D{2 * r:.9f} G1 X{pts[0][0]:.9f} Y{pts[0][1]:.9f}"]
    # round the profile and along its first side again, so that the corner at the start is cut
    # as a corner of the profile too
    text += [f"X{p[0]:.9f} Y{p[1]:.9f}" for p in list(pts[1:]) + [pts[0], pts[1]]]
    text.append(f"G40 X{lead[0]:.9f} Y{lead[1]:.9f}")
    prog = parse_program("\n".join(text) + "\n")
    n = len(pts)
    # the sides from corner 1 round to corner 0 (lines 5 ... 3 + n): both their corners are
    # the profile's (the first side's start follows the entry, the last pass's end the exit)
    cut = [m for m in prog.moves if 5 <= m.line <= 3 + n]
    assert len(cut) >= n - 1
    samples = _samples(replace(prog, moves=tuple(cut)))
    dist = _distance_to_polygon(samples, pts)
    tol = 1e-7 * 50.0 * scale
    assert dist.min() >= r - tol
    ends = np.array([m.end[:2] for m in cut])
    np.testing.assert_allclose(_distance_to_polygon(ends, pts), r, atol=tol)
    inside = code == "G41.1"
    centre = pts.mean(axis=0)
    # inside: every end is nearer the centre than the profile's corners; outside: farther
    radial = np.linalg.norm(ends - centre, axis=1)
    assert (radial < np.linalg.norm(pts - centre, axis=1).max()).all() if inside else \
        (radial > np.linalg.norm(pts - centre, axis=1).min()).all()


@pytest.mark.parametrize("scale", [0.001, 1.0, 1000.0])
def test_a_circle_is_cut_at_its_radius_plus_or_minus_the_tool_radius(scale: float) -> None:
    """A boss (G42 counter-clockwise, outside) is cut all round at R + r after the corner arc
    that rounds the entry. A pocket (G41, inside) at R - r: the perpendicular entry is cut back
    to where the tool touches the circle, so the circle ends where it began (LinuxCNC's reading)."""
    big, tool = 20.0 * scale, 6.0 * scale
    text = "G21 F600\nG0 X0 Y0\n{} D{:.9f} G1 X{:.9f}\nG3 I{:.9f}\nG40 G1 X0\n"
    boss = parse_program(text.format("G42.1", tool, big, -big))
    (arc,) = [m.arc for m in boss.moves if m.arc is not None and m.arc.center == (0.0, 0.0)]
    assert arc.radius_start_mm == pytest.approx(big + tool / 2.0, rel=1e-12)
    assert arc.radius_end_mm == arc.radius_start_mm
    assert arc.sweep_rad == pytest.approx(2 * math.pi)
    pocket = parse_program(text.format("G41.1", tool, big, -big))
    (arc,) = [m.arc for m in pocket.moves if m.arc is not None]
    assert arc.radius_start_mm == pytest.approx(big - tool / 2.0, rel=1e-12)
    assert 1.9 * math.pi < arc.sweep_rad < 2 * math.pi
    entry = pocket.moves[0]
    assert math.hypot(*entry.end[:2]) == pytest.approx(big - tool / 2.0, rel=1e-12)   # on the circle
    assert entry.end[1] == pytest.approx(tool / 2.0)                                    # beside its line


def test_lathe_tool_orientation_is_refused_not_ignored() -> None:
    table = parse_tbl("T2 P2 Z0 X0 D0.2 I85 J25 Q2\nT9 P9 Z0 X0 D0.2 Q9\n")
    with pytest.raises(ProgramError, match=r"lathe tool T2 .*\(orientation Q2\)"):
        parse_program("G21 G18 F600\nG41 D2 G1 Z10\n", tools=table)
    assert parse_program("G21 G18 F600\nG41 D9 G1 Z10\n", tools=table).moves   # Q9: the centre


def test_g18_compensation_is_g17_compensation_with_z_and_x_for_x_and_y() -> None:
    """In G18 the plane's first axis is Z and its second X (LinuxCNC's XZ plane): the same
    profile written with Z for X and X for Y is offset the same way."""
    g17 = ("G21 G17 F600\nG0 X-10 Y-10\nG41.1 D6 G1 X0 Y0\nX40\nG3 X40 Y20 R10\nG1 X20 Y10\n"
           "X0 Y20\nG2 X0 Y0 R10\nG40 G1 X-10 Y-10\n")
    swap = str.maketrans({"X": "Z", "Y": "X"})
    lines = g17.splitlines()
    g18 = "\n".join([lines[0].replace("G17", "G18")] + [ln.translate(swap) for ln in lines[1:]]) + "\n"
    a, b = parse_program(g17), parse_program(g18)
    assert len(a.moves) == len(b.moves) == 11          # with four corner arcs
    for m17, m18 in zip(a.moves, b.moves):
        assert m18.end[[2, 0]].tolist() == pytest.approx(m17.end[[0, 1]].tolist(), abs=1e-9)
        assert (m17.arc is None) == (m18.arc is None)
