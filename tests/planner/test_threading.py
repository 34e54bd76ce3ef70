"""G33 (spindle-synchronised motion) and the G76 threading cycle as the interpreter reads them:
LinuxCNC 2.9's passes, depths, compound angle, tapers and diameter mode, fed at the pitch times
the programmed speed, and recorded as motion this machine refuses to run (no spindle encoder)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from planner.core.errors import ProgramError
from planner.core.machine import AxisSpec, MachineSpec
from planner.core.program import MoveKind, SynchronisedMotion
from planner.gcode.interpreter import parse_program
from tests.planner.refusals import refused_at
from tools.linuxcnc_oracle import RS274, motion_alike

# an outside thread from X10 Z5 to Z-20: 1.5 mm pitch, 1 mm off the drive line, first cut 0.1 mm,
# full depth 0.9 mm
THREAD = "G21 G18 M3 S500\nG0 X10 Z5\nG76 P1.5 Z-20 I-1 J0.1 K0.9\nM2\n"


def _feeds(program):
    return [m for m in program.moves if m.kind is MoveKind.LINE]


def test_a_thread_is_cut_in_passes_of_growing_depth_then_once_at_full_depth() -> None:
    p = parse_program(THREAD)
    feeds = _feeds(p)
    # depths I + J n (n = 1 ... 8) while below I + K, then I + K: X is the drive line less the depth
    depths = [1.0 + 0.1 * n for n in range(1, 9)] + [1.9]
    assert [m.end[0] for m in feeds] == pytest.approx([10.0 - d for d in depths])
    assert all(m.end[2] == pytest.approx(-20.0) for m in feeds)
    assert all(m.feed_mm_s == pytest.approx(1.5 * 500 / 60) for m in feeds)   # the pitch each turn
    # each pass: rapid back clear of the thread, rapid in, feed over, rapid out; then to the end point
    first = p.moves[1:5]
    assert [m.kind for m in first] == [MoveKind.RAPID, MoveKind.RAPID, MoveKind.LINE, MoveKind.RAPID]
    assert first[0].end.tolist() == pytest.approx([10.0 - 1.1 + 1.9, 0.0, 5.0])
    assert first[3].end.tolist() == pytest.approx([10.0 - 1.1 + 1.9, 0.0, -20.0])
    assert p.moves[-1].end.tolist() == pytest.approx([10.0, 0.0, -20.0])
    assert all(m.exact_stop for m in p.moves[1:])
    assert p.synchronised == (SynchronisedMotion("G76", 3),)


def test_degression_spring_passes_and_a_boring_thread() -> None:
    # R2: the n-th pass cuts to J sqrt(n); H2: two more passes at full depth; I > 0: boring, the
    # passes go out in +X
    p = parse_program("G21 M4 S300\nG0 X20 Z0\nG76 P2 Z-30 I1 J0.2 K1.2 R2 H2\nM2\n")
    depths = [1.0 + 0.2 * math.sqrt(n) for n in range(1, 37) if 0.2 * math.sqrt(n) < 1.2] + [2.2] * 3
    assert [m.end[0] for m in _feeds(p)] == pytest.approx([20.0 + d for d in depths])
    assert all(m.feed_mm_s == pytest.approx(2 * 300 / 60) for m in _feeds(p))


def test_the_compound_angle_moves_each_pass_along_z_by_its_depth() -> None:
    p = parse_program("G21 M3 S500\nG0 X10 Z5\nG76 P1.5 Z-20 I-1 J0.25 K0.9 Q30\nM2\n")
    over = _feeds(p)
    assert len(over) == 4                  # depths 1.25, 1.5, 1.75, then the full 1.9
    for m_over in over:
        depth = 10.0 - m_over.end[0] - 1.0
        assert m_over.start[2] == pytest.approx(5.0 - depth * math.tan(math.radians(30)))
        assert m_over.end[2] == pytest.approx(-20.0 + 0.9 * math.tan(math.radians(30))
                                              - depth * math.tan(math.radians(30)))


def test_tapers_feed_in_and_out_at_the_pitch_along_the_slope() -> None:
    p = parse_program("G21 M3 S600\nG0 X10 Z5\nG76 P1 Z-20 I-1 J0.5 K0.8 E2 L3\nM2\n")
    pitch_slope = 1.0 * math.hypot(2.0, 0.8) / 2.0
    rates = sorted({round(m.feed_mm_s * 60 / 600, 9) for m in _feeds(p)})
    assert rates == pytest.approx(sorted({1.0, pitch_slope}))
    last_pass = _feeds(p)[-4:]             # in, angled in, over, angled out
    assert [m.end[2] for m in last_pass] == pytest.approx([5.0, 3.0, -18.0, -20.0])
    assert [m.end[0] for m in last_pass] == pytest.approx([10.0 - 1.8 + 0.8, 8.2, 8.2, 10.0 - 1.8 + 0.8])


def test_in_diameter_mode_i_j_k_are_diameters() -> None:
    radius = parse_program("G21 M3 S500\nG0 X10 Z5\nG76 P1.5 Z-20 I-1 J0.1 K0.9\nM2\n")
    diameter = parse_program("G21 G7 M3 S500\nG0 X20 Z5\nG76 P1.5 Z-20 I-2 J0.2 K1.8\nM2\n")
    assert len(diameter.moves) == len(radius.moves) == 1 + 9 * 4
    assert np.allclose([m.end for m in diameter.moves], [m.end for m in radius.moves], atol=1e-12)


def test_g33_feeds_at_the_pitch_times_the_speed_whatever_the_feed_mode() -> None:
    for mode in ("G94 F100", "G93", "G95 F0.1"):
        p = parse_program(f"G21 {mode} M3 S600\nG33 Z-10 K1.25\nM4\nG33 Z0 K1.25\nM2\n")
        assert [m.feed_mm_s for m in p.moves] == pytest.approx([1.25 * 600 / 60] * 2), mode
        assert p.synchronised == (SynchronisedMotion("G33", 2), SynchronisedMotion("G33", 4))
    inch = parse_program("G20 M3 S300\nG33 Z-1 K0.05\nM2\n")
    assert inch.moves[0].feed_mm_s == pytest.approx(0.05 * 25.4 * 300 / 60)


@pytest.mark.parametrize(("text", "col_word", "reason"), [
    ("G21\nG33 Z-10 K1\n", "G33", "spindle not turning in G33"),
    ("G21 M3 S0\nG33 Z-10 K1\n", "G33", "spindle at S0"),
    ("G21 M3 S500\nG33 Z-10\n", "G33", "G33 needs a K word"),
    ("G21 M3 S500\nG33 Z-10 K1 F100\n", "F100", "the feed is the pitch K times the spindle speed"),
    ("G21 M3 S500\nG33 Z-10 K-1\n", "K-1", "must be above 0"),
    ("G21 M3 S500 F100\nG41.1 D2\nG1 X5\nG33 Z-10 K1\n", "G33", "cutter radius compensation"),
    ("G21\nG76 P1 Z-10 I-1 J0.1 K1\n", "G76", "spindle not turning in G76"),
    ("G21 M3 S500\nG76 Z-10 I-1 J0.1 K1\n", "G76", "G76 needs a P word"),
    ("G21 M3 S500\nG76 P1 Z-10 I-1 K1\n", "G76", "J missing"),
    ("G21 M3 S500\nG76 P1 Z-10 I0 J0.1 K1\n", "I0",
     "I (the thread's offset from the drive line) must not be 0"),
    ("G21 M3 S500\nG76 P1 Z-10 I-1 J0.1 K0.1\n", "K0.1", "K (the full thread depth) must be greater than J"),
    ("G21 M3 S500\nG76 P0 Z-10 I-1 J0.1 K1\n", "P0", "the pitch P0 must be above 0"),
    ("G21 M3 S500\nG76 P1 Z-10 I-1 J0.1 K1 H1.5\n", "H1.5", "whole number"),
    ("G21 M3 S500\nG76 P1 Z-10 I-1 J0.1 K1 L0.5\n", "L0.5", "whole number"),
    ("G21 M3 S500\nG76 P1 Z-10 I-1 J0.00001 K1 R3\n", "J0.00001", "passes"),
    ("G21 M3 S500 F100\nG41.1 D2\nG1 X5\nG76 P1 Z-10 I-1 J0.1 K1\n", "G76", "cutter radius compensation"),
    ("G21 M3 S500\nG1 X1 E2 F10\n", "E2", "E word with no G33, G33.1, G76, M67 or M68"),
])
def test_refusals_name_the_word_and_the_reason(text: str, col_word: str, reason: str) -> None:
    assert refused_at(text, col_word, reason).line == len(text.splitlines())


needs_rs274 = pytest.mark.skipif(RS274 is None, reason="LinuxCNC's rs274 is not installed (make test "
                                                       "installs it as root)")


def test_rotary_axes_stay_where_they_are() -> None:
    axes = tuple(AxisSpec(n, drive_position=i, v_max=30, a_max=1000, j_max=10000)
                 for i, n in enumerate("XYZ"))
    machine = MachineSpec("XYZA", axes + (AxisSpec("A", rotary=True, drive_position=3, v_max=90, a_max=1800,
                                                   j_max=36000),))
    with pytest.raises(ProgramError, match="cannot move rotary axes with G76"):
        parse_program("G21 M3 S500\nG76 P1 Z-10 A5 I-1 J0.1 K1\nM2\n", machine=machine)
    p = parse_program("G21 M3 S500\nG0 A30\nG76 P1 Z-10 A30 I-1 J0.1 K1\nM2\n", machine=machine)
    assert {float(m.end[3]) for m in p.moves} == {30.0}


@needs_rs274
@pytest.mark.parametrize("text", [
    THREAD,
    "G21 M3 S500\nG0 X10 Z5\nG76 P1.5 Z-20 I1 J0.1 K0.9 R2 Q29.5 H2 E1 L3\nM2\n",
    "G20 G7 M4 S300\nG0 X1 Z.2\nG76 P.0625 Z-1 I-.05 J.01 K.06 Q29 E.1 L1\nM2\n",
    "G21 M3 S500\nG0 X10 Z-25\nG76 P1.5 Z5 X3 I-1 J0.1 K0.9 Q30 E2 L2\nM2\n",
    # the mode changed in the G76's own block: LinuxCNC scales I J K there as well as in the cycle
    "G21 G8 M3 S500\nG0 X10 Z5\nG7 G76 P1.5 Z-20 I-1 J0.1 K0.9\nM2\n",
    "G20 G7 M3 S500\nG0 X10 Z5\nG8 G76 P.05 Z-2 I-.1 J0.01 K0.09\nM2\n",
    # in a rotated coordinate system with G92, incremental, modal
    "G21 M3 S500\nG10 L2 P2 X5 Y-3 Z1 R30\nG55 G92 X1 Z2\nG0 X10 Y4 Z5\nG91 G76 P1 Z-12 I-1 J0.2 K0.8\n"
    "G90 Z-4 P1 I-1 J0.2 K0.8\nM2\n",
    "G21 M3 S600\nG0 X0 Y0 Z10\nG33 Z-10 K1.25\nM4\nG33 Z10 K1.25\nG93 G33 X3 Z0 K1\nM2\n",
])
def test_threads_are_the_moves_linuxcnc_makes(text: str) -> None:
    motion_alike(text)


@st.composite
def thread_specs(draw) -> dict:
    """The words of a random G76 and where it starts, in hundredths of a unit (lengths) or as
    they are written (R, Q, H, L), with its units, mode and spindle direction."""
    def hundredths(lo: float, hi: float) -> int:
        return draw(st.integers(int(lo * 100), int(hi * 100)))

    j = hundredths(0.05, 0.5)
    spec = {"P": hundredths(0.5, 3.0), "Z": hundredths(-40.0, 40.0),
            "I": hundredths(0.2, 3.0) * draw(st.sampled_from([1, -1])), "J": j,
            "K": j + hundredths(0.05, 1.5),
            "x0": hundredths(-20.0, 20.0), "z0": hundredths(-40.0, 40.0)}
    if draw(st.booleans()):
        spec["X"] = hundredths(-20.0, 20.0)
    if draw(st.booleans()):
        spec["E"] = hundredths(0.1, 4.0)
    for letter, values in (("R", [1.0, 1.5, 2.5, 0.5]), ("Q", [29.5, 30.0, -1.0]), ("H", [0, 1, 3]),
                           ("L", [0, 1, 2, 3])):
        value = draw(st.sampled_from([None, *values]))
        if value is not None:
            spec[letter] = value
    spec["order"] = draw(st.permutations([k for k in spec if k in "PZIJKXERQHL"]))
    spec["head"] = (f"{'G7' if draw(st.booleans()) else 'G8'} M{draw(st.sampled_from([3, 4]))} S400")
    return spec


def thread_text(spec: dict, size: float, inch: bool) -> str:
    """The program of ``spec`` with its lengths times ``size`` (mm, or inches of the same size)."""
    scale = size / 25.4 if inch else size

    def word(letter: str) -> str:
        value = spec[letter]
        if letter in "PZIJKXE":
            return f"{letter}{value / 100.0 * scale:.15f}"
        return f"{letter}{value}"

    return (f"{'G20' if inch else 'G21'} {spec['head']}\nG0 X{spec['x0'] / 100.0 * scale:.15f} "
            f"Z{spec['z0'] / 100.0 * scale:.15f}\nG76 {' '.join(word(k) for k in spec['order'])}\nM2\n")


@needs_rs274
@settings(max_examples=60, deadline=None)
@given(thread_specs(), st.sampled_from([1.0, 1000.0]), st.booleans())
def test_random_threads_are_the_moves_linuxcnc_makes(spec: dict, size: float, inch: bool) -> None:
    """Threads of mm and inch parts, of millimetres and of metres (rs274 prints 4 decimals: a
    thousandth of the part is held to these by scale below)."""
    text = thread_text(spec, size, inch)
    try:
        parse_program(text)
    except ProgramError as exc:
        # refused only where a pass count would run away (J tiny against K with degression)
        assert "passes" in exc.errors[0].message, (exc, text)
        return
    motion_alike(text)


@settings(max_examples=60, deadline=None)
@given(thread_specs(), st.booleans())
def test_a_thread_scaled_is_the_same_thread_scaled(spec: dict, inch: bool) -> None:
    """Every length of G76 scales its moves: a thousandth of the part, or a thousand times it,
    gives the same passes, each end point scaled (unless a pass falls on the full depth to the
    last bit, where rounding decides whether it is cut, in LinuxCNC too)."""
    passes = (spec["K"] / spec["J"]) ** max(spec.get("R", 1.0), 1.0)
    assume(abs(passes - round(passes)) > 1e-6)
    try:
        base = parse_program(thread_text(spec, 1.0, inch))
    except ProgramError as exc:
        assert "passes" in exc.errors[0].message, exc
        return
    ends = np.array([m.end for m in base.moves])
    for size in (0.001, 1000.0):
        scaled = parse_program(thread_text(spec, size, inch))
        assert len(scaled.moves) == len(base.moves), size
        assert np.allclose([m.end for m in scaled.moves], ends * size, rtol=1e-7, atol=1e-9 * size)
