"""The sample programs shipped in resources/programs read as their comments say."""

from __future__ import annotations

import math

import numpy as np
import pytest

from planner.core.machine import load_machine
from planner.core.program import EventKind, MoveKind
from planner.gcode.interpreter import parse_file
from resources import PROGRAMS, shipped_machine


def load(name: str):
    path = PROGRAMS / name
    if not path.is_file():
        pytest.skip(f"{path} not present")
    return parse_file(path)


def test_every_sample_parses():
    files = sorted(PROGRAMS.glob("*.nc"))
    if not files:
        pytest.skip("no sample programs")
    paper = load_machine(str(shipped_machine("paper_yzca")))
    for f in files:
        # the tyre mould is the paper's Y-Z-C-A machine's, the others the default mill's
        program = parse_file(f, paper if f.name == "tyre_mould.nc" else None)
        assert program.moves and program.events[-1].kind is EventKind.END


def test_fig7_five_g02_r_arcs_then_g01():
    p = load("fig7_circle.nc")
    feeds = [m for m in p.moves if m.kind is not MoveKind.RAPID]
    assert [m.kind for m in feeds] == [MoveKind.ARC] * 5 + [MoveKind.LINE]
    for m in feeds[:5]:
        assert m.arc.plane == "XY" and m.arc.sweep_rad < 0 and m.arc.radius_start_mm == pytest.approx(10)


def test_fig9_six_g03_half_circles_descending():
    p = load("fig9_helix.nc")
    arcs = [m for m in p.moves if m.arc is not None]
    assert len(arcs) == 6
    for m in arcs:
        assert m.arc.sweep_rad == pytest.approx(math.pi) and m.arc.rise_mm < 0
    z = [m.end[2] for m in arcs]
    assert np.all(np.diff(z) < 0)


def test_pocket_ijk_arcs_and_helical_entry():
    p = load("pocket.nc")
    arcs = [m for m in p.moves if m.arc is not None]
    assert arcs and all(m.arc.sweep_rad > 0 for m in arcs)
    assert any(m.arc.rise_mm < 0 for m in arcs)
