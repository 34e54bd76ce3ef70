"""Program loading off the GUI thread: the "loading" activity, cycle start refused meanwhile,
a newer load supersedes an older one, a failed load unloads, the synchronous path for headless
use, and the GUI thread keeps ticking while a large program is checked."""

from __future__ import annotations

import math
import time
from pathlib import Path

from PySide6.QtCore import QTimer

from app.machine.controller import MachineController
from app.machine.model import MachineState

SHORT = "G0 X5 Y0\nG1 X20 F1800\nG3 X20 Y20 R10\nG1 X5\nM30\n"
BAD = "G0 X1\nG1 X2 Q5 F100\n"


def big_program(lines: int) -> str:
    """Rings of short G01 chords and G03 arcs inside the XYZ mill's travel (a finishing pass)."""
    out = ["G21 G17 G90 G94", "G0 X40 Y0 Z5", "G1 Z0 F600"]
    angle, radius, z = 0.0, 40.0, 0.0
    while len(out) < lines - 1:
        angle += math.radians(3.0)
        x, y = radius * math.cos(angle), radius * math.sin(angle)
        if len(out) % 4 == 0:
            out.append(f"G3 X{x:.4f} Y{y:.4f} R{radius:.4f} F1800")
        else:
            out.append(f"G1 X{x:.4f} Y{y:.4f} F1800")
        if angle >= 2 * math.pi:
            angle -= 2 * math.pi
            radius, z = radius * 0.999, z - 0.01
            out.append(f"G1 X{radius * math.cos(angle):.4f} Y{radius * math.sin(angle):.4f} Z{z:.4f}")
    out.append("M30")
    return "\n".join(out) + "\n"


def test_load_runs_in_the_background_and_refuses_cycle_start_meanwhile(qtbot, ctl: MachineController) -> None:
    loading: list[tuple[bool, str]] = []
    ctl.loadingChanged.connect(lambda on, name: loading.append((on, name)))
    with qtbot.waitSignal(ctl.programLoaded, timeout=10_000) as blocker:
        r = ctl.load_program(SHORT, name="short.nc")
        assert r  # accepted: being checked
        assert ctl.loading and ctl.loading_name == "short.nc"
        refused = ctl.cycle_start()
        assert not refused and "being checked" in refused.reason
        assert "being checked" in ctl.refusal("run_from_line")
        assert ctl.program_info is None
    assert blocker.args[0].name == "short.nc" and ctl.program_info is blocker.args[0]
    assert not ctl.loading and loading == [(True, "short.nc"), (False, "short.nc")]
    assert ctl.cycle_start() and ctl.state is MachineState.RUNNING


def test_a_newer_load_supersedes_an_older_one(qtbot, ctl: MachineController) -> None:
    loaded: list[str] = []
    errors: list[object] = []
    ctl.programLoaded.connect(lambda info: loaded.append(info.name))
    ctl.programErrors.connect(errors.append)
    assert ctl.load_program(big_program(3000), name="old.nc")
    assert ctl.load_program(SHORT, name="new.nc")
    qtbot.waitUntil(lambda: not ctl.loading, timeout=20_000)
    qtbot.wait(50)  # a late result of the old load would arrive now: it must be dropped
    assert loaded == ["new.nc"] and not errors
    assert ctl.program_info is not None and ctl.program_info.name == "new.nc"
    # a synchronous load supersedes one in flight as well
    assert ctl.load_program(big_program(3000), name="old2.nc")
    assert ctl.load_program(SHORT, name="sync.nc", wait=True)
    assert not ctl.loading
    qtbot.wait(50)
    assert loaded == ["new.nc", "sync.nc"] and ctl.program_info.name == "sync.nc"


def test_failed_background_load_unloads_the_previous_program(qtbot, ctl: MachineController) -> None:
    assert ctl.load_program(SHORT, wait=True) and ctl.program_info is not None
    with qtbot.waitSignal(ctl.programErrors, timeout=10_000) as blocker:
        assert ctl.load_program(BAD)  # accepted for checking; refused when checked
    assert [i.line for i in blocker.args[0]] == [2]
    assert ctl.program_info is None and not ctl.loading
    r = ctl.cycle_start()
    assert not r and r.reason == "no program loaded"
    r = ctl.wait_loaded()
    assert not r and "error" in r.reason


def test_wait_loaded_without_an_event_loop(ctl: MachineController) -> None:
    loaded: list[object] = []
    ctl.programLoaded.connect(loaded.append)
    assert ctl.load_program(SHORT)
    r = ctl.wait_loaded(20.0)
    assert r and ctl.program_info is not None and not ctl.loading and len(loaded) == 1
    from PySide6.QtCore import QCoreApplication

    QCoreApplication.processEvents()  # the queued result arrives later: applied once only
    assert len(loaded) == 1
    assert ctl.load_program(SHORT, timeout_s=20.0)  # start and wait in one call


def test_unreadable_file_fails_at_once(ctl: MachineController) -> None:
    loading: list[bool] = []
    ctl.loadingChanged.connect(lambda on, _name: loading.append(on))
    assert ctl.load_program(SHORT)
    r = ctl.load_program(Path("/nonexistent/dir/prog.nc"))  # supersedes the one in flight
    assert not r and "cannot read" in r.reason and not ctl.loading and ctl.program_info is None
    assert loading == [True, False]


def test_gui_thread_keeps_ticking_during_a_large_load(qtbot, ctl: MachineController) -> None:
    """A 6,000-line program is checked (parse, soft limits, plan) while a 10 ms timer in the
    GUI thread keeps firing: it ticks during the load and never stalls long (generous bound:
    the machine is a shared 2-core box; typical longest gap ~30 ms, a synchronous load ~0.2 s
    with no tick at all)."""
    text = big_program(6000)
    ticks: list[float] = []
    timer = QTimer()
    timer.setInterval(10)
    timer.timeout.connect(lambda: ticks.append(time.perf_counter()))
    timer.start()
    qtbot.wait(50)
    started = time.perf_counter()
    assert ctl.load_program(text, name="big.nc")
    returned = time.perf_counter()
    qtbot.waitUntil(lambda: not ctl.loading, timeout=60_000)
    finished = time.perf_counter()
    timer.stop()
    assert ctl.program_info is not None and ctl.program_info.move_count > 5000
    during = [t for t in ticks if started <= t <= finished]
    stamps = [max(t for t in ticks if t < started), *during, finished]
    max_gap = max(b - a for a, b in zip(stamps, stamps[1:]))
    assert returned - started < 0.1, f"load_program blocked for {returned - started:.3f} s"
    assert len(during) >= 3, f"only {len(during)} ticks in a {finished - started:.3f} s load"
    assert max_gap < 0.25, f"GUI thread stalled {1000 * max_gap:.0f} ms (load {finished - started:.3f} s)"


def test_vectorised_bounds_table_matches_move_bounds() -> None:
    """The per-move table (NumPy over lines, exact extremes for arcs) equals ``move_bounds``
    move by move, and the soft-limit check built on it reports what a per-move loop finds."""
    import numpy as np

    from planner.core.machine import load_machine
    from planner.gcode.interpreter import parse_program
    from planner.geometry.softlimits import (
        check_program,
        move_bounds,
        move_bounds_pieces,
        move_bounds_table,
        program_bounds,
    )
    from resources import shipped_machine

    machine = load_machine(shipped_machine("xyz_mill"))
    tail = "G0 X0 Y0\nG2 X0 Y0 I0 J-300 F600\nG1 X400 Y10 Z-700\nG3 X380 Y-10 R30\n"  # 3 beyond travel
    text = big_program(2500).replace("M30\n", "") + tail
    program = parse_program(text, "t.nc", machine=machine)
    pieces = list(move_bounds_pieces(program, piece=700))       # pieces that end amid the moves
    lo, hi = np.concatenate([p[1] for p in pieces]), np.concatenate([p[2] for p in pieces])
    whole = move_bounds_table(program)
    assert np.array_equal(whole[0], lo) and np.array_equal(whole[1], hi)
    for i, m in enumerate(program.moves):
        a, b, _ = move_bounds(m)
        assert np.array_equal(lo[i], a) and np.array_equal(hi[i], b), i
    plo, phi = program_bounds(program)
    assert np.array_equal(plo, np.minimum(program.start_position, lo.min(axis=0)))
    assert np.array_equal(phi, np.maximum(program.start_position, hi.max(axis=0)))
    violations = check_program(program, machine, max_reports=1000)
    n = len(program.moves)
    assert {v.line for v in violations} == {program.moves[k].line for k in range(n - 3, n)}
    wheres = {v.where for v in violations}
    assert "arc extreme" in wheres and "end point" in wheres


def test_a_nan_parameter_number_is_a_located_error_not_an_internal_one(ctl: MachineController) -> None:
    """Loading such a program once reported "line 0: internal error"; it names the line and column."""
    issues: list[object] = []
    ctl.programErrors.connect(issues.append)
    r = ctl.load_program("G0 X1\n#[[10**300*10**300]-[10**300*10**300]]=5\n", wait=True)
    assert not r
    (errors,) = issues
    assert [(e.line, e.col) for e in errors] == [(2, 39)]
    assert "parameter number #nan out of range" in errors[0].message


def test_the_tool_path_is_made_with_the_check_not_by_the_pages(ctl: MachineController) -> None:
    """The preview's tool path comes with the loaded program (made off the GUI thread, seconds
    for millions of moves); the panel's program model takes it as it is."""
    from app.program_model import ProgramModel
    from app.toolpath import ToolPath

    assert ctl.load_program(big_program(3000), wait=True)
    info = ctl.program_info
    assert isinstance(info.toolpath, ToolPath)
    assert len(info.toolpath.move_lines) == info.move_count
    model = ProgramModel()
    model.set_loaded(info, ctl.coordinates.machine())
    assert model.toolpath is info.toolpath


def test_a_check_in_the_background_tells_how_far_it_is(qtbot, ctl: MachineController) -> None:
    seen: list[float] = []
    timer = QTimer()
    timer.timeout.connect(lambda: seen.append(ctl.loading_progress))
    timer.start(5)
    with qtbot.waitSignal(ctl.programLoaded, timeout=60_000):
        assert ctl.load_program(big_program(60_000), name="big.nc")
    timer.stop()
    from app.machine.program.checks import LOAD_SHARES

    moving = [p for p in seen if p > 0.0]
    assert moving and moving == sorted(moving) and max(moving) <= 1.0
    read, planned = LOAD_SHARES[0], LOAD_SHARES[0] + LOAD_SHARES[1]
    assert any(0.0 < p < read for p in moving)  # seen while the program was read
    assert any(planned < p < planned + LOAD_SHARES[2] for p in moving)  # ... and while planned
    assert ctl.loading_progress == 0.0  # nothing is being checked any more


def test_a_file_is_read_by_the_worker_not_the_calling_thread(qtbot, ctl: MachineController, tmp_path,
                                                            monkeypatch) -> None:
    """The call only looks whether the file opens; the worker reads it (a 250 MB file took the
    GUI thread half a second), and a file that cannot be read by then is refused with why."""
    import app.machine.program.checks as program_load

    path = tmp_path / "prog.nc"
    path.write_text(SHORT, encoding="utf-8")
    readers: list[str] = []
    real_read = program_load.read_program

    def read(p, *rest):
        import threading

        readers.append(threading.current_thread().name)
        return real_read(p, *rest)

    monkeypatch.setattr(program_load, "read_program", read)
    with qtbot.waitSignal(ctl.programLoaded, timeout=10_000) as blocker:
        assert ctl.load_program(path)
        assert ctl.loading
    assert blocker.args[0].text == SHORT and blocker.args[0].path == str(path)
    assert len(readers) == 1 and readers[0] != "MainThread"

    def gone(p, *_rest):
        raise program_load.PlannerError(f"{p}: cannot read: No such file or directory")

    monkeypatch.setattr(program_load, "read_program", gone)
    with qtbot.waitSignal(ctl.programErrors, timeout=10_000) as failed:
        assert ctl.load_program(path)
    assert "cannot read" in failed.args[0][0].message and ctl.program_info is None


def test_a_program_is_let_go_once_another_is_loaded(qtbot, ctl: MachineController) -> None:
    """Loading programs all shift long keeps only the one loaded: the last one is freed when
    the next replaces it, without waiting for a collection (each load's garbage is collected
    before what survives it is frozen; a 10,000,000-line program is 600 MB)."""
    import gc
    import weakref

    for name in ("first.nc", "second.nc"):
        with qtbot.waitSignal(ctl.programLoaded, timeout=20_000):
            assert ctl.load_program(big_program(2000), name=name)
        if name == "first.nc":
            first = weakref.ref(ctl.program_info.program)
    qtbot.wait(50)
    gc.disable()            # no collection may be what frees it
    try:
        assert ctl.program_info.name == "second.nc"
        assert first() is None
    finally:
        gc.enable()


def test_the_loaded_program_is_let_go_as_a_check_starts(qtbot, ctl: MachineController) -> None:
    """Two programs are never held at once: the loaded one (run to its end) goes as soon as a
    load starts, its own check again after a configuration change included (whatever the
    outcome, the load replaces it), without waiting for a collection. A 10,000,000-line
    program is half a gigabyte: held while its successor is read, the panel took 1.4 GB."""
    import gc
    import weakref
    from dataclasses import replace

    from tests.machine.conftest import run_to_idle

    assert ctl.load_program(big_program(150), name="a.nc", wait=True)   # 28 s of motion
    assert ctl.cycle_start()
    run_to_idle(ctl, 60)
    assert ctl.last_run.completed
    program = weakref.ref(ctl.program_info.program)
    cfg = ctl.config
    slower = replace(cfg, machine=cfg.machine.with_limits(a_max_mm_s2=cfg.machine.limits.a_max_mm_s2 * 0.8))
    gc.disable()            # no collection may be what frees it
    try:
        with qtbot.waitSignal(ctl.programLoaded, timeout=20_000):
            assert ctl.update_config(slower)
            assert ctl.loading and ctl.program_info is None
            assert program() is None
    finally:
        gc.enable()
    assert ctl.program_info.name == "a.nc"   # the same program, checked again


def test_a_load_forgets_where_the_program_it_replaces_stopped(qtbot, ctl: MachineController) -> None:
    """The point a fault left to resume from belongs to the program loaded. A load replaces
    that program whatever its outcome (this one is refused), so the point goes as the load
    starts: resume is refused meanwhile, never run on the program let go."""
    assert ctl.load_program(SHORT, wait=True)
    assert ctl.cycle_start(wait=True)
    assert ctl.run_until(lambda: ctl.current_line == 3, 5)
    ctl.advance(0.1)
    ctl.worker.inject("drive_fault", "Y", 0x2310)
    assert ctl.run_until(lambda: ctl.state is MachineState.ALARM, 1)
    ctl.advance(0.3)
    assert ctl.resume_line == 3
    assert ctl.reset() and ctl.state is MachineState.IDLE
    with qtbot.waitSignal(ctl.programErrors, timeout=20_000):
        assert ctl.load_program(BAD, name="bad.nc")
        assert ctl.loading and ctl.resume_line == 0
        refused = ctl.resume()
        assert not refused and "nothing to resume" in refused.reason
    assert ctl.program_info is None and ctl.resume_line == 0
