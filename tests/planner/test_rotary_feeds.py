"""Rotary axes run as LinuxCNC 2.9 runs them (docs "Feed Rate", RS274/NGC 2.1.2.5), on the
paper's Y-Z-C-A machine:

- a move with a linear axis runs F along the linear distance, the rotary axes following;
- a move of rotary axes alone runs F in degrees per minute along sqrt(dA^2 + dC^2);
- G93 makes a block take 1/F minutes;
- a rapid moves each axis up to its own limit (the linear path at ``rapid_mm_s``);

each as fast as the path and axis limits allow, and within every limit on the samples. A move's
planned time is the rule's time plus at most its ramps (accelerating and braking)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from planner.core.machine import MachineSpec, load_machine
from planner.gcode.interpreter import parse_program
from planner.motion.plan import plan_program
from resources import shipped_machine

MACHINE = load_machine(str(shipped_machine("paper_yzca")))
AXES = MACHINE.axis_names          # Y Z C A


def rule_time_s(start: np.ndarray, end: np.ndarray, g: int, f: float, inverse: bool, m: MachineSpec) -> float:
    """LinuxCNC's time for one block from ``start`` to ``end`` (machine units), unramped."""
    d = np.abs(end - start)
    rotary = np.array([a.rotary for a in m.axes])
    v_axis = np.array([a.v_max for a in m.axes])
    axis_floor = float(np.max(d / v_axis))            # no axis faster than its own limit
    lin, rot = math.hypot(*d[~rotary]), math.hypot(*d[rotary])
    lim = m.limits
    if g == 0:
        path = lin / lim.rapid_mm_s if lin > 0 else rot / lim.rapid_deg_s
        return max(path, axis_floor)
    if inverse:
        programmed = 60.0 / f
    else:
        programmed = (lin if lin > 0 else rot) / (f / 60.0)
    cap = lin / lim.v_max_mm_s if lin > 0 else rot / lim.v_max_deg_s
    return max(programmed, cap, axis_floor)


def ramp_allowance_s(start: np.ndarray, end: np.ndarray, m: MachineSpec) -> float:
    """What accelerating from rest and braking to rest adds at most: twice a jerk-limited ramp
    to the fastest speed an axis may have, by the slowest acceleration and jerk of any axis
    (and the path's)."""
    a = min(min(x.a_max for x in m.axes), m.limits.a_max_mm_s2)
    j = min(min(x.j_max for x in m.axes), m.limits.j_max_mm_s3)
    v = max(x.v_max for x in m.axes)
    return 2.0 * (v / a + a / j) + 0.01


@pytest.mark.parametrize("block, want_s", [
    ("G1 C360 F3600", 6.0),            # 60 deg/s along C alone
    ("G1 A90 C360 F3600", 6.185),      # sqrt(90^2 + 360^2) = 371.1 deg at 60 deg/s
    ("G93 G1 C360 F10", 6.0),          # 1/10 min
    ("G0 C360", 4.0),                  # C at its own 90 deg/s
    ("G1 A-90 F5400", 1.0),            # 90 deg/s: A's own limit
    ("G1 Y100 C360 F1200", 5.0),       # 20 mm/s along Y; C follows (72 deg/s)
])
def test_the_issue_table(block: str, want_s: float) -> None:
    prog = parse_program(f"G21 G90\n{block}\nM2\n", machine=MACHINE)
    plan = plan_program(prog, MACHINE)
    m = prog.moves[0]
    assert rule_time_s(np.asarray(m.start), np.asarray(m.end), 0 if block.startswith("G0") else 1,
                       float(block.split("F")[-1]) if "F" in block else 0.0, "G93" in block,
                       MACHINE) == pytest.approx(want_s, abs=0.01)
    assert want_s <= plan.cycle_time_s <= want_s + ramp_allowance_s(np.asarray(m.start), np.asarray(m.end),
                                                                     MACHINE)


@st.composite
def blocks(draw: st.DrawFn) -> tuple[str, int, float, bool]:
    """One block: G0 / G1 (G94) / G93 G1, moving some of Y Z C A."""
    g = draw(st.sampled_from([0, 1, 1, 93]))
    words = []
    for axis, span in (("Y", 200.0), ("Z", 100.0), ("C", 720.0), ("A", 100.0)):
        if draw(st.booleans()):
            words.append(f"{axis}{draw(st.floats(-span, span, allow_nan=False)):.3f}")
    if not words:
        words.append(f"C{draw(st.floats(1.0, 720.0)):.3f}")
    if g == 0:
        return "G0 " + " ".join(words), 0, 0.0, False
    if g == 93:
        f = draw(st.floats(1.0, 120.0))
        return "G93 G1 " + " ".join(words) + f" F{f:.4f}", 1, round(f, 4), True
    f = draw(st.floats(60.0, 6000.0))
    return "G94 G1 " + " ".join(words) + f" F{f:.3f}", 1, round(f, 3), False


@settings(max_examples=60, deadline=None)
@given(st.lists(blocks(), min_size=1, max_size=6))
def test_every_block_takes_linuxcncs_time_within_its_ramps_and_every_limit_holds(program) -> None:
    # G61: every block starts and ends at rest, so each one's time is its own
    text = "G21 G90 G61\n" + "\n".join(b for b, *_ in program) + "\nM2\n"
    prog = parse_program(text, machine=MACHINE)
    plan = plan_program(prog, MACHINE)
    seg = plan.segment
    t_move = plan.t1 - plan.t0
    by_line = {int(line): k for k, line in enumerate(seg.table.line)}
    for n, (_block, g, f, inverse) in enumerate(program, start=2):
        k = by_line.get(n)
        if k is None:                   # moved nothing (already there)
            continue
        start, end = seg.table.start[k], seg.table.end[k]
        want = rule_time_s(start, end, g, f, inverse, MACHINE)
        got = float(t_move[k])
        assert want - 1e-6 <= got <= want + ramp_allowance_s(start, end, MACHINE), (n, _block, want, got)
    report = plan.limit_report()
    assert not report.violations, report.violations
