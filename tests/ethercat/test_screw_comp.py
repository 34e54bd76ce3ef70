"""Leadscrew compensation: the table file read as LinuxCNC's COMP_FILE (types 0 and 1, every
malformed line refused at its line), its curve (through every line, twice continuously
differentiable, its derivative bounds true), and the 1 ms loop sending nominal + curve +
take-up to the drives: equal to nominal + table at every sample outside a take-up, every
sample of the sum within the axis' limits, the actual position reported nominal."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from bench.stepped import enabled as enabled_worker
from ethercat.bus import DriveSpec
from ethercat.errors import ConfigurationError
from ethercat.screw_comp import MAX_CORRECTION, CompCurve, ScrewComp, read_comp_file, take_up_limits
from ethercat.worker import CompSpec, CyclicWorker, WorkerConfig
from ethercat.worker.compensation import REVERSAL, Compensation
from ethercat.worker.handwheel import Follower

TS = 0.001
TRAVEL = (-50.0, 250.0)
RATED = (40.0, 1500.0, 30_000.0)            # the axis' own limits (mm/s, mm/s^2, mm/s^3)
SHARE = 0.15                                 # what the compensation keeps of them
HOME_OFFSET = 7.25                           # machine position = set-point - this


def _file(tmp_path: Path, text: str) -> Path:
    p = tmp_path / "x.comp"
    p.write_text(text)
    return p


# ------------------------------------------------------------------------------ the file
def test_type_0_holds_actual_positions_and_type_1_the_corrections(tmp_path: Path) -> None:
    """LinuxCNC's two formats: type 0 (nominal, where the axis got to moving up, moving down)
    is corrected by nominal - actual; type 1 carries the corrections as they are. Comments and
    blank lines are allowed."""
    p = _file(tmp_path, "# X axis, laser 2026-11\n0 0.002 -0.003\n\n100 99.990 99.985  # mid\n"
                        "200 200.004 199.996\n")
    t0 = read_comp_file(p, 0, TRAVEL)
    assert t0.nominal == (0.0, 100.0, 200.0)
    assert t0.forward.y == pytest.approx((-0.002, 0.010, -0.004), abs=1e-12)
    assert t0.reverse.y == pytest.approx((0.003, 0.015, 0.004), abs=1e-12)
    t1 = read_comp_file(_file(tmp_path, "0 0.002 -0.003\n100 0.01 -0.01\n"), 1, TRAVEL)
    assert t1.forward.y == (0.002, 0.01) and t1.reverse.y == (-0.003, -0.01)
    assert t1.forward(50.0) == pytest.approx(0.006) and t1.reverse(0.0) == -0.003


@pytest.mark.parametrize(("text", "line", "words"), [
    ("0 0 0\n10 0.001\n", 2, "expected three numbers"),
    ("0 0 0\n10 0.001 x\n", 2, "expected three numbers"),
    ("0 0 0\n10 0 0\n10 0 0\n", 3, "not above 10 on line 2"),
    ("0 0 0\n20 0 0\n# note\n15 0 0\n", 4, "not above 20 on line 2"),
    ("0 0 0\n300 0 0\n", 2, "outside the axis' travel -50 .. 250"),
    ("0 0 0\n10 0 1.5\n", 2, "reverse correction 1.5 is beyond"),
    ("0 0 0\n10 nan 0\n", 2, "expected three numbers"),
])
def test_a_malformed_table_is_refused_at_its_line(tmp_path: Path, text: str, line: int, words: str) -> None:
    p = _file(tmp_path, text)
    with pytest.raises(ConfigurationError) as err:
        read_comp_file(p, 1, TRAVEL)
    assert f"{p}:{line}:" in str(err.value) and words in str(err.value)


def test_an_empty_table_a_missing_file_and_a_wrong_type_are_refused(tmp_path: Path) -> None:
    with pytest.raises(ConfigurationError, match="has no lines"):
        read_comp_file(_file(tmp_path, "# nothing\n\n"), 0, TRAVEL)
    with pytest.raises(ConfigurationError, match="cannot read"):
        read_comp_file(tmp_path / "none.comp", 0, TRAVEL)
    with pytest.raises(ConfigurationError, match="COMP_FILE_TYPE 2"):
        read_comp_file(_file(tmp_path, "0 0 0\n"), 2, TRAVEL)


def test_a_table_whose_end_slope_runs_beyond_the_bound_over_the_travel_is_refused(tmp_path: Path) -> None:
    """Beyond its last line the curve goes on along its end slope: over a travel far past the
    table that would exceed the bound, and the file says how to fix it."""
    p = _file(tmp_path, "0 0 0\n1 0.02 0.02\n")
    with pytest.raises(ConfigurationError, match="add lines up to the travel's ends"):
        read_comp_file(p, 1, (0.0, 100.0))


# ------------------------------------------------------------------------------ the curve
@settings(max_examples=60, deadline=None)
@given(scale=st.sampled_from([0.001, 1.0, 1000.0]),
       gaps=st.lists(st.floats(0.5, 40.0), min_size=1, max_size=12),
       ys=st.lists(st.floats(-0.05, 0.05), min_size=13, max_size=13))
def test_the_curve_goes_through_every_line_and_its_bounds_hold(scale: float, gaps: list[float],
                                                               ys: list[float]) -> None:
    """At the scales x0.001 to x1000: the curve takes each line's value, its slope and
    curvature agree on both sides of every line (C2), and its sampled first, second and third
    derivatives stay within ``bounds``."""
    x = np.concatenate([[0.0], np.cumsum(gaps)]) * scale
    y = np.array(ys[:len(x)]) * scale
    c = CompCurve.through(x, y)
    for xk, yk in zip(x, y):
        assert c(float(xk)) == pytest.approx(float(yk), abs=1e-12 * scale)
    d1, d2, d3 = c.bounds(float(x[0]) - 5 * scale, float(x[-1]) + 5 * scale)
    h = 1e-4 * scale
    for xk in x:
        left = [c(float(xk) - k * h) for k in range(4)][::-1]
        right = [c(float(xk) + k * h) for k in range(4)]
        for seq in (left, right):
            assert abs(seq[1] - seq[0]) / h <= d1 * (1 + 1e-6) + 1e-9
        # slope and curvature from both sides agree to the step's order
        assert abs((left[3] - left[2]) - (right[1] - right[0])) / h <= 3 * d2 * h + 1e-9 * scale
    xs = np.linspace(float(x[0]) - 5 * scale, float(x[-1]) + 5 * scale, 4001)
    vals = np.array([c(float(v)) for v in xs])
    dx = float(xs[1] - xs[0])
    assert np.abs(np.diff(vals)).max() / dx <= d1 * (1 + 1e-6) + 1e-12
    assert np.abs(np.diff(vals, 2)).max() / dx**2 <= d2 * (1 + 1e-3) + 1e-6 / scale
    if len(x) > 2:
        assert np.abs(np.diff(vals, 3)).max() / dx**3 <= d3 * (1 + 1e-3) + 1e-3 / scale**2


def test_backlash_is_plus_and_minus_half_of_it_and_bounded() -> None:
    b = ScrewComp.backlash(0.02)
    assert b.forward(123.0) == 0.01 and b.reverse(-5.0) == -0.01
    assert b.bounds(*TRAVEL) == (0.0, 0.0, 0.0, 0.0)
    with pytest.raises(ConfigurationError):
        ScrewComp.backlash(MAX_CORRECTION * 2)


def test_a_table_too_steep_for_the_reserve_is_refused(tmp_path: Path) -> None:
    """Lines 1 mm apart with 0.5 mm between them: at full speed the table alone would move
    the axis faster than the reserve allows; the message names the file and what to do."""
    p = _file(tmp_path, "0 0 0\n1 0.5 0.5\n2 0 0\n3 0.5 0.5\n4 0 0\n")
    comp = read_comp_file(p, 1, (0.0, 4.0))
    with pytest.raises(ConfigurationError, match="x.comp: at full speed .* raise comp_reserve"):
        take_up_limits(comp, (0.0, 4.0), RATED, SHARE, TS)


@settings(max_examples=30, deadline=None)
@given(scale=st.sampled_from([0.001, 1.0, 1000.0]), seed=st.integers(0, 2**32 - 1),
       backlash=st.floats(0.0, 0.05), ripple=st.floats(0.0, 0.01))
def test_any_table_and_any_moves_keep_the_limits_at_any_scale(scale: float, seed: int, backlash: float,
                                                              ripple: float) -> None:
    """A random table (backlash plus a random ripple on either column) and random jerk-limited
    moves with reversals, at the scales x0.001 to x1000: what the drive gets (path + table +
    take-up) keeps the axis' own limits at every sample, and is exactly path + table once every
    take-up has ended."""
    rng = np.random.default_rng(seed)
    lo, hi = 0.0, 300.0 * scale
    x = np.linspace(lo, hi, 8)
    fwd = (backlash / 2 + ripple * rng.uniform(-1, 1, 8)) * scale
    rev = (-backlash / 2 + ripple * rng.uniform(-1, 1, 8)) * scale
    comp = ScrewComp(CompCurve.through(x, fwd), CompCurve.through(x, rev), "random")
    rated = tuple(r * scale for r in RATED)
    take = take_up_limits(comp, (lo, hi), rated, SHARE, TS)     # (gentle enough: never refused)
    loop = Compensation((CompSpec(0, comp, take),), 1, TS, 8)
    f = Follower(TS)
    vp, ap, jp = ((1.0 - SHARE) * r for r in rated)
    f.start(hi / 2, vp, ap, jp)
    path = [hi / 2]
    for _ in range(6):
        near = path[-1] + float(rng.normal(0, 0.2 * scale))
        target = float(rng.uniform(lo, hi)) if rng.random() < 0.6 else near
        path += [f.step(min(max(target, lo), hi)) for _ in range(int(rng.integers(5, 1500)))]
    path += [f.step(path[-1]) for _ in range(4000)]
    ref, out = np.zeros(1), np.zeros(1)
    assert loop.switch(0, True, 0.0)
    sent = []
    for k, q in enumerate(path):
        ref[0] = q
        loop.command(ref, out, k % 8)
        sent.append(float(out[0]))
    y = np.array(sent)
    v, a, j = _sampled(y)
    tol = 8.0 * np.finfo(float).eps * hi / TS**3
    assert v <= rated[0] * (1 + 1e-9) and a <= rated[1] * (1 + 1e-9) + tol * TS, (v, a)
    assert j <= rated[2] * (1 + 1e-6) + tol, j
    last = path[-1]
    up = loop.axes[0].up
    assert y[-1] == last + (comp.forward(last) if up else comp.reverse(last))


# ------------------------------------------------------------------------------ in the loop
def _table(tmp_path: Path) -> ScrewComp:
    lines = [f"{x:g} {0.004 * np.sin(x / 40.0) + 0.006:.6f} {0.004 * np.sin(x / 40.0) - 0.008:.6f}"
             for x in range(-50, 251, 25)]
    return read_comp_file(_file(tmp_path, "\n".join(lines) + "\n"), 1, TRAVEL)


def _worker(comp: ScrewComp) -> tuple[CyclicWorker, CompSpec]:
    spec = CompSpec(0, comp, take_up_limits(comp, TRAVEL, RATED, SHARE, TS))
    cfg = WorkerConfig((DriveSpec(0, "X"), DriveSpec(1, "Z", direction=-1)), mode="manual",
                       compensation=(spec,))
    return enabled_worker(cfg), spec


def _path(rng: np.random.Generator, start: float, moves: int) -> np.ndarray:
    """Jerk-limited moves to random targets (within the share of the limits motion has), with
    random pauses: many reversals, some right after a stop."""
    v, a, j = ((1.0 - SHARE) * x for x in RATED)
    f = Follower(TS)
    f.start(start, v, a, j)
    out: list[float] = []
    for _ in range(moves):
        target = float(rng.uniform(TRAVEL[0] + HOME_OFFSET + 1, TRAVEL[1] + HOME_OFFSET - 1))
        if rng.random() < 0.5:
            target = out[-1] + float(rng.uniform(-0.5, 0.5)) if out else start
        hold = int(rng.integers(20, 2500))
        out += [f.step(target) for _ in range(hold)]
    out += [f.step(out[-1]) for _ in range(3 * f.n + 600)]      # and every take-up ended
    return np.array(out)


def _run(w: CyclicWorker, path: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The path through the loop, one cycle at a time: set-points (nominal), what was sent
    (units) and the target counts."""
    loop = w._loop
    assert loop is not None and loop.bus is not None
    q = np.zeros((len(path), 2))
    q[:, 0] = path
    refs, cmds, counts = [], [], []
    pushed = 0
    for _ in range(len(path) + 5):
        if pushed < len(path):
            pushed += w.push(q[pushed:pushed + 1000])
        w.step(1)
        refs.append(loop.ref[0])
        cmds.append(loop.cmd[0])
        counts.append(int(loop.bus.target_position[0]))
    return np.array(refs), np.array(cmds), np.array(counts)


def _sampled(y: np.ndarray) -> tuple[float, float, float]:
    v = np.diff(y) / TS
    a = np.diff(v) / TS
    j = np.diff(a) / TS
    return tuple(float(np.abs(x).max(initial=0.0)) for x in (v, a, j))  # type: ignore[return-value]


@pytest.mark.parametrize("seed", range(4))
def test_the_drive_gets_nominal_plus_table_and_reversals_keep_the_limits(tmp_path: Path, seed: int) -> None:
    """Random moves of a homed, compensated axis: every sample sent is the set-point plus the
    table's correction for the direction it last moved, except while a reversal's step is taken
    up; the take-up ends; every sample of what the drive gets (path + table + take-up) is
    within the axis' own limits; and the actual position read back is nominal."""
    comp = _table(tmp_path)
    w, spec = _worker(comp)
    try:
        start = float(w.snapshot().reference_position[0])
        assert w.compensate(0, True, HOME_OFFSET)
        rng = np.random.default_rng(seed)
        ref, cmd, counts = _run(w, _path(rng, start, 12))
        # the counts are what was sent, rounded to the drive's resolution
        assert np.array_equal(counts, np.rint(cmd * 10_000.0).astype(np.int64))
        # what the table says, by the direction of the last move (standing keeps it)
        # none until the first move (before it the worker's set-point stood at start)
        # (a reversal counts once it is more than the rounding: REVERSAL)
        moved = np.zeros(len(ref), dtype=bool)
        up = np.ones(len(ref), dtype=bool)
        before, turn, going = start, start, None
        for k in range(len(ref)):
            q = float(ref[k])
            if going is None:
                if q != before:
                    going, turn = q > before, q
            elif (q - turn > 0) == going:
                turn = q
            elif abs(q - turn) > REVERSAL * (1 + abs(q)):
                going, turn = not going, q
            moved[k], up[k] = going is not None, bool(going)
            before = q
        x = ref - HOME_OFFSET
        table = np.where(up, [comp.forward(v) for v in x], [comp.reverse(v) for v in x])
        take = cmd - (ref + np.where(moved, table, 0.0))
        # a take-up of the first move's step and one per reversal; outside them exactly the table
        settle = spec_cycles(spec)
        flips = np.flatnonzero((up[1:] != up[:-1]) | (moved[1:] != moved[:-1])) + 1
        if moved[0]:
            flips = np.r_[0, flips]
        inside = np.zeros(len(ref), dtype=bool)
        for k in flips:
            inside[k:k + settle] = True
        assert len(flips) >= 3
        assert (~inside).sum() > len(ref) // 3 and np.abs(take[~inside]).max() <= 1e-12
        assert np.abs(take[-1]) == 0.0
        v, a, j = _sampled(cmd)
        assert v <= RATED[0] * (1 + 1e-9) and a <= RATED[1] * (1 + 1e-9), (v, a)
        assert j <= RATED[2] * (1 + 1e-6), j
        snap = w.snapshot()
        assert snap.compensation_on[0] and not snap.compensation_on[1]
        assert snap.compensation[0] == pytest.approx(float(cmd[-1] - ref[-1]), abs=1e-12)
        w.step(10)
        assert abs(float(w.snapshot().actual_position[0]) - float(ref[-1])) <= 1.5e-4   # nominal
    finally:
        w.stop()


def spec_cycles(spec: CompSpec) -> int:
    """An upper bound of a take-up's length in cycles for steps up to 0.05 mm."""
    v, a, j = spec.take_up
    d = 0.05
    return int((d / v + 2 * v / a + 2 * a / j + 2 * np.sqrt(d / a)) / TS) + int(2 * a / (j * TS)) + 10


def _steps(w: CyclicWorker, n: int) -> np.ndarray:
    loop = w._loop
    assert loop is not None
    out = []
    for _ in range(n):
        w.step(1)
        out.append(float(loop.cmd[0]))
    return np.array(out)


def test_no_correction_before_the_first_move_and_homing_reads_the_table_elsewhere(tmp_path: Path) -> None:
    """Standing since start: no direction yet, no correction. The first move up
    takes up the forward correction of the table's first line (unhomed: it is read there);
    homed, it is read at the machine position, and the step between the two is taken up
    within the limits, landing exactly; unhomed again, it is read where the axis stands, so
    nothing moves; the drive's set-point for the other axis never changes."""
    comp = _table(tmp_path)
    w, _spec = _worker(comp)
    try:
        loop = w._loop
        assert loop is not None
        start = float(loop.ref[0])
        assert float(_steps(w, 100)[-1]) == start                       # no direction yet
        f = Follower(TS)
        f.start(start, *((1.0 - SHARE) * x for x in RATED))
        move = [f.step(start + 0.01) for _ in range(400)]
        assert move[-1] == start + 0.01
        assert w.push(np.array([[q, 0.0] for q in move])) == len(move)
        series = np.concatenate([[start], _steps(w, 1500)])
        ref = start + 0.01
        assert series[-1] == ref + comp.forward(comp.nominal[0])       # unhomed: its first line
        assert w.compensate(0, True, HOME_OFFSET)
        series = np.concatenate([series, _steps(w, 1500)])
        want = ref + comp.forward(ref - HOME_OFFSET)
        assert series[-1] == want
        v, a, j = _sampled(series)
        assert v <= RATED[0] and a <= RATED[1] and j <= RATED[2] * (1 + 1e-6)
        assert w.compensate(0, False)
        assert float(_steps(w, 500)[-1]) == want and not w.snapshot().compensation_on[0]
        assert float(loop.cmd[1]) == float(loop.ref[1])
        assert not w.compensate(1, True, 0.0)        # Z has none
    finally:
        w.stop()


def test_rounding_in_the_last_digits_is_no_reversal() -> None:
    """A set-point that goes back by the rounding of a position (1e-13 mm at 50 mm) keeps the
    direction: no backlash is taken up; back by a micrometre, it is a reversal."""
    loop = Compensation((CompSpec(0, ScrewComp.backlash(0.02), (5.0, 200.0, 4000.0)),), 1, TS, 8)
    ref, out = np.zeros(1), np.zeros(1)
    sent = []
    for q in [50.0 + 0.01 * k for k in range(100)] + [50.99 - 1e-13] * 400 + [50.989] * 400:
        ref[0] = q
        loop.command(ref, out, 0)
        sent.append(float(out[0]) - q)
    assert sent[499] == pytest.approx(0.01, abs=1e-12)     # still up after the rounding
    assert sent[-1] == pytest.approx(-0.01, abs=1e-12)     # down after the micrometre


def test_a_worker_without_compensation_sends_the_set_points_unchanged() -> None:
    w = CyclicWorker(WorkerConfig((DriveSpec(0, "X"),), mode="manual"))
    w.start()
    try:
        w.step(3)
        w.enable()
        w.step(20)
        loop = w._loop
        assert loop is not None
        start = float(loop.ref[0])
        q = (start + np.linspace(0.0, 1.0, 300)).reshape(-1, 1)
        w.push(q)
        w.step(300)
        assert float(loop.cmd[0]) == float(loop.ref[0]) == float(q[-1, 0])
        assert not w.compensate(0, True, 0.0)
    finally:
        w.stop()
