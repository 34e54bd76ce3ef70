"""Loading and quitting: a failed load unloads the previous program; shutdown (and disconnect)
mid-run stop the motion along its path before the worker and the feeder go, so no bogus
"set-point buffer underrun" alarm is persisted and the drives are not cut at speed."""

from __future__ import annotations

import json
import shutil
import time
from pathlib import Path

import numpy as np
import pytest

from app.machine.config import DEFAULT_LEAD_S
from app.machine.controller import MachineController
from app.machine.model import MachineState
from resources import shipped_machine
from tests.machine.conftest import make_controller, trace

SHORT = "G0 X5 Y0\nG1 X20 F1800\nG3 X20 Y20 R10\nG1 X5\nM30\n"
A_PATH = 1000.0  # xyz_mill path acceleration limit, mm/s^2


def saved_alarms(state_dir: Path) -> list[dict]:
    p = state_dir / "alarms.json"
    return json.loads(p.read_text()) if p.exists() else []


def test_failed_load_unloads_the_previous_program(ctl: MachineController) -> None:
    assert ctl.load_program(SHORT, wait=True) and ctl.program_info is not None
    errors = []
    ctl.programErrors.connect(errors.append)
    assert not ctl.load_program("G1 X2 Q5 F100\n", wait=True)
    assert errors and ctl.program_info is None and ctl.program is None and ctl.plan is None
    r = ctl.cycle_start()
    assert not r and r.reason == "no program loaded"
    assert ctl.refusal("cycle_start") == "no program loaded"
    assert not ctl.load_program(Path("/nonexistent/dir/prog.nc"), wait=True)  # unreadable file: same rule
    assert ctl.program_info is None
    assert ctl.load_program(SHORT, wait=True) and ctl.cycle_start()  # a good load is accepted again


def test_shutdown_mid_run_stops_along_the_path_first(qapp, config_path: Path, state_dir: Path) -> None:
    ctl = make_controller(config_path, state_dir)
    finished = []
    ctl.programFinished.connect(finished.append)
    try:
        assert ctl.load_program(SHORT, wait=True) and ctl.cycle_start()
        ctl.advance(0.5)  # in line 2 at 30 mm/s
        assert ctl.state is MachineState.RUNNING and ctl.snapshot().path_speed_mm_s > 10.0
        x0 = ctl.reference_position[0]
    finally:
        ctl.shutdown()
    assert ctl.state is MachineState.DISCONNECTED and ctl.worker is None
    assert finished and not finished[-1].completed
    assert not any("underrun" in a["cause"] for a in saved_alarms(state_dir))
    ref = trace(ctl)["reference"]
    assert ref[-1, 0] > x0 + 1.0  # the stop ran on past the point of the request ...
    d2 = np.linalg.norm(np.diff(ref[:, :2], 2, axis=0), axis=1) / 1e-6
    assert d2.max() <= A_PATH * (1 + 1e-6)  # ... as a jerk-limited ramp, not a cut at speed
    assert np.linalg.norm(ref[-1] - ref[-2]) < 1e-9  # standing when the drives were disabled
    st = json.loads((state_dir / "state.json").read_text())
    assert abs(st["raw_position"][0] - ref[-1, 0]) < 1e-3  # persisted where it stopped


def test_realtime_shutdown_mid_run_leaves_no_underrun_alarm(qapp, tmp_path: Path, state_dir: Path) -> None:
    shipped = tmp_path / "shipped.toml"  # the default lead_s, in real time (worker thread + feeder thread)
    shutil.copyfile(shipped_machine("xyz_mill"), shipped)
    ctl = MachineController(shipped, state_dir=state_dir, worker_mode="thread")
    assert ctl.config.controller.lead_s == DEFAULT_LEAD_S
    try:
        assert ctl.connect_bus() and ctl.set_machine_zero_here()
        assert ctl.load_program("G1 X60 F1800\nM30\n", wait=True) and ctl.cycle_start()
        time.sleep(0.6)
        assert ctl.state is MachineState.RUNNING
    finally:
        t0 = time.monotonic()
        ctl.shutdown()
        took = time.monotonic() - t0
    assert ctl.state is MachineState.DISCONNECTED
    assert took < 2.0
    assert not any("underrun" in a["cause"] for a in saved_alarms(state_dir))
    x = json.loads((state_dir / "state.json").read_text())["raw_position"][0]
    assert 5.0 < x < 60.0


def test_on_a_cpu_without_store_order_the_worker_runs_as_a_thread(qapp, config_path: Path, state_dir: Path,
                                                                  monkeypatch) -> None:
    """The worker's own process needs x86's store order; on an ARM panel PC the controller runs
    the same loop as a thread instead of failing to connect, and says so."""
    from ethercat.worker import shared

    monkeypatch.setattr(shared.platform, "machine", lambda: "aarch64")
    ctl = MachineController(config_path, state_dir=state_dir, worker_mode="process")
    try:
        assert ctl.connect_bus()
        assert ctl.worker.config.mode == "thread"
        assert any(a.code == "worker_thread_mode" for a in ctl.alarms)
    finally:
        ctl.shutdown()


@pytest.mark.parametrize("absolute", [False, True])
def test_after_an_unclean_end_axes_need_homing_unless_the_encoders_are_absolute(qapp, config_path: Path,
                                                                              state_dir: Path,
                                                                              absolute: bool) -> None:
    text = config_path.read_text()
    config_path.write_text(text.replace("drive_method = 35", f"drive_method = 35\nabsolute_encoders = "
                                                             f"{'true' if absolute else 'false'}"))
    (state_dir / "state.json").write_text(json.dumps({
        "axes": ["X", "Y", "Z"], "raw_position": [1.0, 2.0, 3.0], "home_offset": [0.0, 0.0, 0.0],
        "homed": [True, True, True], "active_offset": "G54", "running": True, "saved": 1.7e9}))
    ctl = MachineController(config_path, state_dir=state_dir, worker_mode="manual")
    try:
        assert ctl.homed == ((True,) * 3 if absolute else (False,) * 3)
        (alarm,) = [a for a in ctl.alarms if a.code == "unclean_shutdown"]
        assert ("homed flags kept" in alarm.cause) is absolute
    finally:
        ctl.shutdown()
    assert json.loads((state_dir / "state.json").read_text())["running"] is False


def test_one_control_per_state_folder(qapp, config_path: Path, state_dir: Path) -> None:
    """Two controls on one state folder would each trust their own positions and homed flags:
    the second is refused with the first one's pid, and may start once the first has ended."""
    import os

    from app.machine.errors import StateFolderBusy

    first = MachineController(config_path, state_dir=state_dir, worker_mode="manual")
    try:
        busy = f"another control \\(pid {os.getpid()}\\) uses the state folder"
        with pytest.raises(StateFolderBusy, match=busy):
            MachineController(config_path, state_dir=state_dir, worker_mode="manual")
    finally:
        first.shutdown()
    second = MachineController(config_path, state_dir=state_dir, worker_mode="manual")
    second.shutdown()


def test_a_second_panel_on_the_same_state_folder_is_refused(tmp_path: Path) -> None:
    import os
    import subprocess
    import sys

    from app.machine.infra.persist import StateStore

    state = tmp_path / "state"
    holder = StateStore(state, exclusive=True)            # a first control, as far as the folder knows
    try:
        env = {**os.environ, "QT_QPA_PLATFORM": "offscreen"}
        done = subprocess.run([sys.executable, "-m", "app", "--demo", "--state-dir", str(state),
                               "--screenshot", str(tmp_path / "x.png")], env=env, capture_output=True,
                              text=True, timeout=120, cwd=Path(__file__).resolve().parents[2])
    finally:
        holder.release()
    assert done.returncode == 2
    assert f"another control (pid {os.getpid()}) uses the state folder" in done.stderr
    assert not (tmp_path / "x.png").exists()
