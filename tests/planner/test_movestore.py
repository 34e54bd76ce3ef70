"""A program's moves kept as columns read as the Move objects they stand for."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from planner.core.movestore import MoveBuffer, MoveStore
from planner.core.program import MoveKind
from planner.geometry.movetable import MoveTable
from planner.geometry.softlimits import move_bounds_table
from tests.planner.motion_programs import parse, random_program


def _fields(m):
    return (m.index, m.line, m.kind, m.feed_mm_s, m.length_mm, m.arc, m.exact_stop, m.blend,
            m.start.tolist(), m.end.tolist())


@pytest.fixture(scope="module")
def program():
    p = parse(random_program(7, n_blocks=60))
    assert isinstance(p.moves, MoveStore) and any(m.arc is not None for m in p.moves)
    return p


def test_indexing_iteration_and_slices_agree(program):
    moves = program.moves
    n = len(moves)
    listed = list(moves)
    assert [_fields(m) for m in listed] == [_fields(moves[i]) for i in range(n)]
    assert _fields(moves[-1]) == _fields(listed[-1])
    part = moves[5:17]
    assert len(part) == 12 and [m.index for m in part] == list(range(5, 17))
    assert [_fields(m) for m in part] == [_fields(m) for m in listed[5:17]]
    assert len(moves[17:5]) == 0
    with pytest.raises(IndexError):
        moves[n]
    with pytest.raises(ValueError):
        moves[::2]


def test_moves_join_end_to_start(program):
    listed = list(program.moves)
    for a, b in zip(listed, listed[1:]):
        np.testing.assert_array_equal(a.end, b.start)
    np.testing.assert_array_equal(listed[0].start, program.start_position)


def test_a_store_of_moves_made_one_by_one_is_the_same(program):
    again = MoveStore.from_moves(tuple(program.moves), program.start_position)
    assert [_fields(m) for m in again] == [_fields(m) for m in program.moves]


@pytest.mark.parametrize("first", [0, 1, 13, 40])
def test_a_piece_numbered_from_zero_is_the_store_made_of_its_moves(program, first: int) -> None:
    """What follows a probe runs as a program of its own: the piece of the store, numbered from
    0, reads as the store made of its moves one by one (arcs and blends where they were)."""
    piece = program.moves[first:]
    own = piece.numbered_from_zero()
    made = MoveStore.from_moves(list(piece), piece.positions[0])
    assert [_fields(m) for m in own] == [_fields(m) for m in made]
    assert [m.index for m in own] == list(range(len(piece)))
    a, b = own.columns(), made.columns()
    assert a.first == b.first == 0 and a.arcs == b.arcs
    np.testing.assert_array_equal(a.arc_rows, b.arc_rows)
    assert own.nbytes == program.moves.nbytes               # the columns shared, not copied


def test_tables_and_bounds_from_columns_equal_those_from_move_objects(program):
    objects = replace(program, moves=tuple(program.moves))
    a = MoveTable.from_store(program.moves[3:40], 3)
    b = MoveTable.from_moves(list(objects.moves[3:40]), 3)
    for name in MoveTable.__slots__:
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name), err_msg=name)
    for x, y in zip(move_bounds_table(program), move_bounds_table(objects)):
        np.testing.assert_array_equal(x, y)


def test_the_buffer_moves_an_end_and_drops_a_move_packed_or_not():
    buf = MoveBuffer([0.0, 0.0, 0.0])
    buf.CHUNK = 4  # pack early, so that both places are exercised
    for i in range(10):
        buf.append([float(i + 1), 0.0, 0.0], i + 1, int(MoveKind.LINE), 5.0, 1.0, None, False)
    assert buf._packed == 8 and len(buf) == 10
    buf.replace(2, [3.0, 1.0, 0.0], 1.5, None)  # packed
    buf.replace(9, [10.0, 2.0, 0.0], 1.2, None)  # still a list
    assert buf.end(2) == [3.0, 1.0, 0.0] and buf.record(9)[3] == 1.2
    buf.delete(4)  # packed
    buf.delete(7)  # was move 8, still a list
    assert buf.last_end() == [10.0, 2.0, 0.0]
    store = buf.store()
    assert [m.line for m in store] == [1, 2, 3, 4, 6, 7, 8, 10]
    assert store[2].length_mm == 1.5 and store[1].end.tolist() == [2.0, 0.0, 0.0]


def test_blend_report_reads_columns_as_move_objects():
    from planner.geometry.blend import blend_report
    from planner.motion.blending import blend_program
    from tests.planner.motion_programs import paper_machine

    text = "G64 P0.05\nG1 F6000\n" + "".join(f"X{i * 3} Y{(i % 2) * 0.5}\n" for i in range(1, 30))
    machine = paper_machine()
    blended = blend_program(parse(text, machine), machine, only_where_quicker=False)
    store = replace(blended, moves=MoveStore.from_moves(tuple(blended.moves), blended.start_position))
    a, b = blend_report(blended), blend_report(store)
    assert a.blends > 10 and a == b


_KIND_LINE, _KIND_RAPID = int(MoveKind.LINE), int(MoveKind.RAPID)


@st.composite
def _buffer_steps(draw):  # noqa: ANN001, ANN202
    """Moves appended one at a time (lines and rapids, feeds from a few values or from every
    float, lengths the distance between the ends or not, as arcs have) or a block at a time,
    with ends moved and moves dropped among them, anywhere."""
    scale = draw(st.sampled_from([0.001, 1.0, 1000.0]))
    coord = st.floats(-100.0, 100.0, allow_nan=False).map(lambda v: v * scale)
    feeds = st.one_of(st.sampled_from([0.0, -0.0, 600.0, 1200.0]),
                      st.floats(allow_nan=True, allow_infinity=True))
    steps = []
    for _ in range(draw(st.integers(1, 60))):
        what = draw(st.sampled_from(["append", "append", "append", "extend", "replace", "delete"]))
        if what == "append":
            end = [draw(coord) for _ in range(3)]
            length = draw(st.one_of(st.none(), st.floats(0.0, 1e6), st.just(-0.0), st.just(math.nan)))
            kind = draw(st.sampled_from([_KIND_LINE, _KIND_RAPID]))
            steps.append(("append", end, draw(st.integers(1, 10**6)), kind, draw(feeds), length,
                          draw(st.booleans())))
        elif what == "extend":
            k = draw(st.integers(0, 40))
            steps.append(("extend", [[draw(coord) for _ in range(3)] for _ in range(k)], draw(feeds),
                          draw(st.booleans()), draw(st.booleans())))
        else:
            steps.append((what, draw(st.floats(0.0, 1.0)), [draw(coord) for _ in range(3)],
                          draw(st.floats(0.0, 1e3))))
    return steps


def _run_steps(steps, chunk: int) -> MoveStore:  # noqa: ANN001
    from planner.core.packed import straight_lengths

    buf = MoveBuffer([0.0, 0.0, 0.0])
    buf.CHUNK = chunk
    for step in steps:
        if step[0] == "append":
            _, end, line, kind, feed, length, stop = step
            if length is None:   # a straight move's own length, as the interpreter gives it
                length = float(straight_lengths(np.array([buf.last_end(), end]))[0])
            buf.append(list(end), line, kind, feed, length, None, stop)
        elif step[0] == "extend":
            _, ends, feed, straight, stop = step
            ends = np.array(ends, float).reshape(-1, 3)
            before = np.vstack((buf.last_end(), ends))
            length = straight_lengths(before) if straight else np.full(len(ends), 2.5)
            buf.extend(ends, np.arange(1, len(ends) + 1), np.full(len(ends), _KIND_LINE),
                       np.full(len(ends), feed), length, stop)
        elif len(buf):
            _, at, end, length = step
            i = min(int(at * len(buf)), len(buf) - 1)
            if step[0] == "replace":
                buf.replace(i, list(end), length, None)
            else:
                buf.delete(i)
    return buf.store()


@settings(max_examples=150, deadline=None)
@given(_buffer_steps(), st.sampled_from([1, 2, 3, 4096]))
def test_chunks_kept_sparse_give_the_store_of_plain_ones_bit_for_bit(steps, chunk: int) -> None:  # noqa: ANN001
    """The chunks' feed and length kept sparse while a program is read give back the very
    values the moves were made with, whatever was moved or dropped in between: the store is
    that of plain chunks, bit for bit (NaN, -0.0 and every float feed included)."""
    import planner.core.movestore as movestore

    sparse = _run_steps(steps, chunk)
    made = movestore._sparse_feed, movestore._sparse_length
    # nothing kept sparse: the plain chunks of before
    movestore._sparse_feed, movestore._sparse_length = (lambda feed: feed), (lambda length, _e, _b: length)
    try:
        plain = _run_steps(steps, chunk)
    finally:
        movestore._sparse_feed, movestore._sparse_length = made
    a, b = sparse.columns(), plain.columns()
    for name in ("start", "end", "line", "kind", "feed", "length", "exact_stop"):
        x, y = np.asarray(getattr(a, name)), np.asarray(getattr(b, name))
        assert x.dtype == y.dtype and x.shape == y.shape, name
        assert x.tobytes() == y.tobytes(), name


def test_a_raster_s_chunks_hold_no_feed_or_length_a_move() -> None:
    """Reading a CAM raster, the chunks done with keep their feeds as runs and their lengths
    as the ends give them: under a byte a move for both, not 16."""
    from planner.core.packed import straight_lengths

    buf = MoveBuffer([0.0, 0.0, 0.0])
    ends = np.zeros((100_000, 3))
    ends[:, 0] = np.arange(1, 100_001) * 0.1
    ends[:, 1] = np.sin(np.arange(100_000))
    for k in range(0, 100_000, 10_000):
        piece = ends[k:k + 10_000]
        buf.extend(piece, np.arange(k + 1, k + 10_001), np.full(10_000, _KIND_LINE), np.full(10_000, 1200.0),
                   straight_lengths(np.vstack((buf.last_end(), piece))), False)
    done = buf._chunks[:-1]
    held = sum(c[3].nbytes + c[4].rows.nbytes + c[4].values.nbytes for c in done)
    assert len(done) == 9 and held < 9 * 10_000
