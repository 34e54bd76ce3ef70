"""`cnc-run` and one run in real time (the worker in its own process, as in the panel)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from app import run_cli
from app.machine.controller import MachineController
from app.machine.model import MachineState
from resources import (
    PROGRAMS,  # noqa: E402
    shipped_machine,
)
from tests.shm import shm_before, wait_for_new_blocks

ROOT = Path(__file__).resolve().parents[2]


def test_cnc_run_json_fast(qapp, capsys, tmp_path: Path) -> None:
    code = run_cli.main([str(PROGRAMS / "fig7_circle.nc"), "--sim", "--json", "--worker", "manual",
                         "--state-dir", str(tmp_path), "--trace", str(tmp_path / "t.npz")])
    out = json.loads(capsys.readouterr().out)
    assert code == 0 and out["completed"]
    assert out["limits_ok"]
    assert out["cycle_time_s"] == pytest.approx(out["estimated_cycle_time_s"], abs=0.01)
    assert set(out["tracking"]) == {"X", "Y", "Z"} and out["tracking"]["X"]["rmse"] > 0
    assert out["reference_end_position"] == [0.0, 0.0, 0.0]
    with np.load(tmp_path / "t.npz") as z:
        assert z["reference"].shape[1] == 3


def test_cnc_run_bad_program_exit_2(qapp, capsys, tmp_path: Path) -> None:
    bad = tmp_path / "bad.nc"
    bad.write_text("G1 X1 F100\nG1 X2 Q7\nG0 X900\n")
    code = run_cli.main([str(bad), "--sim", "--worker", "manual", "--state-dir", str(tmp_path / "s")])
    err = capsys.readouterr().err
    assert code == 2
    assert "line 2" in err and "Q" in err


def test_cnc_run_moves_real_drives_only_when_told(qapp, capsys, tmp_path: Path) -> None:
    """A configuration on EtherCAT drives is refused unless --hardware says the operator is at
    the machine (with --hardware the bus is opened: here its adapter does not exist)."""
    head = shipped_machine("xyz_mill").read_text(encoding="utf-8").split("[bus]")[0]
    config = tmp_path / "machine.toml"
    config.write_text(head + '[bus]\nkind = "soem"\nadapter = "nosuchif0"\n', encoding="utf-8")
    program = tmp_path / "p.nc"
    program.write_text("G1 X1 F100\n")
    code = run_cli.main([str(program), "--config", str(config), "--state-dir", str(tmp_path / "s")])
    err = capsys.readouterr().err
    assert code == 2 and "drives real hardware" in err and "--hardware" in err
    code = run_cli.main([str(program), "--config", str(config), "--hardware", "--worker", "thread",
                         "--state-dir", str(tmp_path / "s2")])
    captured = capsys.readouterr()
    assert code != 0 and "nosuchif0" in captured.err + captured.out


def test_cnc_run_text_report(qapp, capsys, tmp_path: Path) -> None:
    prog = tmp_path / "p.nc"
    prog.write_text("G1 X10 F1800\nG2 X20 Y0 R5\nM30\n")
    code = run_cli.main([str(prog), "--sim", "--worker", "manual",
                         "--config", str(shipped_machine("xyz_mill")), "--state-dir", str(tmp_path / "s")])
    out = capsys.readouterr().out
    assert code == 0
    assert "completed" in out and "RMSE" in out and "within limits: yes" in out


def test_realtime_run_in_the_worker_process(qtbot, config_path: Path, state_dir: Path) -> None:
    ctl = MachineController(config_path, state_dir=state_dir)  # worker_mode="process": real time
    try:
        assert ctl.connect_bus()
        assert ctl.set_machine_zero_here()
        done = []
        ctl.programFinished.connect(done.append)
        assert ctl.load_program("G1 X10 F1800\nG3 X10 Y10 R5\nG1 X0\nM30\n", wait=True)
        assert ctl.cycle_start()
        qtbot.waitUntil(lambda: bool(done), timeout=10_000)
        qtbot.waitUntil(lambda: ctl.state is MachineState.IDLE, timeout=2_000)
        s = done[0]
        assert s.completed and s.cycle_time_s == pytest.approx(ctl.program_info.cycle_time_s, abs=0.1)
        qtbot.wait(200)
        np.testing.assert_allclose(ctl.machine_position, (0.0, 10.0, 0.0), atol=1e-3)
        np.testing.assert_array_equal(ctl.reference_position, (0.0, 10.0, 0.0))
    finally:
        ctl.shutdown()


@pytest.mark.slow
def test_cnc_run_pocket_in_real_time(qapp, capsys, tmp_path: Path) -> None:
    """About 16 s of real time: the shipped pocket on simulated drives, worker in its process."""
    code = run_cli.main([str(PROGRAMS / "pocket.nc"), "--sim", "--json", "--state-dir", str(tmp_path)])
    out = json.loads(capsys.readouterr().out)
    assert code == 0 and out["completed"] and out["limits_ok"]
    assert out["cycle_time_s"] == pytest.approx(out["estimated_cycle_time_s"], abs=0.05)
    assert out["wall_time_s"] < out["cycle_time_s"] + 2.0  # real time, not slower


def test_sigterm_stops_a_headless_run_cleanly(tmp_path: Path) -> None:
    """cnc-run killed politely: the program stops along the path, the worker (its own
    process) ends, its shared memory is released, and the result says why it stopped."""
    import signal
    import subprocess
    import sys
    import time

    prog = tmp_path / "long.nc"
    prog.write_text("G1 X200 F600\nM30\n")          # 20 s at 10 mm/s
    before = shm_before()
    proc = subprocess.Popen([sys.executable, "-m", "app.run_cli", str(prog), "--sim", "--json",
                             "--worker", "process"], cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True)
    try:
        mine = wait_for_new_blocks(before, proc)
        assert mine, "the worker never started"
        assert proc.stderr is not None
        for line in iter(proc.stderr.readline, ""):   # its handlers are in place once it runs
            if "running;" in line:
                break
        else:
            raise AssertionError("the run never said it was running")
        time.sleep(1.0)
        proc.send_signal(signal.SIGTERM)
        out, err = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait(timeout=10)
    assert proc.returncode == 1, err                 # ran, did not complete
    result = json.loads(out)
    assert result["completed"] is False and "stopped by signal SIGTERM" in result["notes"]
    # what ran is told: the line reached, the time run, the limits measured so far
    assert result["reason"] == "signal" and result["last_line"] == 1
    assert 1.0 < result["cycle_time_s"] < 20.0 and result["limits_ok"] is True and result["limits"]
    assert result["final_state"] == "idle"
    assert not [p for p in mine if p.exists()], "shared memory left behind"


def test_a_sigterm_while_the_run_is_set_up_ends_it_cleanly_before_the_program_starts(tmp_path: Path) -> None:
    """The signal comes as soon as the worker exists, while a long program is still read (the
    worker starts first): the run ends by itself (not killed by the signal), says so, and gives
    its shared memory back."""
    import signal
    import subprocess
    import sys

    prog = tmp_path / "long.nc"
    prog.write_text("G21 G90 F600\n" + "".join(f"G1 X{i % 100} Y{i % 7}\n" for i in range(300_000)) + "M30\n")
    before = shm_before()
    proc = subprocess.Popen([sys.executable, "-m", "app.run_cli", str(prog), "--sim", "--json",
                             "--worker", "process"], cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True)
    try:
        mine = wait_for_new_blocks(before, proc)
        assert mine, "the worker never started"
        proc.send_signal(signal.SIGTERM)
        out, err = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait(timeout=10)
    assert proc.returncode == 1, err                 # its own end, not -15
    result = json.loads(out)
    assert result["completed"] is False and result["reason"] == "signal"
    assert "stopped by signal SIGTERM before the program started" in err
    assert not [p for p in mine if p.exists()], "shared memory left behind"


def test_a_run_stopped_at_the_time_limit_tells_what_ran_and_which_actions_were_not_done(
        qapp, capsys, tmp_path: Path) -> None:
    from app.run_cli import main

    prog = tmp_path / "long.nc"
    prog.write_text("G21 G90\n" + "".join(f"G1 X{(i % 2) * 50} Y{i} F600\n" for i in range(40)) + "M30\n")
    script = tmp_path / "ops.jsonl"
    script.write_text('{"after_s": 0.5, "op": "feed_override", "percent": 100}\n'
                      '{"after_s": 100, "op": "feed_hold"}\n')
    argv = [str(prog), "--sim", "--worker", "manual", "--script", str(script), "--json"]
    assert main([*argv, "--max-s", "3"]) == 1
    result = json.loads(capsys.readouterr().out)
    assert result["reason"] == "time limit" and result["completed"] is False
    assert result["last_line"] >= 3 and 2.5 < result["cycle_time_s"] < 4.0
    assert result["limits_ok"] is True and result["limits"]["axis_v"] > 0
    assert result["final_state"] == "idle"
    notes = result["notes"]
    assert any(n.endswith("actions not done: feed_hold after 100 s") for n in notes), notes
    script.write_text('{"after_s": 0.5, "op": "feed_override", "percent": 100}\n')
    assert main([*argv, "--max-s", "2"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["reason"] == "time limit"
    assert any(n.endswith("actions not done: none") for n in result["notes"]), result["notes"]


def test_a_run_killed_by_sigkill_leaves_the_state_unclean_and_no_axis_homed(qapp, tmp_path: Path) -> None:
    """Power loss, as far as a test can have one: cnc-run killed with SIGKILL mid-program. The
    state folder then says the last run did not end cleanly, and the next controller on it
    starts with no axis homed and an alarm saying why."""
    import signal
    import subprocess
    import sys
    import time

    state = tmp_path / "state"
    prog = tmp_path / "long.nc"
    prog.write_text("G1 X200 F600\nM30\n")
    cmd = [sys.executable, "-m", "app.run_cli"]
    run = [*cmd, str(prog), "--sim", "--json", "--worker", "thread", "--state-dir", str(state)]
    proc = subprocess.Popen(run, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline:
            time.sleep(0.3)
            status = subprocess.run([*cmd, "--state-dir", str(state), "--status", "--json"], cwd=ROOT,
                                    capture_output=True, text=True)
            if status.returncode == 0 and json.loads(status.stdout)["position"][0] > 1.0:
                break                                    # moving, with the position saved on the way
        else:
            raise AssertionError("the run never got under way")
        proc.send_signal(signal.SIGKILL)
        proc.wait(timeout=10)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait(timeout=10)
    status = json.loads(subprocess.run([*cmd, "--state-dir", str(state), "--status", "--json"], cwd=ROOT,
                                       capture_output=True, text=True, check=True).stdout)
    assert status["unclean_shutdown"] is True and all(status["homed"].values())
    ctl = MachineController(None, state_dir=state, worker_mode="manual")
    try:
        assert ctl.homed == (False, False, False)
        unclean = [a for a in ctl.alarms if a.code == "unclean_shutdown"]
        assert len(unclean) == 1 and "did not shut down cleanly" in unclean[0].cause
        assert ctl.connect_bus()
        assert not ctl.cycle_start() and ctl.refusal("cycle_start").startswith("axes not homed")
    finally:
        ctl.shutdown()
    clean = json.loads(subprocess.run([*cmd, "--state-dir", str(state), "--status", "--json"], cwd=ROOT,
                                      capture_output=True, text=True, check=True).stdout)
    assert clean["unclean_shutdown"] is False                # that controller shut down cleanly


class _Following:
    """Axes a few cycles behind the path's end, closing half the gap at each tick (a drive
    that follows its target), or never (a drive that does not move)."""

    def __init__(self, moving: bool) -> None:
        self.reference_position = (3.0, 1.0)
        self.machine_position = (3.0113, 0.9887)
        self.moving = moving
        self.ticks = 0

    def tick(self) -> None:
        self.ticks += 1
        if self.moving:
            self.machine_position = tuple(r + 0.5 * (m - r) for m, r in
                                          zip(self.machine_position, self.reference_position))


def test_the_end_position_is_read_once_the_axes_are_in_position() -> None:
    """A run ends with its last set-point while the drives still follow: cnc-run reads the end
    position once every axis is within 1 um of where the path ended, and waits no longer than
    SETTLE_S for a drive that stays behind."""
    import time

    ctl = _Following(moving=True)
    run_cli._settle(ctl, ctl.tick)
    assert max(abs(m - r) for m, r in zip(ctl.machine_position, ctl.reference_position)) <= run_cli.SETTLE_MM
    assert ctl.ticks == 4                      # 11.3 um halved four times: 0.7 um
    stuck = _Following(moving=False)
    t0 = time.monotonic()
    run_cli._settle(stuck, lambda: time.sleep(0.01))
    assert run_cli.SETTLE_S <= time.monotonic() - t0 < run_cli.SETTLE_S + 0.5


@pytest.mark.parametrize("worker", ["manual", "thread"])
def test_the_shortest_cycle_the_configuration_allows_runs(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                                          worker: str) -> None:
    """[planner] ts_s = 0.0001, the documented minimum: the 0.5 s lead is 5,000 set-points,
    and the worker's ring holds twice that."""
    from resources import shipped_machine

    text = shipped_machine("xyz_mill").read_text()
    config = tmp_path / "machine.toml"
    config.write_text(text.replace("\nts_s = 0.001", "\nts_s = 0.0001", 1))
    assert "ts_s = 0.0001" in config.read_text()
    program = tmp_path / "p.ngc"
    program.write_text("G21 G90\nG1 X5 Y3 F600\nM30\n")
    code = run_cli.main([str(program), "--sim", "--worker", worker, "--config", str(config), "--json",
                         "--state-dir", str(tmp_path / "state")])
    out = json.loads(capsys.readouterr().out)
    assert code == 0 and out["completed"] and out["limits_ok"]
