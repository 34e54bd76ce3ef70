"""A spindle on its own CiA 402 drive: the drive model's velocity modes (cyclic synchronous
velocity follows 0x60FF, profile velocity ramps to it at 0x6083/0x6084, a load slows it) and
the 1 ms loop turning it (enabled on demand, the command ramped, the speed read back, stopped
and disabled at 0, quick-stopped with the machine, its faults alarms that a fault reset clears)."""

from __future__ import annotations

import numpy as np
import pytest

from bench.stepped import enabled as enabled_worker
from ethercat.bus import DriveSpec, SpindleDriveSpec
from ethercat.cia402 import CSV, CW_ENABLE_OPERATION, CW_QUICK_STOP, PV, SW_TARGET_REACHED, Cia402State
from ethercat.drive_model import DriveModel, DriveParams
from ethercat.errors import ConfigurationError
from ethercat.worker import AlarmCode, CyclicWorker, SpindleState, WorkerConfig

TS = 0.001
PER_RPM = 10_000.0 / 60.0          # counts/s per rpm of a 10,000-count spindle encoder


def _enabled_model(mode: int, **params: float) -> DriveModel:
    m = DriveModel(DriveParams(v_max_counts_s=20_000 * PER_RPM, a_max_counts_s2=10_000 * PER_RPM,
                               velocity_lag_s=0.02, **params))  # type: ignore[arg-type]
    m.modes_of_operation = int(mode)
    for cw in (0x00, 0x06, 0x07, CW_ENABLE_OPERATION, CW_ENABLE_OPERATION):
        m.controlword = cw
        m.step(TS)
    assert m.state is Cia402State.OPERATION_ENABLED
    return m


def _run(m: DriveModel, seconds: float) -> np.ndarray:
    out = []
    for _ in range(int(round(seconds / TS))):
        m.step(TS)
        out.append(m.velocity_actual / PER_RPM)
    return np.array(out)


def test_cyclic_synchronous_velocity_follows_the_target_within_the_motor_limits() -> None:
    m = _enabled_model(CSV)
    m.target_velocity = int(6000 * PER_RPM)
    rpm = _run(m, 1.5)
    assert rpm[-1] == pytest.approx(6000, abs=1)
    assert np.diff(rpm).max() <= 10_000 * TS + 2 / PER_RPM             # the motor's acceleration
    assert m.statusword & (1 << 12)                                    # follows the command value
    m.target_velocity = int(-3000 * PER_RPM)
    assert _run(m, 2.0)[-1] == pytest.approx(-3000, abs=1)


def test_profile_velocity_ramps_at_its_own_acceleration_and_says_when_it_is_there() -> None:
    m = _enabled_model(PV)
    m.write_object(0x6083, 0, int(2000 * PER_RPM))      # 2,000 rpm/s up
    m.write_object(0x6084, 0, int(4000 * PER_RPM))      # 4,000 rpm/s down
    m.target_velocity = int(4000 * PER_RPM)
    rpm = _run(m, 1.0)
    assert rpm[-1] == pytest.approx(2000, abs=60)                     # half way after 1 s
    assert not m.statusword & SW_TARGET_REACHED
    rpm = _run(m, 1.5)
    assert rpm[-1] == pytest.approx(4000, abs=1) and m.statusword & SW_TARGET_REACHED
    m.target_velocity = 0
    rpm = _run(m, 0.5)
    assert rpm[-1] == pytest.approx(2000, abs=100)                    # down at 4,000 rpm/s (and its lag)


def test_a_load_holds_the_spindle_below_its_speed_and_a_quick_stop_brakes_it() -> None:
    m = _enabled_model(CSV)
    m.target_velocity = int(6000 * PER_RPM)
    _run(m, 1.5)
    m.set_load(2500 * PER_RPM)
    assert _run(m, 1.0)[-1] == pytest.approx(2500, abs=1)
    m.set_load(None)
    assert _run(m, 1.0)[-1] == pytest.approx(6000, abs=1)
    m.controlword = CW_QUICK_STOP
    rpm = _run(m, 3.0)
    assert rpm[-1] == 0.0 and m.state is Cia402State.SWITCH_ON_DISABLED


# ------------------------------------------------------------------------------ in the loop
def _worker(mode: int = 9) -> CyclicWorker:
    return enabled_worker(WorkerConfig((DriveSpec(0, "X"),), mode="manual",
                                       spindle=SpindleDriveSpec(1, PER_RPM, mode)))


def _watch(w: CyclicWorker, seconds: float) -> tuple[np.ndarray, np.ndarray]:
    cmd, act = [], []
    for _ in range(int(round(seconds / TS))):
        w.step(1)
        s = w.snapshot()
        cmd.append(s.spindle_rpm_command)
        act.append(s.spindle_rpm_actual)
    return np.array(cmd), np.array(act)


def test_the_loop_enables_ramps_reads_back_and_stops_the_spindle() -> None:
    """6,000 rpm at 3,000 rpm/s: the drive is enabled, the command ramps at that rate, the
    speed read follows it to within 1 rpm; 0 ramps down and disables the drive; -2,000 turns it
    the other way."""
    w = _worker()
    try:
        s = w.snapshot()
        assert s.spindle_state == SpindleState.OFF
        assert s.spindle_drive_state is not Cia402State.OPERATION_ENABLED
        assert w.spindle(6000.0, 3000.0)
        cmd, act = _watch(w, 2.5)
        assert np.diff(cmd).max() <= 3000.0 * TS * (1 + 1e-9) and cmd[-1] == 6000.0
        assert act[-1] == pytest.approx(6000.0, abs=1.0)
        s = w.snapshot()
        assert s.spindle_state == SpindleState.RUNNING
        assert s.spindle_drive_state is Cia402State.OPERATION_ENABLED
        assert w.spindle(0.0, 3000.0)
        cmd, act = _watch(w, 2.5)
        assert cmd[-1] == 0.0 and abs(act[-1]) < 1.0
        s = w.snapshot()
        assert s.spindle_state == SpindleState.OFF
        assert s.spindle_drive_state is not Cia402State.OPERATION_ENABLED
        assert w.spindle(-2000.0, 3000.0)
        _cmd, act = _watch(w, 1.5)
        assert act[-1] == pytest.approx(-2000.0, abs=1.0)
    finally:
        w.stop()


def test_profile_velocity_leaves_the_ramp_to_the_drive() -> None:
    w = _worker(mode=3)
    try:
        assert w.spindle(4000.0, 1.0)                  # the loop's ramp does not apply in mode 3
        cmd, act = _watch(w, 1.0)
        assert cmd[-1] == 4000.0 and act[-1] == pytest.approx(4000.0, abs=2.0)   # 8,000 rpm/s sim
    finally:
        w.stop()


def test_a_load_slows_it_and_e_stop_quick_stops_it_and_keeps_it_off() -> None:
    w = _worker()
    try:
        assert w.spindle(6000.0, 6000.0)
        _watch(w, 1.5)
        w.inject("spindle_load", 0, 1500)
        _cmd, act = _watch(w, 1.0)
        assert act[-1] == pytest.approx(1500.0, abs=1.0) and w.snapshot().spindle_rpm_command == 6000.0
        w.inject("spindle_unload", 0)
        _watch(w, 1.0)
        w.estop("test")
        assert not w.spindle(3000.0, 3000.0)            # quick-stopping: refused
        _cmd, act = _watch(w, 1.5)
        assert abs(act[-1]) < 1.0 and w.snapshot().spindle_state == SpindleState.OFF
        assert not w.spindle(3000.0, 3000.0)            # the machine's drives are off: refused
        assert w.spindle(0.0, 3000.0)                   # (stopping always may)
        w.fault_reset()
        w.step(20)
        w.enable()
        w.step(20)
        assert w.spindle(3000.0, 3000.0)
    finally:
        w.stop()


def test_a_spindle_drive_fault_is_an_alarm_and_a_fault_reset_clears_it() -> None:
    w = _worker()
    try:
        assert w.spindle(3000.0, 6000.0)
        _watch(w, 1.0)
        w.inject("spindle_fault", 0, 0x2310)
        _watch(w, 0.1)
        s = w.snapshot()
        assert s.spindle_state == SpindleState.FAULT and s.spindle_error_code == 0x2310
        alarm = next(a for a in s.alarms if a.code is AlarmCode.SPINDLE)
        assert "the spindle's drive faulted (error code 0x2310" in alarm.message
        assert not w.spindle(3000.0, 6000.0)
        w.step(1000)
        w.fault_reset()
        w.step(50)
        assert w.snapshot().spindle_state == SpindleState.OFF
        assert not w.spindle(1000.0, 6000.0)           # the reset left the machine's drives off
        w.enable()
        w.step(20)
        assert w.spindle(1000.0, 6000.0)
        _cmd, act = _watch(w, 1.0)
        assert act[-1] == pytest.approx(1000.0, abs=1.0)
    finally:
        w.stop()


def test_a_spindle_drive_at_an_axis_drive_position_is_refused() -> None:
    with pytest.raises(ConfigurationError, match="position"):
        WorkerConfig((DriveSpec(0, "X"),), spindle=SpindleDriveSpec(0))
    with pytest.raises(ConfigurationError, match="mode 8"):
        SpindleDriveSpec(1, mode=8)
