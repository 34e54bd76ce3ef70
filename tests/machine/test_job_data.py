"""Job data: a program run to its end makes a part, a target stops further cycle starts with
the reason, and every run is logged (program, start and end, result, the line it stopped at,
its cycle time, its alarms) in a file a crash never tears."""

from __future__ import annotations

import csv
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

from app.machine.controller import MachineController
from app.machine.model import MachineState
from tests.machine.conftest import make_controller

ROOT = Path(__file__).resolve().parents[2]
PROGRAM = "G21 G90\nG0 X0 Y0\nG1 X20 F1200\nG1 Y20\nG1 X0\nM30\n"


def _run(ctl: MachineController) -> None:
    assert ctl.cycle_start(wait=True)
    assert ctl.run_until(lambda: ctl.state is MachineState.IDLE and ctl.stream.job is None, 60)


def test_runs_to_the_end_count_parts_and_each_run_is_logged(qapp, config_path: Path, state_dir: Path,
                                                             tmp_path: Path) -> None:
    ctl = make_controller(config_path, state_dir)
    try:
        path = tmp_path / "square.nc"
        path.write_text(PROGRAM)
        assert ctl.load_program(path, wait=True)
        before = time.time()
        for _ in range(3):
            _run(ctl)
        assert ctl.part_count == 3
        runs = ctl.runs()
        assert [r.part for r in runs] == [1, 2, 3] and all(r.completed for r in runs)
        assert all(r.program == "square.nc" and r.path == str(path) and r.result == "completed" for r in runs)
        assert all(before <= r.start_s <= r.end_s for r in runs) and runs[0].cycle_time_s > 1.0
        # a run stopped part-way makes no part; resumed to its end, it makes one
        assert ctl.cycle_start(wait=True)
        assert ctl.run_until(lambda: ctl.current_line >= 4, 30)
        assert ctl.stop()
        assert ctl.run_until(lambda: ctl.state is MachineState.IDLE, 30)
        stopped = ctl.runs()[-1]
        assert not stopped.completed and stopped.part == 0 and stopped.last_line >= 4
        assert ctl.resume()
        assert ctl.run_until(lambda: ctl.state is MachineState.IDLE and ctl.stream.job is None, 60)
        assert ctl.runs()[-1].completed and ctl.part_count == 4
        # an alarm during a run is in its record
        assert ctl.cycle_start(wait=True)
        assert ctl.run_until(lambda: ctl.current_line >= 4, 30)
        ctl.estop("operator")
        assert ctl.run_until(lambda: ctl.runs()[-1].alarms != (), 10)
        assert any("E-stop" in a for a in ctl.runs()[-1].alarms) and ctl.part_count == 4
        csv_path, json_path = ctl.export_runs(tmp_path)
        rows = list(csv.DictReader(csv_path.open()))
        assert [r["part"] for r in rows] == ["1", "2", "3", "0", "4", "0"]
        assert len(json.loads(json_path.read_text())) == 6
    finally:
        ctl.shutdown()
    again = make_controller(config_path, state_dir)
    try:
        assert again.part_count == 4 and len(again.runs()) == 6        # kept in the state folder
    finally:
        again.shutdown()


def test_a_target_reached_refuses_cycle_start_until_the_counter_is_reset(qapp, config_path: Path,
                                                                         state_dir: Path) -> None:
    ctl = make_controller(config_path, state_dir)
    try:
        assert ctl.load_program(PROGRAM, name="square.nc", wait=True)
        messages: list[str] = []
        ctl.message.connect(messages.append)
        ctl.set_part_target(2)
        _run(ctl)
        _run(ctl)
        assert "2 part(s) made: the target of 2 is reached" in messages
        r = ctl.cycle_start(wait=True)
        assert not r and "the target of 2 part(s) is reached" in r.reason and ctl.part_count == 2
        ctl.reset_part_count()
        assert ctl.part_count == 0
        _run(ctl)
        assert ctl.part_count == 1
    finally:
        ctl.shutdown()


def test_a_line_a_crash_cut_short_is_skipped_and_the_next_run_is_whole(qapp, config_path: Path,
                                                                       state_dir: Path) -> None:
    ctl = make_controller(config_path, state_dir)
    try:
        assert ctl.load_program(PROGRAM, name="square.nc", wait=True)
        _run(ctl)
        with open(state_dir / "runs.jsonl", "ab") as f:
            f.write(b'{"program": "cut.nc", "path": "", "sta')          # power lost while writing
        assert [r.part for r in ctl.runs()] == [1]
        _run(ctl)
        assert [r.part for r in ctl.runs()] == [1, 2]
    finally:
        ctl.shutdown()


def test_the_log_survives_kill_9_of_the_control(tmp_path: Path) -> None:
    state = tmp_path / "state"
    short = tmp_path / "short.nc"
    short.write_text("G21 G90\nG1 X5 F1200\nM30\n")
    argv = [sys.executable, "-m", "app.run_cli", str(short), "--sim", "--json", "--state-dir", str(state),
            "--worker", "manual"]
    done = subprocess.run(argv, cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    long = tmp_path / "long.nc"
    long.write_text("G21 G90\nG1 X200 F600\nM30\n")          # 20 s
    proc = subprocess.Popen([sys.executable, "-m", "app.run_cli", str(long), "--sim", "--state-dir",
                             str(state)],
                            cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert proc.stderr is not None
        for line in proc.stderr:                                  # it prints its progress once running
            if "line" in line and "%" in line:
                break
        os.kill(proc.pid, signal.SIGKILL)
        proc.wait(10)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait(10)
    lines = (state / "runs.jsonl").read_text().splitlines()
    assert len(lines) == 1 and json.loads(lines[0])["program"] == "short.nc"
    assert json.loads((state / "parts.json").read_text())["count"] == 1


