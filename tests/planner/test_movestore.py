"""A program's moves kept as columns read as the Move objects they stand for."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from planner.movestore import MoveBuffer, MoveStore
from planner.movetable import MoveTable
from planner.program import MoveKind
from planner.softlimits import move_bounds_table
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


def test_tables_and_bounds_from_columns_equal_those_from_move_objects(program):
    objects = replace(program, moves=tuple(program.moves))
    a = MoveTable.from_moves(program.moves[3:40], 3)
    b = MoveTable.from_moves(objects.moves[3:40], 3)
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
    from planner.blend import blend_program, blend_report
    from tests.planner.motion_programs import paper_machine

    text = "G64 P0.05\nG1 F6000\n" + "".join(f"X{i * 3} Y{(i % 2) * 0.5}\n" for i in range(1, 30))
    machine = paper_machine()
    blended = blend_program(parse(text, machine), machine, only_where_quicker=False)
    store = replace(blended, moves=MoveStore.from_moves(tuple(blended.moves), blended.start_position))
    a, b = blend_report(blended), blend_report(store)
    assert a.blends > 10 and a == b
