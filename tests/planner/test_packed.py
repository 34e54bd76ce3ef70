"""Packed float columns give back exactly the values they were made from, and a CAM
program's moves hold no float a move for their feed and length."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from bench.bench_big import raster
from planner.core.movestore import MoveStore
from planner.core.packed import ColumnPacker, DenseColumn, DerivedLength, RunColumn, straight_lengths
from planner.core.program import MoveKind
from tests.planner.motion_programs import parse


def _same_bits(a: np.ndarray, b: np.ndarray) -> bool:
    return a.shape == b.shape and a.astype(float).tobytes() == b.astype(float).tobytes()


def _cuts(draw, n: int) -> list[int]:
    """Where a column of n rows is cut into the pieces it is given in."""
    cuts = sorted(draw(st.lists(st.integers(0, n), max_size=6)))
    return [0, *cuts, n]


def _check_column(column, values: np.ndarray, draw) -> None:
    n = len(values)
    assert len(column) == n
    assert _same_bits(column.array(), values)
    for i in draw(st.lists(st.integers(0, max(0, n - 1)), max_size=5)) if n else []:
        assert np.float64(column.at(i)).tobytes() == values[i].tobytes()
    a = draw(st.integers(0, n))
    b = draw(st.integers(a, n))
    part = column.slice(a, b)
    assert _same_bits(part.array(), values[a:b])
    if b > a:
        c = draw(st.integers(0, b - a))
        assert _same_bits(part.slice(c, b - a).array(), values[a + c:b])
        assert np.float64(part.at(b - a - 1)).tobytes() == values[b - 1].tobytes()


@settings(max_examples=200, deadline=None)
@given(st.data())
def test_runs_give_back_every_value_bit_for_bit(data) -> None:
    palette = data.draw(st.lists(st.floats(allow_nan=True, allow_infinity=True, width=64), min_size=1,
                                 max_size=4))
    n = data.draw(st.integers(0, 400))
    run_lengths = data.draw(st.lists(st.integers(1, 120), min_size=1, max_size=40))
    values = np.array([palette[(k // max(1, run_lengths[k % len(run_lengths)])) % len(palette)]
                       for k in range(n)], float)
    packer = ColumnPacker(n)
    cuts = _cuts(data.draw, n)
    for a, b in zip(cuts, cuts[1:]):
        packer.add(values[a:b])
    column = packer.column()
    _check_column(column, values, data.draw)


def test_runs_keep_the_bits_of_signed_zeros_and_nans() -> None:
    values = np.array([0.0, -0.0, -0.0, np.nan, np.nan, 0.0, 5.0])
    packer = ColumnPacker(len(values))
    packer.add(values[:2])
    packer.add(values[2:])
    column = packer.column()
    assert isinstance(column, RunColumn) and len(column.values) == 5
    assert _same_bits(column.array(), values)
    assert [np.float64(column.at(i)).tobytes() for i in range(7)] == [v.tobytes() for v in values]


def test_runs_are_packed_and_many_changes_fall_back_to_an_array() -> None:
    few = np.repeat([1000.0, np.inf, 25.0], 10_000)
    packer = ColumnPacker(len(few))
    for a in range(0, len(few), 4096):
        packer.add(few[a:a + 4096])
    packed = packer.column()
    assert isinstance(packed, RunColumn) and packed.nbytes == 3 * 16
    rng = np.random.default_rng(3)
    many = rng.uniform(1.0, 100.0, 30_000)       # inverse time: a feed for every move
    packer = ColumnPacker(len(many))
    for a in range(0, len(many), 4096):
        packer.add(many[a:a + 4096])
    dense = packer.column()
    assert isinstance(dense, DenseColumn) and _same_bits(dense.array(), many)


@settings(max_examples=200, deadline=None)
@given(st.data())
def test_lengths_give_back_every_value_bit_for_bit(data) -> None:
    n = data.draw(st.integers(0, 300))
    d = data.draw(st.integers(1, 5))
    scale = data.draw(st.sampled_from([1e-3, 1.0, 1e3]))
    rng = np.random.default_rng(data.draw(st.integers(0, 2**32 - 1)))
    positions = np.round(rng.uniform(-100, 100, (n + 1, d)), 3) * scale
    lengths = straight_lengths(positions)
    other = data.draw(st.lists(st.integers(0, max(0, n - 1)), max_size=n)) if n else []
    lengths[other] = rng.uniform(0.0, 50.0, len(other))    # arcs: not the chord
    packer = ColumnPacker(n, positions)
    cuts = _cuts(data.draw, n)
    for a, b in zip(cuts, cuts[1:]):
        packer.add(lengths[a:b])
    _check_column(packer.column(), lengths, data.draw)


def test_straight_lengths_do_not_depend_on_the_rows_beside() -> None:
    rng = np.random.default_rng(5)
    positions = rng.uniform(-1e3, 1e3, (5_001, 3))
    whole = straight_lengths(positions)
    one_by_one = np.array([straight_lengths(positions[i:i + 2])[0] for i in range(5_000)])
    assert _same_bits(whole, one_by_one)
    column = DerivedLength(positions, np.zeros(0, np.int64), np.zeros(0), 0, 5_000)
    assert _same_bits(column.array(), whole)


def test_a_cam_raster_keeps_no_float_a_move_for_feed_and_length() -> None:
    program = parse(raster(20_000, 0.1, 20.0))
    moves = program.moves
    assert isinstance(moves, MoveStore) and len(moves) > 19_000
    # positions (3 floats), line, kind and exact stop: 30 bytes a move; feed and length packed
    assert moves.nbytes < 31 * len(moves), moves.nbytes / len(moves)
    cols = moves.columns()
    chords = [math.dist(a, b) for a, b in zip(moves.positions[:-1], moves.positions[1:])]
    np.testing.assert_allclose(cols.length, chords, rtol=4.5e-16, atol=0)
    rapid = cols.kind == int(MoveKind.RAPID)
    assert rapid.sum() == 2 and np.all(cols.feed[rapid] == np.inf)
    assert np.all(cols.feed[~rapid] == 3000.0 / 60.0)     # the program's F3000
