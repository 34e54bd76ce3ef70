"""Canned cycles (G73, G74, G81-G86, G89, G98/G99, L, G80) read as LinuxCNC 2.9 reads them:
LinuxCNC's own interpreter tests (tests/data/linuxcnc_interp, its canonical output) call by
call, the cycles LinuxCNC's tests do not cover against its documented motions, and every
refusal with its line, column and reason."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from planner.core.errors import ProgramError
from planner.core.machine import AxisSpec, MachineSpec
from planner.core.program import Dwell, EventKind, Program, SpindleSpeed
from planner.gcode.canon import canon_records
from planner.gcode.interpreter import parse_program
from tools.linuxcnc_oracle import RS274, canon_calls

DATA = Path(__file__).resolve().parents[1] / "data" / "linuxcnc_interp"
REFERENCES = sorted(p.parent for p in DATA.glob("g8*/*/*/expected"))


def linuxcnc_calls(expected: Path) -> list[tuple]:
    """Motion, dwell and spindle direction from LinuxCNC's canonical output, in mm; a spindle
    stop followed by a start is one change of direction, as the project writes it."""
    out: list[tuple] = []
    # what follows COMMENT("done") is M2's reset (LinuxCNC stops the spindle there)
    for name, args, scale in canon_calls(expected.read_text(), stop_at='COMMENT("done")'):
        if name in ("STRAIGHT_TRAVERSE", "STRAIGHT_FEED"):
            out.append((name.lower(), tuple(round(float(v) * scale, 3) for v in args[:3])))
        elif name == "DWELL":
            out.append(("dwell", float(args[0])))
        elif name.startswith("START_SPINDLE"):
            if out and out[-1] == ("spindle", 0):
                out.pop()
            out.append(("spindle", -1 if "COUNTER" in name else 1))
        elif name == "STOP_SPINDLE_TURNING":
            out.append(("spindle", 0))
    return out


def project_calls(program: Program) -> list[tuple]:
    """The same from the project's reading (canonical records and events, merged in order)."""
    records = canon_records(program)
    after: dict[int, list[tuple]] = {}
    for e in program.events:
        if e.kind is EventKind.DWELL:
            after.setdefault(e.after_move, []).append(("dwell", e.payload_as(Dwell).seconds))
        elif e.kind is EventKind.SPINDLE:
            after.setdefault(e.after_move, []).append(("spindle", e.payload_as(SpindleSpeed).direction))
    out = list(after.get(-1, []))
    for i, rec in enumerate(records):
        out.append((rec["call"], tuple(round(v, 3) for v in rec["args"][:3])))
        out.extend(after.get(i, []))
    return out


#: LinuxCNC 2.9 feeds G74/G84 in the XZ and YZ planes along the wrong axes (convert_cycle_g74_g84
#: passes the coordinates to cycle_feed in the XY order): a tap would be driven sideways. The
#: project feeds along the hole axis there; those reference feeds are compared for the rest.
LINUXCNC_G84_PLANE_BUG = {"g84/g18/g98", "g84/g18/g99", "g84/g19/g98", "g84/g19/g99"}


@pytest.mark.parametrize("folder", REFERENCES, ids=[str(p.relative_to(DATA)) for p in REFERENCES])
def test_linuxcnc_canned_cycle_tests_read_call_by_call(folder: Path) -> None:
    (ngc,) = folder.glob("*.ngc")
    program = parse_program(ngc.read_text(), name=ngc.name)
    want = [c for c in linuxcnc_calls(folder / "expected") if c != ("dwell", 0.0)]
    got = project_calls(program)
    # LinuxCNC writes the zero-length moves of a cycle (already at the R plane); a Program has none
    want = [c for k, c in enumerate(want)
            if not (c[0].startswith("straight") and k and _last_position(want[:k]) == c[1])]
    if str(folder.relative_to(DATA)) in LINUXCNC_G84_PLANE_BUG:
        normal = 1 if "g18" in str(folder) else 0
        lc_feeds = [c for c in want if c[0] == "straight_feed"]
        sideways = [f for f in lc_feeds if any(abs(f[1][i] - _after_traverse(want, f)[i]) > 1e-9
                                               for i in range(3) if i != normal)]
        assert lc_feeds and sideways, "LinuxCNC's feeds here move other axes than the hole's (its bug)"
        want = [c for c in want if c[0] != "straight_feed"]
        for f in [c for c in got if c[0] == "straight_feed"]:
            before = _after_traverse(got, f)
            assert [i for i in range(3) if abs(f[1][i] - before[i]) > 1e-9] == [normal], (f, before)
        got = [c for c in got if c[0] != "straight_feed"]
        # the feed back out ends where LinuxCNC's next traverse starts: those traverses match
    assert got == want


def _after_traverse(calls: list[tuple], feed: tuple) -> tuple:
    """The position the move `feed` starts from: the last straight call before it."""
    k = calls.index(feed)
    return _last_position(calls[:k]) or (0.0, 0.0, 0.0)


def _last_position(calls: list[tuple]) -> tuple | None:
    for c in reversed(calls):
        if c[0].startswith("straight"):
            return c[1]
    return (0.0, 0.0, 0.0)


def test_reference_data_is_present() -> None:
    assert len(REFERENCES) == 12, REFERENCES


def read(text: str, **kw: object) -> Program:
    return parse_program(text, name="t.ngc", **kw)


def moves(program: Program) -> list[tuple[str, tuple[float, ...]]]:
    return [(r["call"][9:13], tuple(round(v, 4) for v in r["args"][:3])) for r in canon_records(program)]


def test_g83_pecks_back_to_r_and_down_to_a_quarter_millimetre_above_the_last_depth() -> None:
    """LinuxCNC 2.9 comes back down to 0.010 inch (0.254 mm) above the last peck."""
    p = read("G21 G90 G99 F100\nG0 X0 Y0 Z10\nG83 X5 Y0 Z-7 R2 Q3\nM2\n")
    assert moves(p) == [
        ("trav", (0, 0, 10)), ("trav", (5, 0, 10)), ("trav", (5, 0, 2)),
        ("feed", (5, 0, -1)), ("trav", (5, 0, 2)), ("trav", (5, 0, -0.746)),
        ("feed", (5, 0, -4)), ("trav", (5, 0, 2)), ("trav", (5, 0, -3.746)),
        ("feed", (5, 0, -7)), ("trav", (5, 0, 2)),
    ]
    assert all(m.exact_stop for m in p.moves[1:])


def test_g73_breaks_chips_with_a_small_retract() -> None:
    """LinuxCNC 2.9 backs off 0.010 inch (0.254 mm) and takes no D word with a cycle."""
    p = read("G21 G90 G98 F100\nG0 X0 Y0 Z10\nG73 X0 Y0 Z-5 R1 Q2\nM2\n")
    assert moves(p) == [
        ("trav", (0, 0, 10)), ("trav", (0, 0, 1)),
        ("feed", (0, 0, -1)), ("trav", (0, 0, -0.746)),
        ("feed", (0, 0, -3)), ("trav", (0, 0, -2.746)),
        ("feed", (0, 0, -5)), ("trav", (0, 0, 10)),          # G98: back to the initial level
    ]
    with pytest.raises(ProgramError, match="D word with no G41, G41.1, G42, G42.1 or G96 to use it"):
        read("G21 G90 G98 F100\nG73 X0 Y0 Z-5 R1 Q2 D0.5\nM2\n")


@pytest.mark.parametrize("code, tail", [
    ("G82", [("feed", (3, 4, -2)), ("dwell", 0.5), ("trav", (3, 4, 3))]),
    ("G85", [("feed", (3, 4, -2)), ("feed", (3, 4, 1)), ("trav", (3, 4, 3))]),
    ("G89", [("feed", (3, 4, -2)), ("dwell", 0.5), ("feed", (3, 4, 3))]),
    ("G86", [("feed", (3, 4, -2)), ("dwell", 0.5), ("spindle", 0), ("trav", (3, 4, 3)), ("spindle", 1)]),
])
def test_boring_cycles_feed_dwell_and_retract_as_documented(code: str, tail: list[tuple]) -> None:
    """G98 from Z3 with R1: down at feed, the cycle's own way back, the rest at rapid to Z3."""
    dwell = "" if code == "G85" else " P0.5"
    p = read(f"G21 G90 G98 F100 S1000 M3\nG0 X0 Y0 Z3\n{code} X3 Y4 Z-2 R1{dwell}\nM2\n")
    calls = [(c[0][9:13], c[1]) if c[0].startswith("straight") else c for c in project_calls(p)]
    start = calls.index(("trav", (3, 4, 1)))
    assert calls[start + 1:] == tail, calls


def test_g74_needs_the_spindle_counterclockwise_and_reverses_it() -> None:
    p = read("G21 G90 G99 F100 S500 M4\nG0 X0 Y0 Z5\nG74 X1 Y1 Z-3 R2\nM2\n")
    spindle = [e.payload_as(SpindleSpeed).signed_rpm for e in p.events if e.kind is EventKind.SPINDLE]
    assert spindle == [-500.0, 500.0, -500.0]
    assert "floating tap holder" in [e.message for e in p.events if e.kind is EventKind.SPINDLE][1]
    assert moves(p)[-2:] == [("feed", (1, 1, -3)), ("feed", (1, 1, 2))]


def test_sticky_words_and_modal_repeat_at_new_positions() -> None:
    p = read("G21 G90 G99 F100\nG0 Z5\nG81 X1 Y1 Z-2 R1\nX2\nY3 Z-4\nG80\nG0 X0 Y0\nM2\n")
    bottoms = [m[1] for m in moves(p) if m[0] == "feed"]
    assert bottoms == [(1, 1, -2), (2, 1, -2), (2, 3, -4)]


def test_g80_beside_another_motion_code_is_ignored() -> None:
    """LinuxCNC accepts G80 with another motion code in one block; the other one counts."""
    a = read("G21 G90 F100\nG0 X1 Y2 Z3 G80\nG80 G1 X4\nM2\n")
    assert moves(a) == [("trav", (1, 2, 3)), ("feed", (4, 2, 3))]


def test_incremental_cycle_with_repeats_steps_from_the_initial_level() -> None:
    p = read("G21 G91 G99 F100\nG81 X10 Y0 Z-3 R-1 L3\nM2\n", start_position=(0, 0, 5))
    assert [m[1] for m in moves(p) if m[0] == "feed"] == [(10, 0, 1), (20, 0, 1), (30, 0, 1)]


def test_a_plain_move_ends_the_cycle_sequence_so_g98_takes_a_new_level() -> None:
    p = read("G21 G90 G98 F100\nG0 Z10\nG81 X1 Y1 Z-1 R2\nG0 Z20\nG81 X2 Y2 Z-1 R2\nM2\n")
    assert moves(p)[-1] == ("trav", (2, 2, 20))


def test_cycles_move_with_the_work_offset_and_inch_units() -> None:
    spec = replace(MachineSpec.default(), work_offsets={"G55": (100.0, 50.0, -10.0)})
    p = read("G20 G90 G99 F10 G55\nG0 X0 Y0 Z1\nG81 X1 Y1 Z-0.5 R0.1\nM2\n", machine=spec)
    assert moves(p)[-2:] == [("feed", (25.4, 25.4, -12.7)), ("trav", (25.4, 25.4, 2.54))]   # work coordinates
    np.testing.assert_allclose(p.moves[-2].end, [125.4, 75.4, -22.7])                       # machine


@pytest.mark.parametrize("text, line, col, words", [
    ("G21 F100\nG81 X1 Y1 Z-1\n", 2, 1, "needs an R word"),
    ("G21 F100\nG81 X1 Y1 R1\n", 2, 1, "needs a Z word"),
    ("G21 F100\nG82 X1 Z-1 R1\n", 2, 1, "needs a P word"),
    ("G21 F100\nG83 X1 Z-1 R1\n", 2, 1, "needs a Q word"),
    ("G21 F100\nG83 X1 Z-1 R1 Q-1\n", 2, 15, "negative or zero Q"),
    ("G21 F100\nG81 X1 Z1 R0\n", 2, 11, "R (0) below the bottom Z (1)"),
    ("G21 F100\nG81 X1 Z-1 R1 L0\n", 2, 15, "whole number of 1 or more"),
    ("G21 F100\nG81 X1 Z-1 R1 L2.5\n", 2, 15, "whole number of 1 or more"),
    ("G21\nG81 X1 Z-1 R1\n", 2, 1, "feed rate is zero"),
    ("G21 F100\nG1 X1 L2\n", 2, 7, "L word with no canned cycle, G05.2, G10, G76 or M66"),
    ("G21 F100\nG1 X1 R2\n", 2, 7, "R word with no G02/G03 or canned cycle"),
    ("G21 F100 S100 M3\nG84 X1 Z-1 R1 Q1\n", 2, 15, "Q word with no code that uses it"),
    ("G21 F100 S100\nG84 X1 Z-1 R1\n", 2, 1, "spindle not turning in G84"),
    ("G21 F100 S100 M4\nG84 X1 Z-1 R1\n", 2, 1, "spindle turning counterclockwise in G84"),
    ("G21 F100\nG86 X1 Z-1 R1 P1\n", 2, 1, "spindle not turning in G86"),
    ("G21 F100\nG83 X0 Z-100 R0 Q0.0001\n", 2, 17, "more than 100000 pecks"),
    ("G21 F100\nG87 X1 Z-1 R1\n", 2, 1, "G87 is not supported (G87 back boring"),
    ("G21 F100\nG88 X1 Z-1 R1 P1\n", 2, 1, "G88 is not supported"),
    ("G21 F100\nG80 X1\n", 2, 5, "cannot use axis values with G80"),
    ("G21 F100\nG81 G82 X1 Z-1 R1 P1\n", 2, 5, "same modal group"),
])
def test_refusals_name_line_column_and_reason(text: str, line: int, col: int, words: str) -> None:
    with pytest.raises(ProgramError) as exc:
        read(text)
    (err,) = exc.value.errors
    assert (err.line, err.col) == (line, col) and words in err.message, err


def test_rotary_axis_word_in_a_cycle_is_refused_as_linuxcnc_does() -> None:
    axes = tuple(AxisSpec(n, drive_position=i, v_max=30, a_max=1000, j_max=10000)
                 for i, n in enumerate("XYZ"))
    spec = MachineSpec("XYZA", axes + (AxisSpec("A", rotary=True, drive_position=3, v_max=90, a_max=1800,
                                                j_max=36000),))
    for ngc in sorted((DATA / "bad").glob("a-in-canned-cycle*.ngc")):
        text = ngc.read_text()
        assert text.splitlines()[0] == ";Cannot put an a in canned cycle"
        with pytest.raises(ProgramError, match="cannot put an A word in a canned cycle"):
            read(text, machine=spec)


@settings(max_examples=150, deadline=None)
@given(code=st.sampled_from(["G73", "G74", "G81", "G82", "G83", "G84", "G85", "G86", "G89"]),
       plane=st.sampled_from(["G17", "G18", "G19"]), retract=st.sampled_from(["G98", "G99"]),
       absolute=st.booleans(), repeats=st.integers(1, 3),
       start=st.floats(-20, 20), r=st.floats(-10, 10), depth=st.floats(0.01, 15),
       q=st.floats(0.2, 5), scale=st.sampled_from([0.001, 1.0, 1000.0]))
def test_every_cycle_stays_between_its_bottom_and_its_clearance(code: str, plane: str, retract: str,
                                                                  absolute: bool, repeats: int, start: float,
                                                                  r: float, depth: float, q: float,
                                                                  scale: float) -> None:
    """Whatever the words, a cycle's hole axis never goes below the bottom nor above the higher of
    the start level and R (G73/G83 may retract a peck clearance, 1 program unit, above them, as in
    LinuxCNC), ends at its clearance, and feeds only along the hole axis."""
    normal = {"G17": 2, "G18": 1, "G19": 0}[plane]
    letter = "XYZ"[normal]
    spin = "M4" if code == "G74" else "M3"
    s = scale
    if absolute:
        words = f"{letter}{(r - depth) * s:.6f} R{r * s:.6f}"
    else:
        words = f"{letter}{-depth * s:.6f} R{(r - start) * s:.6f}"
    start_pos = [0.0, 0.0, 0.0]
    start_pos[normal] = start * s
    text = (f"G21 {plane} {retract} {'G90' if absolute else 'G91'} F100 S1000 {spin}\n"
            f"{code} {words} Q{q * s:.6f} P0.1 L{repeats}\nM2\n")
    if code not in ("G73", "G83"):
        text = text.replace(f" Q{q * s:.6f}", "")
    if code not in ("G82", "G86", "G89", "G74", "G84"):
        text = text.replace(" P0.1", "")
    program = read(text, start_position=tuple(start_pos))
    lo, hi = (r - depth) * s, max(start, r) * s + (1.0 if code in ("G73", "G83") else 0.0)
    tol = 1e-6 * max(1.0, s * 20)
    ends = np.array([m.end[normal] for m in program.moves])
    assert ends.min() >= lo - tol and ends.max() <= hi + tol
    clear = r * s if retract == "G99" else max(start, r) * s
    assert abs(ends[-1] - clear) <= tol
    for m in program.moves:
        if m.kind.name != "RAPID":
            d = np.abs(np.asarray(m.end) - np.asarray(m.start))
            assert d[[i for i in range(3) if i != normal]].max() <= tol


def _pecks_by_loop(z0: float, r: float, bottom: float, q: float, g83: bool) -> list[tuple[str, float]]:
    """LinuxCNC's G73/G83 loop (interp_cycles.cc), written out move by move: the reference the
    interpreter's pecks, made all at once, must equal bit for bit."""
    out = []
    if z0 > r:
        out.append(("rapid", r))
    depth = r - q
    while depth > bottom:
        out.append(("feed", depth))
        if g83:
            out.append(("rapid", r))
        out.append(("rapid", depth + 0.254))
        depth -= q
    out.append(("feed", bottom))
    out.append(("rapid", r))
    merged: list[tuple[str, float]] = []
    at = z0
    for kind, z in out:
        if abs(z - at) > 1e-9:           # a move to where the tool is (within 1e-9 mm) is no move
            merged.append((kind, z))
            at = z
    return merged


@settings(max_examples=150, deadline=None)
@given(r=st.floats(-20, 20), depth=st.floats(0.01, 60), q=st.floats(0.001, 5), g83=st.booleans(),
       scale=st.sampled_from([0.001, 1.0, 1000.0]))
def test_pecks_are_linuxcnc_s_loop_bit_for_bit(r: float, depth: float, q: float, g83: bool,
                                               scale: float) -> None:
    q = max(q, depth / 20_000)                      # at most 20,000 pecks
    # the words as written (9 decimals); the reference computes from the same numbers
    r_t, bottom_t, q_t, z0_t = (f"{v * scale:.9f}" for v in (r, r - depth, q, r + 5.0))
    r, bottom, q, z0 = float(r_t), float(bottom_t), float(q_t), float(z0_t)
    if not (q > 0 and bottom < r):
        return
    code = "G83" if g83 else "G73"
    text = f"G21 G90 G99 F100\nG0 X0 Y0 Z{z0_t}\n{code} X0 Y0 Z{bottom_t} R{r_t} Q{q_t}\nM2\n"
    program = parse_program(text)
    got = [("rapid" if m.kind == 0 else "feed", float(m.end[2])) for m in program.moves[1:]]
    assert got == _pecks_by_loop(z0, r, bottom, q, g83)
    ends = np.array([m.end for m in program.moves])
    starts = np.array([m.start for m in program.moves])
    np.testing.assert_array_equal(starts[1:], ends[:-1])
    np.testing.assert_allclose([m.length_mm for m in program.moves],
                               np.linalg.norm(ends - starts, axis=1), rtol=1e-12)


@pytest.mark.skipif(RS274 is None, reason="LinuxCNC's rs274 is not installed (make test installs it as root)")
@pytest.mark.parametrize("text", [
    # G18: holes along Y, a turned axis when the system is rotated; G19: along X
    "G21 F100\nG10 L2 P1 X10 Y20 Z-5 R30\nG54\nG0 X1 Y2 Z3\nG18 G81 X5 Y-4 Z2 R6\nG17 G80\nM2\n",
    "G21 F100\nG10 L2 P1 X-7 Y3 R-45\nG54\nG0 X5 Y1 Z1\nG19 G99 G83 Y1 Z1 X-3 R4 Q0.7\nG17 G80\nM2\n",
    "G21 F100\nG10 L2 P2 R90\nG55\nG0 X2 Y8 Z0\nG18 G98 G73 X1 Z-2 Y-6 R5 Q1.1 L2\n"
    "G91 G18 G81 X2 Z1 Y-3 R1 L2\nG90 G17 G80\nM2\n",
])
def test_cycles_in_g18_g19_of_a_rotated_system_are_linuxcnc_s(text: str) -> None:
    from tools.linuxcnc_oracle import project_motion, run_linuxcnc

    theirs = run_linuxcnc(text)
    assert not theirs.error, theirs.error
    program = parse_program(text)
    ours = project_motion(program)
    assert [c for c, _ in ours] == [c for c, _ in theirs.motion]
    for (_, a), (_, b) in zip(ours, theirs.motion, strict=True):
        assert a == pytest.approx(b, abs=0.003)
