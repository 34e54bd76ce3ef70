"""Plain coordinate lines read many at a time (planner.gcode.bulk) read exactly as one at a time.

The line-by-line interpreter is the reference: the same moves (positions bit for bit, line,
kind, feed, exact stop; lengths to the last bit of a double), events, modal record, offsets and
errors, on generated programs that mix plain runs with every line that ends a run, at the
scales of a watch part and of a ship's propeller, and on the shared CAM programs.
"""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from planner.core.errors import ProgramError
from planner.gcode.bulk import scan_plain
from planner.gcode.interpreter import Interpreter, parse_file, parse_program
from tests.planner.motion_programs import xyza_machine

SHARED_CAM = Path(__file__).resolve().parents[3] / "shared" / "gcode" / "cam"


def _scan(text: str, letters: str = "XYZFGN"):
    data = np.frombuffer(text.encode(), np.uint8)
    nl = np.flatnonzero(data == 10)
    starts = np.concatenate(([0], nl + 1))
    ends = np.concatenate((nl, [data.shape[0]]))
    return scan_plain(data, starts, ends, letters)


decimal = st.builds(
    lambda sign, whole, frac, point: f"{sign}{whole}{'.' if point or frac else ''}{frac}",
    st.sampled_from(["", "-", "+"]),
    st.text("0123456789", min_size=0, max_size=9),
    st.text("0123456789", min_size=0, max_size=6),
    st.booleans(),
).filter(lambda s: any(c.isdigit() for c in s))


@settings(max_examples=400)
@given(st.lists(decimal, min_size=1, max_size=30))
def test_numbers_read_to_the_same_double_as_float(numbers):
    block = _scan("\n".join(f"X{v}" for v in numbers))
    assert block.plain.all()
    for v, got in zip(numbers, block.values[:, 0]):
        assert got == float(v) and np.signbit(got) == np.signbit(float(v)), v


@pytest.mark.parametrize("line, plain", [
    ("X1.5 Y-2 Z.25", True), ("N10 G1 X1 F800", True), ("", True), ("   ", True),
    ("x-0.000y3.", True), ("G01 Y2", True), ("X+5 Y-.5", True), ("N5", True),
    ("(comment)", False), ("X 1", False), ("X1X2", False), ("G2 X1", False), ("1.5", False),
    ("X1.2.3", False), ("G1N5", False), ("X1234567890", False), ("X0.1234567890123456", False),
    ("X1e3", False), ("X1\tY2", False), ("X-", False), ("X.", False), ("X1-", False), ("G1.0 X1", False),
    ("#1=2", False), ("A5", False), ("M3", False), ("X[1]", False), ("%", False), ("/X1", False),
    ("X1;c", False), ("G0 X1 G1", False),
])
def test_what_is_a_plain_line(line, plain):
    assert bool(_scan(line).plain[0]) is plain


def _read(text: str, bulk: bool, machine=None, start=None):
    old_bulk, old_run = Interpreter.use_bulk, Interpreter.BULK_MIN_RUN
    Interpreter.use_bulk = bulk
    Interpreter.BULK_MIN_RUN = 1  # every run in bulk, however short
    try:
        return parse_program(text, "p.ngc", machine, start)
    except ProgramError as e:
        return e
    finally:
        Interpreter.use_bulk, Interpreter.BULK_MIN_RUN = old_bulk, old_run


def assert_same_reading(a, b) -> None:
    assert type(a) is type(b)
    if isinstance(a, ProgramError):
        where = [(e.line, e.col, e.message) for e in a.errors]
        assert where == [(e.line, e.col, e.message) for e in b.errors]
        return
    assert len(a.moves) == len(b.moves)
    np.testing.assert_array_equal(a.moves.positions, b.moves.positions)
    ca, cb = a.moves.columns(), b.moves.columns()
    for name in ("line", "kind", "feed", "exact_stop", "arc_rows"):
        np.testing.assert_array_equal(getattr(ca, name), getattr(cb, name), err_msg=name)
    np.testing.assert_allclose(ca.length, cb.length, rtol=4.5e-16, atol=0)  # one rounding (math.dist vs sqrt)
    assert ca.arcs == cb.arcs
    assert a.events == b.events
    assert a.modal == b.modal and a.frames == b.frames
    np.testing.assert_array_equal(a.move_frames, b.move_frames)
    assert a.line_count == b.line_count


def _coord(scale: float):
    return st.floats(-200.0, 200.0, allow_nan=False).map(lambda v: f"{v * scale:.4f}".rstrip("0"))


def plain_line(scale: float):
    word = st.tuples(st.sampled_from("XYZxyz"), _coord(scale)).map(lambda t: f"{t[0]}{t[1]}")
    def join(n, g, ws, f):  # one word per letter: a letter twice is no plain line
        return " ".join(p for p in (n, g, *dict((w[0].upper(), w) for w in ws).values(), f) if p)

    return st.builds(
        join,
        st.sampled_from(["", "N10", "n7"]), st.sampled_from(["", "", "G1", "G0", "G01", "g00"]),
        st.lists(word, max_size=3), st.sampled_from(["", "", "", "F600", "F0", "F-5", "f1200.5"]),
    )


# lines that end a run or change what the next run means
OTHER = ["G91", "G90", "G20", "G21", "G10 L2 P1 X5 Y-3 Z1", "G92 X1 Y2", "G92.1", "G55", "G54",
         "G2 X1 Y1 I1 J0 F100", "(a comment)", "G4 P0.1", "M0", "G1", "G0", "G93", "G94", "G61", "G64 P0.01",
         "G10 L2 P1 R30", "G10 L2 P1 R0", "%", "X1 Y1 ; remark", "G41 D1", "G40", "M3 S1000", "M5",
         "#<a>=3", "X#<a>", "G80", "X 1.5", "X1.5  Y 2", "G17", "G18", "G1 X1 X2", "A5"]


def program(scale: float):
    return st.lists(st.one_of(plain_line(scale), plain_line(scale), plain_line(scale),
                              st.sampled_from(OTHER)), min_size=1, max_size=60)


@settings(max_examples=300, deadline=None)
@given(program(1.0), st.sampled_from(["", "G1 F300\n", "G0\n", "G91 G1 F100\n", "G20 F10\n"]))
def test_bulk_reads_generated_programs_as_the_line_reader(lines, head):
    text = head + "\n".join(lines) + "\n"
    assert_same_reading(_read(text, True), _read(text, False))


@settings(max_examples=100, deadline=None)
@given(st.sampled_from([0.001, 1000.0]).flatmap(lambda s: program(s)))
def test_bulk_reads_scaled_programs_as_the_line_reader(lines):
    text = "G1 F300\n" + "\n".join(lines) + "\n"
    assert_same_reading(_read(text, True), _read(text, False))


def test_a_rotary_machine_and_a_start_position_read_the_same():
    machine = xyza_machine()
    body = "\n".join(f"X{i * 0.1:.3f} Y{(i % 7) * 0.2:.3f}" for i in range(200))
    text = "G1 F300\n" + body + "\nA5\nX1 Y1\n"
    a = _read(text, True, machine, [1.0, 2.0, 3.0, 4.0])
    assert_same_reading(a, _read(text, False, machine, [1.0, 2.0, 3.0, 4.0]))
    assert not isinstance(a, ProgramError) and len(a.moves) > 150


def test_zero_length_lines_inside_a_run_are_dropped_as_one_by_one():
    text = "G1 F300\n" + "X1\nX1\nX1.0000000001\nX2\nX2\n" * 30
    a = _read(text, True)
    assert_same_reading(a, _read(text, False))
    assert len(a.moves) == 60


@settings(max_examples=200, deadline=None)
@given(program(1.0), st.lists(st.integers(0, 3), min_size=60, max_size=60),
       st.sampled_from(["", "G1 F300\n", "G91 G1 F100\n"]))
def test_repeated_points_read_in_bulk_as_the_line_reader(lines, repeats, head):
    """Every line written again up to three times (CAM's repeated points): each copy a move of
    zero length, dropped where it stands, in bulk as line by line."""
    text = head + "\n".join(x for line, n in zip(lines, repeats) for x in [line] * (n + 1)) + "\n"
    assert_same_reading(_read(text, True), _read(text, False))


def test_a_program_of_repeated_points_stays_in_the_bulk_reader():
    """600,000 ``G1 X0`` lines: each a move of zero length after the first. Read line by line
    (as the bulk reader left every one of them to the line reader) they took minutes; in bulk,
    the run is not cut at each one."""
    import time

    from planner.gcode.fast import FastPaths

    text = "G21 G90 G1 F300\nX1\n" + "G1 X0\n" * 20_000 + "X2\n"
    calls: list[int] = []
    original = FastPaths.bulk_lines

    def counting(self, *args, **kwargs):  # noqa: ANN001, ANN002, ANN003, ANN202 - a spy on the method
        calls.append(1)
        return original(self, *args, **kwargs)

    FastPaths.bulk_lines = counting  # type: ignore[method-assign]
    try:
        started = time.process_time()
        program = parse_program(text, "p.ngc")
        spent = time.process_time() - started
    finally:
        FastPaths.bulk_lines = original  # type: ignore[method-assign]
    assert len(program.moves) == 3 and len(calls) < 10, len(calls)
    assert spent < 30


def test_an_error_inside_a_run_has_its_line():
    # F0 alone moves nothing; the first line of the run after it is the G01 with no feed
    text = "G1 F100\n" + "".join(f"X{i}\n" for i in range(1, 20)) + "F0\n"
    text += "".join(f"X{i}\n" for i in range(20, 40))
    a = _read(text, True)
    assert isinstance(a, ProgramError) and a.errors[0].line == 22
    assert_same_reading(a, _read(text, False))


@pytest.mark.skipif(not SHARED_CAM.is_dir(), reason="../shared/gcode/cam is not here (CI has it)")
def test_shared_cam_programs_read_the_same_in_bulk():
    files = sorted(p for p in SHARED_CAM.glob("*/*") if p.suffix.lower() in (".ngc", ".nc", ".gcode"))
    assert len(files) >= 10
    for path in files:
        text = path.read_bytes().decode("latin-1")
        assert_same_reading(_read(text, True), _read(text, False))


@pytest.mark.parametrize("encoding, newline", [("utf-8", "\n"), ("utf-8", "\r\n"), ("latin-1", "\n")])
def test_a_file_reads_as_its_text(tmp_path, encoding, newline):
    """parse_file hands the bulk reader the file's own bytes when they are UTF-8 with plain line
    ends, and the text otherwise: the same program either way."""
    body = "(Überfräsen, ø6)\nG1 F300\n" + "".join(f"X{i * 0.1:.2f} Y{i % 3}\n" for i in range(100)) + "M2\n"
    path = tmp_path / "p.ngc"
    path.write_bytes(body.replace("\n", newline).encode(encoding))
    read = parse_file(path)
    assert len(read.moves) == 99
    assert_same_reading(read, parse_program(body, str(path)))


@settings(max_examples=200, deadline=None)
@given(program(1.0), st.sampled_from([1, 9, 40, 200]), st.booleans())
def test_a_program_read_a_piece_at_a_time_reads_as_the_line_reader(lines, piece, from_bytes):
    """The bulk reader indexes the program a piece (cut after a newline) at a time: pieces of
    one line and more, from the text or from its bytes, read as line by line."""
    text = "G1 F300\n" + "\n".join(lines) + "\nM2\n"
    old = Interpreter.BULK_PIECE, Interpreter.BULK_MIN_RUN
    Interpreter.BULK_PIECE, Interpreter.BULK_MIN_RUN = piece, 1
    try:
        got = _read_bytes(text.encode("utf-8")) if from_bytes else _read(text, True)
    finally:
        Interpreter.BULK_PIECE, Interpreter.BULK_MIN_RUN = old
    ref = _read(text, False)
    assert_same_reading(got, ref)
    if not isinstance(ref, ProgramError):
        assert got.line_count == ref.line_count


def test_blocks_of_short_runs_then_long_runs_read_the_same(monkeypatch):
    """A program that starts with arcs between few lines (the reader stops scanning for some
    blocks) and goes on with long plain runs reads as line by line, across small blocks."""
    monkeypatch.setattr(Interpreter, "BULK_LINES", 32)
    def arcs(n: int) -> str:
        return "".join(f"G1 X{i % 5} Y{i % 3}\nG2 X{i % 5 + 2} Y{i % 3} I1 J0\n" for i in range(n))

    raster = "G1\n" + "".join(f"X{i * 0.1:.1f} Y{(i // 50) * 0.2:.1f}\n" for i in range(400))
    text = "G1 F600\n" + arcs(150) + raster + arcs(20) + raster
    old = Interpreter.use_bulk
    try:
        a = parse_program(text, "m.ngc")
        Interpreter.use_bulk = False
        b = parse_program(text, "m.ngc")
    finally:
        Interpreter.use_bulk = old
    assert len(a.moves) > 1000
    assert_same_reading(a, b)


@pytest.mark.parametrize("bulk", [True, False])
def test_a_long_program_reports_how_far_it_is_read(monkeypatch, bulk):
    monkeypatch.setattr(Interpreter, "use_bulk", bulk)
    monkeypatch.setattr(Interpreter, "BULK_LINES", 1000)
    monkeypatch.setattr(Interpreter, "PROGRESS_LINES", 1000)
    text = "G1 F600\n" + "".join(f"X{i * 0.01:.2f} Y{i % 7}\n" for i in range(5000))
    seen: list[float] = []
    parse_program(text, "p.ngc", progress=lambda done, total: seen.append(done / total))
    assert len(seen) >= 4
    # lines read of the lines (line by line), characters read of the text (in bulk)
    assert seen == sorted(seen) and seen[-1] >= 5000 / 5002 and seen[0] <= 0.2


def test_a_big_file_is_decoded_in_pieces_as_at_once(tmp_path, monkeypatch):
    """Pieces cut after newlines, multi-byte characters near the cuts: the same text; a file
    that is not UTF-8 still falls back to Latin-1."""
    import planner.gcode.source as source

    monkeypatch.setattr(source, "DECODE_PIECE", 7)
    text = "".join(f"G1 X{i} (é°ü{i % 3 * 'İ'})\n" for i in range(200)) + "M2"
    path = tmp_path / "u.ngc"
    path.write_bytes(text.encode("utf-8"))
    assert source.read_program(path) == text
    path.write_bytes(text.encode("utf-8") + b"\xff\n")
    assert source.read_program(path) == (text.encode("utf-8") + b"\xff\n").decode("latin-1")


@pytest.mark.parametrize("at", [0, 5, 6, 7, 12, 13])
def test_windows_line_ends_are_found_across_the_pieces_searched(at):
    from planner.gcode.source import contains

    text = "G1X1\nG1X2\nG1X3\n"
    crlf = text[:at] + "\r\n" + text[at:]
    assert contains(crlf, "\r\n", piece=3) and contains(crlf, "\r\n", piece=6)
    assert not contains(text, "\r\n", piece=3)


@settings(max_examples=300, deadline=None)
@given(st.text(alphabet="\r\nG1X.", max_size=60), st.sampled_from(["\r\n", "\r", "G1", "X.1"]),
       st.integers(1, 8), st.booleans())
def test_a_piecewise_search_finds_what_a_whole_one_finds(text: str, needle: str, piece: int,
                                                         raw: bool) -> None:
    """Across pieces, with the needle's first character alone or not followed by the rest
    (old Mac line ends, "\r" without "\n"), in text and in bytes."""
    from planner.gcode.source import contains

    if raw:
        assert contains(text.encode(), needle.encode(), piece=piece) == (needle.encode() in text.encode())
    else:
        assert contains(text, needle, piece=piece) == (needle in text)


def _read_bytes(data: bytes):
    try:
        return parse_program(None, "p.ngc", utf8=data)
    except ProgramError as e:
        return e


@settings(max_examples=200, deadline=None)
@given(program(1.0),
       st.sampled_from(["", "G1 F300\n", "\ufeffG1 F300\n", "o100 sub\no100 endsub\nG1 F300\n"]),
       st.sampled_from(["\n", "\r\n"]))
def test_a_program_read_from_its_bytes_alone_reads_as_its_text(lines, head, newline):
    # a file's bytes are read without their text beside them (250 MB each at 10,000,000 lines):
    # plain programs by the bulk reader, any other (a byte-order mark, Windows line ends,
    # O-words) decoded first; the same program, the same errors, the same line count
    text = (head + "\n".join(lines) + "\nM2\n").replace("\n", newline)
    ref = _read(text, True)
    got = _read_bytes(text.encode("utf-8"))
    assert_same_reading(got, ref)
    if not isinstance(ref, ProgramError):
        assert got.line_count == ref.line_count


@pytest.mark.parametrize("encoding", ["utf-8", "latin-1", "ascii"])
def test_a_file_is_read_from_its_bytes_when_they_are_utf8(tmp_path, encoding):
    from planner.gcode.interpreter import read_program, read_program_bytes

    body = ("(Uberfrasen)\n" if encoding == "ascii" else "(Überfräsen, ø6)\n") + "G1 F300\nX1\nM2\n"
    path = tmp_path / "p.ngc"
    path.write_bytes(body.encode(encoding))
    text, data = read_program_bytes(path)
    if encoding == "latin-1":
        assert data is None and text == body                  # not UTF-8: its text at once
    else:
        assert text is None and data == body.encode(encoding) and read_program(path) == body


@settings(max_examples=100, deadline=None)
@given(st.text(alphabet="G1X\n\r é", max_size=60), st.sampled_from([1, 2, 5, 1 << 22]))
def test_lines_are_counted_a_piece_at_a_time_as_at_once(text, piece):
    from planner.gcode.source import count_lines

    want = len(io.StringIO(text, newline="\n").readlines())    # as an editor numbers them
    assert count_lines(text, piece) == want
    assert count_lines(text.encode("utf-8"), piece) == want


@settings(max_examples=200, deadline=None)
@given(st.text(alphabet="G1X\r\n é°", max_size=80), st.sampled_from([1, 2, 3, 7, 1 << 22]),
       st.sampled_from(["utf-8", "latin-1"]), st.booleans())
def test_a_file_is_read_with_windows_line_ends_made_newlines_a_piece_at_a_time(text, piece, encoding, mark):
    """The text is never held twice to change its line ends or drop a byte-order mark (250 MB
    at 10,000,000 lines): a "\\r\\n" cut between two pieces, or a multi-byte character, reads
    as from the whole; a UTF-8 file's mark is no part of its text."""
    import os
    import tempfile

    import planner.gcode.source as source

    tail = b"\xff" if encoding == "latin-1" else b""         # not UTF-8: read as Latin-1
    data = (b"\xef\xbb\xbf" if mark else b"") + text.encode("utf-8") + tail
    want = data.decode("utf-8-sig" if encoding == "utf-8" else encoding).replace("\r\n", "\n")
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "p.ngc")
        with open(path, "wb") as f:
            f.write(data)
        old = source.DECODE_PIECE
        source.DECODE_PIECE = piece
        try:
            assert source.read_program(path) == want
        finally:
            source.DECODE_PIECE = old
