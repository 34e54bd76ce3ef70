"""The planner holds every limit on the geometry real programs have, at any scale.

Windows of moves from the CAM programs in ../shared/gcode/cam (their exact lines and arcs,
written back as absolute G-code), scaled by 0.001, 1 or 1000, with moves left out (new
corners) and end points nudged (near-tangent joints), are planned and checked on the samples
and in closed form (``check_program``): velocity, acceleration and jerk along the path and on
every axis, exact end points, the path kept."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from planner.core.errors import ProgramError
from planner.core.program import MoveKind, Program
from planner.gcode.interpreter import parse_file, parse_program
from planner.geometry.arcs import SPIRAL_ABS_TOLERANCE_MM
from planner.motion.blending import blend_program
from planner.motion.lookahead import LimitSet
from planner.motion.plan import plan_program
from tests.planner.motion_programs import paper_machine
from tests.planner.test_blend import blend_axis_derivatives
from tests.planner.test_motion_invariants import check_program

CAM = Path(__file__).resolve().parents[3] / "shared" / "gcode" / "cam"
pytestmark = pytest.mark.skipif(not CAM.is_dir(), reason=f"shared CAM programs not found at {CAM}")

_PLANE_G = {"XY": "G17", "ZX": "G18", "YZ": "G19"}
_CENTRE = {"X": "I", "Y": "J", "Z": "K"}


def _programs() -> list[Program]:
    out = []
    if not CAM.is_dir():
        return out
    for path in sorted(CAM.glob("*/*")):
        if path.suffix in (".jsonl", ".tsv"):
            continue
        try:
            program = parse_file(path, machine=paper_machine())
        except ProgramError:
            continue                     # LinuxCNC refuses these too (see test_interp_reference)
        if len(program.moves) >= 8:
            out.append(program)
    return out


PROGRAMS = _programs()


def window_text(program: Program, first: int, count: int, scale: float, skip: set[int],
                nudge: float) -> str:
    """Moves first .. first + count - 1 as absolute G-code (machine coordinates) times
    ``scale``, without the moves in ``skip``; lines end ``nudge`` (relative) off their end."""
    moves = program.moves[first:first + count]
    axes = program.axes
    start = moves[0].start * scale
    out = ["G21 G90 G91.1 G64 " + " ".join(f"G0 {a}{v:.9f}" if i == 0 else f"{a}{v:.9f}"
                                              for i, (a, v) in enumerate(zip(axes, start)))]
    dropped = set(skip)
    for k, m in enumerate(moves):
        if k in dropped:
            continue
        end = m.end * scale
        words = []
        if m.arc is None:
            if nudge and k % 2:       # an arc after it starts off its circle: a spiral
                end = end + nudge * scale * (1.0 + k % 3)
            code = "G0" if m.kind is MoveKind.RAPID else "G1"
            words = [code] + [f"{a}{v:.9f}" for a, v in zip(axes, end)]
        else:
            arc = m.arc
            if k - 1 in dropped:
                dropped.add(k)             # an arc needs its own start point
                continue
            first_l, second_l = axes[arc.first_axis], axes[arc.second_axis]
            ci = arc.center[0] * scale - m.start[arc.first_axis] * scale
            cj = arc.center[1] * scale - m.start[arc.second_axis] * scale
            code = "G3" if arc.sweep_rad > 0 else "G2"
            words = [_PLANE_G[arc.plane], code] + [f"{a}{v:.9f}" for a, v in zip(axes, end)]
            words += [f"{_CENTRE[first_l]}{ci:.9f}", f"{_CENTRE[second_l]}{cj:.9f}"]
            if arc.turns > 1:
                words.append(f"P{arc.turns}")
        if m.kind is not MoveKind.RAPID:
            words.append(f"F{min(m.feed_mm_s * 60.0, 1e6):.4f}")
        out.append(" ".join(words))
    return "\n".join(out) + "\nM2\n"


@pytest.mark.skipif(not PROGRAMS, reason="no plannable CAM program in ../shared/gcode/cam")
@settings(max_examples=40, deadline=None)
@given(data=st.data(), scale=st.sampled_from([0.001, 1.0, 1000.0]),
       nudge=st.sampled_from([0.0, 1e-9, 1e-6]))
def test_windows_of_real_programs_hold_every_limit(data, scale: float, nudge: float) -> None:
    program = data.draw(st.sampled_from(PROGRAMS))
    count = data.draw(st.integers(4, min(24, len(program.moves))))
    first = data.draw(st.integers(0, len(program.moves) - count))
    skip = set(data.draw(st.lists(st.integers(1, count - 1), max_size=3)))
    text = window_text(program, first, count, scale, skip, nudge)
    try:
        parse_program(text, machine=paper_machine())
    except ProgramError:
        assume(False)              # a spiral beyond the centre tolerance once scaled: not a program
    m = paper_machine()
    plan = plan_program(parse_program(text, machine=m), m)
    assume(plan.cycle_time_s < 120.0)   # the sample check costs time in proportion
    check_program(text, m)


def test_the_window_writer_keeps_the_geometry() -> None:
    """The window of a whole program, unscaled, is the program's own path."""
    if not PROGRAMS:
        pytest.skip("no plannable CAM program in ../shared/gcode/cam")
    program = max(PROGRAMS, key=lambda p: sum(m.arc is not None for m in p.moves))
    n = min(len(program.moves), 60)
    again = parse_program(window_text(program, 0, n, 1.0, set(), 0.0), machine=paper_machine())
    assert any(m.arc is not None for m in again.moves)
    ours = [m for m in again.moves]
    theirs = [m for m in program.moves[:n]]
    assert len(ours) == len(theirs)
    for a, b in zip(ours, theirs):
        assert math.dist(a.end, b.end) < 1e-6 and (a.arc is None) == (b.arc is None)


def test_degenerate_spiral_keeps_the_path() -> None:
    """Found by the window fuzz above (ugs_misc/spiral.gcode, a line end nudged by 2 nm): a
    helix whose start is 2 nm off its full circle is a spiral of 1e-10 rad (as LinuxCNC reads
    it). Its samples are within 4e-15 mm of its chord; the contour measure placed them along
    the arc by their angle, whose rounding over that sweep is 44 nm of the 20 mm rise."""
    check_program("G21 G90 G91.1 G64 G0 X0 Y0 Z20\nG17 G3 X0 Y0 Z20 I20 J0 F900\n"
                  "G1 X0.000000002 Y0.000000002 Z0.000000002\nG2 X0 Y0 Z-20 I-20 J0\nM2\n")


def test_spiral_with_a_large_radius_change_holds_the_jerk_limit() -> None:
    """Found by the window fuzz above (linuxcnc_tp/Pasta.ngc at scale 0.001, a move left out
    before an arc, so the arc starts off its circle): a spiral from 2.8 to about 10 um, within
    LinuxCNC's absolute centre tolerance. The jerk of its changing curvature (v^3 dkappa/ds)
    reached 1.06 Jmax on Y until the arc limits counted it."""
    check_program("G21 G90 G91.1 G64 G0 X-0.060020 Y-0.019354 Z0.020000\n"
                  "G0 X-0.028766 Y-0.024899 Z0.020000\nG1 X-0.028766 Y-0.024899 Z-0.001949 F400\n"
                  "G17 G2 X-0.025958 Y-0.035312 Z-0.001949 I-0.002795475 J-0.000092343 F1200\nM2\n")


def test_spiral_limits_come_from_its_small_end() -> None:
    """Found by the window fuzz (camotics/heart.ngc at scale 0.001): the last arc starts off
    its circle (a spiral from 6.4 um to a smaller radius); its limits from the larger radius let
    the axis jerk reach 1.045 Jmax."""
    check_program("G21 G90 G91.1 G64 G0 X-0.001531938 Y0.002986674 Z-0.001\n"
                  "G17 G3 X-0.002729305 Y0.002490708 Z-0.001 I0 J-0.001693332 F70\n"
                  "G17 G3 X-0.003225271 Y0.001293340 Z-0.001 I0.001197368 J-0.001197367 F70\n"
                  "G17 G3 X-0.002873604 Y0.000075133 Z-0.001 I0.002285827 J0 F70\n"
                  "G17 G2 X0.001089662 Y-0.001731848 Z-0.001 I0.005317665 J-0.003517210 F70\nM2\n")


@settings(max_examples=40, deadline=None)
@given(r0=st.floats(0.002, 50.0), grow=st.floats(-0.95, 0.95), sweep=st.floats(0.2, 6.0),
       rise=st.floats(-2.0, 2.0), ccw=st.booleans(), feed=st.sampled_from([60.0, 600.0, 3000.0]))
def test_spirals_of_any_radius_change_hold_every_limit(r0: float, grow: float, sweep: float, rise: float,
                                                       ccw: bool, feed: float) -> None:
    """A centre-form arc whose end radius differs from its start radius by up to LinuxCNC's
    absolute tolerance (0.028 mm: most of a small arc's radius, a rounding on a large one),
    between two lines, from micrometre to 50 mm radii."""
    r1 = max(r0 + grow * SPIRAL_ABS_TOLERANCE_MM, 0.001)
    sign = 1.0 if ccw else -1.0
    x1, y1 = r1 * math.cos(sign * sweep), r1 * math.sin(sign * sweep)
    text = (f"G21 G90 G17 G0 X{r0:.9f} Y{-5 * r0:.9f} Z0\nG1 Y0 F{feed}\n"
            f"G{3 if ccw else 2} X{x1:.9f} Y{y1:.9f} Z{rise * r0:.9f} I{-r0:.9f} J0\n"
            f"G1 X{x1 + 5 * r0:.9f}\nM2\n")
    try:
        program = parse_program(text, machine=paper_machine())
    except ProgramError:
        assume(False)                 # just beyond LinuxCNC's centre tolerance
    assume(any(m.arc is not None and m.arc.radius_start_mm != m.arc.radius_end_mm for m in program.moves))
    m = paper_machine()
    assume(plan_program(program, m).cycle_time_s < 120.0)
    check_program(text, m)


@pytest.mark.skipif(not PROGRAMS, reason="no plannable CAM program in ../shared/gcode/cam")
@settings(max_examples=30, deadline=None)
@given(data=st.data(), scale=st.sampled_from([0.001, 1.0, 1000.0]), tol=st.sampled_from([0.001, 0.01, 0.1]),
       every=st.booleans())
def test_blended_windows_of_real_programs_hold_every_limit(data, scale: float, tol: float,
                                                           every: bool) -> None:
    """The same windows under G64 P (Q = P: lines joined too), every corner blended or only the
    quicker ones: no limit exceeded on the samples, exact end, and every axis' velocity,
    acceleration and jerk on the blends in closed form within its limit."""
    program = data.draw(st.sampled_from(PROGRAMS))
    count = data.draw(st.integers(4, min(24, len(program.moves))))
    first = data.draw(st.integers(0, len(program.moves) - count))
    text = window_text(program, first, count, scale, set(), 0.0)
    text = text.replace("G64 ", f"G64 P{tol * scale:.9f} ", 1)
    m = paper_machine()
    try:
        parsed = parse_program(text, machine=m)
    except ProgramError:
        assume(False)              # an arc too small once scaled: not a program
    blended = blend_program(parsed, m, only_where_quicker=not every)
    plan = plan_program(blended, m)
    assume(plan.cycle_time_s < 120.0)
    rep = plan.limit_report()
    assert rep.violations == {}, rep.violations
    assert rep.joint_jerk["count"] == 0, rep.joint_jerk      # no velocity step at any joint
    assert rep.end_error_mm == 0.0 and not rep.nan and rep.time_increasing
    if any(mv.blend is not None for mv in blended.moves):
        qv, qa, qj = blend_axis_derivatives(plan)
        lim = LimitSet.from_machine(m)
        assert np.all(np.abs(qv) <= lim.v_axis * (1 + 1e-9))
        assert np.all(np.abs(qa) <= lim.a_axis * (1 + 1e-9))
        assert np.all(np.abs(qj) <= lim.j_axis * (1 + 1e-6))


WHOLE = [p for p in sorted(CAM.glob("*/*")) if p.suffix.lower() in (".nc", ".ngc", ".gcode", ".tap")
         and "heart" not in p.name] if CAM.is_dir() else []


@pytest.mark.parametrize("path", WHOLE, ids=[p.name for p in WHOLE])
def test_whole_shared_programs_hold_every_limit_across_joints(path: Path) -> None:
    """Each shared CAM program in G64 P0.01 at 100 mm/s, 1000 mm/s^2 and 10,000 mm/s^3 (the
    LinuxCNC comparison's machine): every limit on the samples, the stencils across joints
    included, and no joint crossed with a velocity step (heart.ngc, 17 minutes of arcs, is
    left to ``bench.bench_linuxcnc``)."""
    from bench.bench_blend import bench_machine, with_mode

    machine = bench_machine(10_000.0)
    try:
        program = parse_program(with_mode(path.read_text(errors="replace"), "G64 P0.01"), path.name, machine)
    except ProgramError:
        pytest.skip(f"{path.name} is refused at a line, as LinuxCNC refuses it")
    plan = plan_program(blend_program(program, machine), machine)
    rep = plan.limit_report()
    assert rep.ok, rep.violations
    assert rep.joint_jerk["count"] == 0, rep.joint_jerk
    assert rep.corner_steps["count"] == 0
    assert max(v["j_joint"] for v in rep.axes.values()) <= 10_000.0 * (1 + 1e-4)


def test_the_linuxcnc_bench_runs_a_program_given_beside_the_shared_ones(tmp_path, capsys) -> None:
    """``bench.bench_linuxcnc --program FILE`` plans a program from elsewhere (LinuxCNC's own
    test programs, say) as it plans the shared ones; a missing file is named, nothing run."""
    from bench import bench_linuxcnc

    prog = tmp_path / "raster_step.ngc"
    prog.write_text("G21 G90\nG0 X20 Y10\nG1 F6000 X0\nY9\nX20\nM2\n")
    assert bench_linuxcnc.main(["--skip-linuxcnc", "--program", str(prog), "--only", "raster_step"]) == 0
    rows = json.loads(capsys.readouterr().out.strip().splitlines()[-1])["rows"]
    assert [r["program"] for r in rows] == [f"{tmp_path.name}/raster_step.ngc"]
    # a 22 mm rapid, 41 mm of feed at 100 mm/s round two right angles within 0.01 mm: 0.99 s
    assert 0.8 < rows[0]["ours J1e+06 time_s"] < 1.2 and rows[0]["ours J1e+06 ok"] is True
    assert bench_linuxcnc.main(["--skip-linuxcnc", "--program", str(tmp_path / "none.ngc")]) == 1
    assert "no such program" in capsys.readouterr().out


def test_the_linuxcnc_bench_measures_path_acceleration_on_samples() -> None:
    """A diagonal in XY at 1000 mm/s^2 on each axis is 1414 mm/s^2 on the path: 1.414x, every
    accelerating sample counted; along X alone 1.0x and none over."""
    from bench.bench_linuxcnc import path_accel_ratio

    t = np.arange(0.0, 0.1, 1e-3)
    s = 0.5 * 1000.0 * t * t                               # mm, each axis at 1000 mm/s^2
    diagonal = np.column_stack([s, s, np.zeros_like(s)])
    ratio, over = path_accel_ratio(diagonal, 1000.0)
    assert ratio == pytest.approx(math.sqrt(2.0), rel=1e-6) and over == len(t) - 2
    along_x = np.column_stack([s, np.zeros_like(s), np.zeros_like(s)])
    assert path_accel_ratio(along_x, 1000.0) == (pytest.approx(1.0, rel=1e-6), 0)


def test_the_linuxcnc_bench_takes_the_path_acceleration_from_the_axes(tmp_path, capsys) -> None:
    """A 20 mm diagonal rapid in XY at 1000 mm/s^2 per axis and path: 0.383 s with the path held
    at 1000 mm/s^2 (ours); 0.354 s at the 1414 mm/s^2 the two axes allow together, which is
    what LinuxCNC 2.9 runs (the bench's axis rule); every sample within every axis' limits."""
    from bench import bench_linuxcnc

    prog = tmp_path / "diagonal.ngc"
    prog.write_text("G21 G90\nG0 X20 Y20\nM2\n")
    assert bench_linuxcnc.main(["--skip-linuxcnc", "--program", str(prog), "--only", "diagonal"]) == 0
    row = json.loads(capsys.readouterr().out.strip().splitlines()[-1])["rows"][0]
    length = 20.0 * math.sqrt(2.0)
    assert row["ours J1e+06 time_s"] == pytest.approx(length / 100.0 + 100.0 / 1000.0, abs=3e-3)
    assert row["ours J1e+06 axis rule time_s"] == pytest.approx(length / 100.0 + 100.0 / 1414.2, abs=3e-3)
    assert row["ours J1e+06 axis rule ok"] is True


def test_the_blend_bench_times_each_pass_on_a_program_repeated(capsys) -> None:
    """``bench.bench_blend --passes NAME --repeat N``: the program's moves N times over, and the
    seconds of each pass of the blending (``blend_program``'s own account); a name that is no
    shared program is said so."""
    from bench import bench_blend

    assert bench_blend.main(["--passes", "51MeanderAve", "--repeat", "2"]) == 0
    row = json.loads(capsys.readouterr().out.strip().splitlines()[-1])
    text = bench_blend.with_mode(next(CAM.rglob("51MeanderAve.ngc")).read_text(errors="replace"), "G64 P0.01")
    once = parse_program(text, "once", bench_blend.bench_machine(10_000.0))
    # twice over (where the copies meet, a move that goes nowhere is not one)
    assert 2 * len(once.moves) - 4 <= row["moves"] <= 2 * len(once.moves)
    assert row["moves_after"] > row["moves"]                # the joints of its arcs eased
    assert row["arc_joints_s"] > 0.0 and all(row[f"{name}_s"] >= 0.0 for name in ("parse", "merge", "fillets",
                                                                                 "corners"))
    assert bench_blend.main(["--passes", "no_such_program"]) == 1
    assert "no shared CAM program" in capsys.readouterr().out
