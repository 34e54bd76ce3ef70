"""Fuzz: random bytes, G-code-like token soup and mutations of real programs either parse or
raise ProgramError (a PlannerError) whose every error has a valid line and column; nothing
else escapes, and whatever parses is geometrically sound (finite, contiguous, evaluable)."""

from __future__ import annotations

from dataclasses import replace
from datetime import timedelta
from pathlib import Path

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from planner.core.errors import PlannerError, ProgramError
from planner.core.machine import MachineSpec
from planner.core.movestore import MoveStore
from planner.core.tools import ToolTable, parse_tbl
from planner.gcode.interpreter import Interpreter, parse_program

SAMPLES_DIR = Path(__file__).resolve().parents[3] / "shared" / "gcode" / "cam"
BUILTIN = (
    "%\nO0001 (PART)\nG21 G17 G90 G94 G54\nT1 M6\nS1000 M3\nG0 X0 Y0 Z5\nG1 Z-1 F300\n"
    "G2 X10 Y0 R5\nG3 X0 Y0 I-5 J0 P2\nG18 G2 X5 Z-1 K1\nG19 G3 Y5 Z0 R3\nG17 G91 G1 X1 Y1\n"
    "G90 G4 P0.5\n#<a> = [1 + 2]\nG0 X#<a> Y[2 * 3]\nG28 Z0\nM5\nM30\n%\n"
)


def samples() -> list[str]:
    texts = [BUILTIN]
    if SAMPLES_DIR.is_dir():
        for p in sorted(SAMPLES_DIR.glob("*/*")):
            if p.is_file() and not p.name.endswith((".jsonl", ".tsv")):
                # the first 60 lines keep each example fast
                texts.append("\n".join(p.read_bytes().decode("latin-1").split("\n")[:60]))
    return texts


SAMPLES = samples()


TOOLS = parse_tbl("T1 P1 Z10.5 D6 ;flat\nT2 P2 X0.25 Z-3 D3 ;ball\n")


#: a machine with a digital input, so that M66 P0 reads (the default machine has none)
MACHINE = replace(MachineSpec.default(), input_bits={0: (0, 16, "")})


def check(text: str, tools: ToolTable | None = None) -> None:
    n_lines = text.count("\n") + 1
    try:
        program = parse_program(text, "fuzz.nc", tools=tools, machine=MACHINE)
    except ProgramError as exc:
        assert isinstance(exc, PlannerError)
        assert exc.errors
        for e in exc.errors:
            assert 1 <= e.line <= n_lines, e
            assert e.col >= 1, e
            assert str(e).startswith(f"fuzz.nc:{e.line}:{e.col}: error: ")
        return
    moves = program.moves
    if not len(moves):
        return
    # every move at once from the columns: finite, contiguous, of some length, on a line
    cols = moves.columns() if hasattr(moves, "columns") else MoveStore.from_moves(
        list(moves), program.start_position).columns()
    assert np.all(np.isfinite(cols.end)) and np.all(np.isfinite(cols.length)) and np.all(cols.length > 0)
    assert np.array_equal(cols.start[0], program.start_position)
    assert np.array_equal(cols.start[1:], cols.end[:-1])
    assert 1 <= int(cols.line.min()) and int(cols.line.max()) <= n_lines
    # a straight move's length is the distance between its ends (the machine's axes are linear)
    straight = np.ones(len(moves), dtype=bool)
    straight[cols.arc_rows] = False
    straight[cols.blend_rows] = False
    chord = np.linalg.norm(cols.end[straight] - cols.start[straight], axis=1)
    np.testing.assert_allclose(cols.length[straight], chord, rtol=1e-12, atol=1e-12)
    # evaluated one by one: every arc and blend, and the first moves (a cycle of 100,000 pecks
    # is straight lines whose evaluation the columns already pin down)
    rows = set(cols.arc_rows.tolist()) | set(cols.blend_rows.tolist()) | set(range(min(len(moves), 2000)))
    for i in sorted(rows):
        m = moves[i]
        pos, tan, curv = m.evaluate(np.array([0.0, m.length_mm / 2, m.length_mm]))
        assert np.all(np.isfinite(pos)) and np.all(np.isfinite(tan)) and np.all(np.isfinite(curv))
        np.testing.assert_array_equal(pos[-1], m.end)
        np.testing.assert_array_equal(m.start, cols.start[i])


@settings(max_examples=150)
@given(st.binary(max_size=300))
def test_random_bytes(data):
    check(data.decode("latin-1"))


token = st.one_of(
    st.sampled_from(list("GMXYZABCIJKRFSTPQNODHLEUVW%/();#[]<>=.-+ \n\t*")),
    st.from_regex(r"[GMXYZIJKRFPST][-+]?[0-9]{0,4}(\.[0-9]{0,4})?", fullmatch=True),
    st.sampled_from(
        [
            "G2",
            "G3",
            "G17",
            "G18",
            "G19",
            "G20",
            "G91",
            "G90.1",
            "G53",
            "G28",
            "M6",
            "M30",
            "SQRT[",
            "ATAN[1]/[",
            "#<x>",
            "#1=",
            "G41",
            "G42.1 D2",
            "G40",
            "G43",
            "G43.1",
            "G43.2",
            "G49",
            "M61",
            "H1",
            "H2",
            "Q1",
            "T2",
            "G80",
            "G4",
            # what a program reads from the machine, and rigid tapping
            "G38.2",
            "G38.3",
            "G38.4",
            "G38.5",
            "#5063",
            "#5070",
            "M66 P0",
            "M66 P0 L3 Q1",
            "#5399",
            "G33.1 K1",
            "G33.1",
            "G33 K1.5",
            "G76 P1.5 I-1 J0.1 K0.9",
            "G76 P2 I1 J0.2 K1.2 R1.5 Q29.5 H1 E1 L3",
            "E2",
            "G7",
            "M67 E0 Q1",
            "M68 E1 Q5",
            "G71 Q100 I1",
            "G70 Q100 P2",
            "G72.2 Q100 I0.5 R0.2",
            "I2",
            # spindle modes, polar steps of repeated cycles
            "G96 S100",
            "G96 D2000 S50",
            "G97 S1000",
            "D0",
            "^30 L3",
            "@2",
            # Fanuc-style subprograms, calls by number, an abort comment
            "M98 P100",
            "M98 P100 L2",
            "O100",
            "M99",
            "o#<s> call",
            "#<s>=100",
            "(ABORT,stop #1)",
            # curves: cubic, quadratic, NURBS control points and their end
            "G5 X3 Y2 I1 J1 P-1 Q1",
            "G5 X4 Y-1 P1 Q-2",
            "G5.1 X2 Y2 I1 J0",
            "G5.2 L4",
            "G5.2 P2",
            "X1 Y3 P0.5",
            "G5.3",
            # lathe diameter mode, the overrides' codes, a tap, the feed of a billion
            "G7",
            "G8",
            "M48",
            "M49",
            "M50 P0",
            "M51",
            "M52 P0",
            "M53 P1",
            "G84 Z-2 R1",
            "F1000000000",
        ]
    ),
)


@settings(max_examples=150)
@given(st.lists(token, max_size=60))
def test_gcode_token_soup(tokens):
    check("".join(tokens))
    check("".join(tokens), TOOLS)   # with a tool table: unknown tools refused, offsets applied


@settings(max_examples=150)
@given(
    st.sampled_from(range(len(SAMPLES))),
    st.lists(
        st.tuples(
            st.integers(0, 10**6), st.integers(0, 5), st.sampled_from(list("GXYZIJKR0123456789.-% ()\n"))
        )
    ),
)
def test_mutated_programs(which, edits):
    text = list(SAMPLES[which])
    for pos, kind, ch in edits[:8]:
        if not text:
            break
        i = pos % len(text)
        if kind == 0:
            del text[i]
        elif kind == 1:
            text.insert(i, ch)
        elif kind == 2:
            text[i] = ch
        elif kind == 3:  # duplicate a slice (repeats lines and words)
            text[i:i] = text[i : i + 40]
        elif kind == 4:  # drop a slice
            del text[i : i + 20]
        else:  # swap neighbours
            j = min(i + 1, len(text) - 1)
            text[i], text[j] = text[j], text[i]
    check("".join(text))


def test_samples_themselves():
    for text in SAMPLES:
        check(text)


# Differential: the one-regex fast path and the general path read every line the same way.
# A trailing "( )" comment sends a line through the general path.
num = st.decimals(-500, 500, places=3, allow_nan=False, allow_infinity=False).map(lambda d: f"{d:f}")
cam_line = st.one_of(
    st.builds(lambda g, x, y: f"G{g} X{x} Y{y}", st.sampled_from(["0", "00", "1", "01"]), num, num),
    st.builds(lambda x, z: f"X{x} Z{z}", num, num),
    st.builds(
        lambda g, x, y, r: f"G{g} X{x} Y{y} R{r}", st.sampled_from(["2", "3", "02", "03"]), num, num, num
    ),
    st.builds(lambda x, y, i, j: f"X{x} Y{y} I{i} J{j}", num, num, num, num),
    st.builds(lambda f: f"F{f}", st.integers(-10, 3000)),
    st.builds(lambda n, x: f"N{n} G1 X{x} F100", st.integers(0, 99999), num),
    st.sampled_from(["G91", "G90", "G20", "G21", "G18", "G17", "G19", "G90.1", "G91.1", "M3 S100", "G1 F0"]),
)


def _outcome(text: str):
    try:
        return parse_program(text, "d.nc")
    except ProgramError as exc:
        return exc


def _same(a, b) -> None:
    assert type(a) is type(b), (a, b)
    if isinstance(a, ProgramError):
        assert [(e.line, e.col, e.message) for e in a.errors] == [
            (e.line, e.col, e.message) for e in b.errors
        ]
        return
    assert len(a.moves) == len(b.moves)
    for ma, mb in zip(a.moves, b.moves):
        assert (ma.line, ma.kind, ma.feed_mm_s, ma.length_mm, ma.exact_stop) == (
            mb.line,
            mb.kind,
            mb.feed_mm_s,
            mb.length_mm,
            mb.exact_stop,
        )
        assert np.array_equal(ma.end, mb.end) and ma.arc == mb.arc
    assert [(e.kind, e.line, e.after_move, e.payload) for e in a.events] == [
        (e.kind, e.line, e.after_move, e.payload) for e in b.events
    ]


@settings(max_examples=100)
@given(st.lists(cam_line, min_size=1, max_size=25))
def test_fast_and_general_paths_agree(lines):
    text = "G1 F300\n" + "\n".join(lines)
    fast = _outcome(text)  # mostly the one-regex path
    commented = _outcome("G1 F300\n" + "\n".join(f"{line} ( )" for line in lines))  # word fast path
    Interpreter.use_fast = False
    try:
        general = _outcome(text)
    finally:
        Interpreter.use_fast = True
    _same(fast, general)
    _same(commented, general)


# Numbers at the edges of what a float holds, and expressions that make NaN and infinity:
# every place a number can stand (word values, parameter numbers, parameter values, indices).
extreme = st.sampled_from([
    "1e400", "-1e400", "1e308", "1e-320", "0", "-0", "999999999", "1000000000", "1e9", "0.0000001",
    "[10**300*10**300]", "[[10**300*10**300]-[10**300*10**300]]", "[0/0]", "[1/0]", "[-1/0]",
    "[SQRT[-1]]", "[LN[0]]", "[ACOS[2]]", "[10**400]", "[2**1024]", "#1", "#[1e400]", "#<_x>",
])
extreme_line = st.one_of(
    st.builds(lambda w, v: f"G1 {w}{v} F100", st.sampled_from(list("XYZIJKRFSP")), extreme),
    st.builds(lambda v: f"G2 X1 Y1 R{v} F100", extreme),
    st.builds(lambda v, w: f"#{v}={w}", extreme, extreme),
    st.builds(lambda v: f"#<_x>={v}\nG1 X#<_x> F100", extreme),
    st.builds(lambda v: f"G4 P{v}", extreme),
    st.builds(lambda v: f"G2 X0 Y0 I5 J0 P{v} F600", extreme),
)


@settings(max_examples=300, deadline=timedelta(seconds=5))
@given(st.lists(extreme_line, min_size=1, max_size=6))
def test_nan_infinity_and_huge_numbers_are_located_errors(lines):
    """A NaN or infinite parameter number once gave a Python traceback; every such input now
    either reads or is a ProgramError with its line and column."""
    check("\n".join(lines) + "\n")


# Programs built from every feature the interpreter reads (cycles, offsets, tool data, feed
# modes, polar words, modal memory, O-words, outputs, cutter compensation), then mutated: they
# parse or fail with ProgramError naming a valid line and column, at any scale.
_FEATURE_BLOCKS = [
    "G81 X{a} Y{b} Z{z} R{p} F{f}", "G83 X{a} Y{b} Z{n} R{p} Q{q} F{f}", "G73 X{a} Z{n} R{p} Q{q} F{f}",
    "G82 X{a} Z{n} R{p} P0.1 F{f}", "G85 Y{b} Z{z} R{p} F{f}", "G91 G81 X{a} Z{n} R{p} L3 F{f}", "G80",
    "G98", "G99", "G10 L2 P{k} X{a} Y{b} R{r}", "G10 L20 P{k} X{a}", "G10 L1 P1 Z{a} R1", "G10 L10 P2 Z{b}",
    "G92 X{a} Y{b}", "G92.1", "G92.2", "G92.3", "G52 X{a}", "G28.1", "G30.1", "G28 Z{p}", "G30",
    "G55", "G59.3", "G54", "G93 G1 X{a} F{f}", "G94 F{f}", "G95 F0.1", "S1000 M3", "G1 @{p} ^{r} F{f}",
    "G91 G0 ^{r}", "G90", "M70", "M72", "M7", "M8", "M9", "G0 X{a} Y{b} Z{p}", "G2 X{a} Y{b} R{p} F{f}",
    "#<v> = [{a} + 1]", "G1 X#<v> F{f}", "G17", "G18", "G19", "G20", "G21",
    "G41.1 D{p} G1 X{a} Y{b} F{f}", "G42.1 D{q}", "G41 D1", "G42", "G40", "G40 G1 X{a}",
    "G3 X{a} Y{b} I{p}", "G1 Y{b}", "G2 X{b} Y{a} R{n}", "G1 Z{z}", "G0 X{b}",
    "G5 X{a} Y{b} I{p} J{q} P{n} Q{p} F{f}", "G5 X{b} Y{a} P{q} Q{n}", "G5.1 X{b} Y{a} I{q} J{p} F{f}",
    "G5.2 X{a} Y{b} P1 L3", "X{b} Y{a} P2", "G5.3",
]
_O_WRAPPERS = [("o10 if [{a} GT 0]", "o10 endif"), ("o20 repeat [2]", "o20 endrepeat"),
               ("o30 while [#<w> LT 2]\n#<w> = [#<w> + 1]", "o30 endwhile")]


# a G83 of Q0.001 down 16 mm in a loop is tens of thousands of pecks, seconds to read: the
# deadline catches a hang, not that
@settings(max_examples=200, deadline=timedelta(seconds=30))
@given(blocks=st.lists(st.sampled_from(_FEATURE_BLOCKS), min_size=1, max_size=14),
       wrap=st.sampled_from([None, *_O_WRAPPERS]),
       values=st.lists(st.floats(-50, 50), min_size=8, max_size=8),
       scale=st.sampled_from([0.001, 1.0, 1000.0]), drop=st.integers(0, 20),
       junk=st.sampled_from(["", "Q", "[", "o", "L-1", "P99"]))
def test_feature_programs_and_their_mutations(blocks, wrap, values, scale, drop, junk) -> None:
    a, b, n, p, q, f, r, k = values
    words = {"a": f"{a * scale:.4f}", "b": f"{b * scale:.4f}", "n": f"{-abs(n) * scale:.4f}",
             "p": f"{abs(p) * scale + 0.01:.4f}", "q": f"{abs(q) * scale + 0.001:.4f}",
             "f": f"{abs(f) * 20 + 1:.1f}", "r": f"{r * 7:.2f}", "k": str(int(abs(k)) % 10),
             "z": f"{n * scale:.4f}"}
    body = [blk.format(**words) for blk in blocks]
    if wrap is not None:
        body = ["#<w> = 0", wrap[0].format(**words), *body, wrap[1]]
    if body and junk:
        body[drop % len(body)] += " " + junk
    text = "G21 G90 F100\n" + "\n".join(body) + "\nM2\n"
    check(text, tools=TOOLS)
