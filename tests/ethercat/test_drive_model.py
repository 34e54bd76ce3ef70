"""The simulated CiA 402 servo drive: every transition, faults, dynamics, homing, SDO."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ethercat.cia402 import (
    SW_FOLLOWING_ERROR,
    SW_HOMING_ATTAINED,
    SW_HOMING_ERROR,
    SW_OP_SPECIFIC_12,
    SW_TARGET_REACHED,
    Cia402State,
    decode_statusword,
)
from ethercat.drive_model import DriveModel, DriveParams
from ethercat.errors import SdoAbortError
from ethercat.object_dictionary import ERROR_FOLLOWING, ERROR_SYNC, OBJECTS, decode_object, encode_object

S = Cia402State
DT = 0.001


def step(m: DriveModel, cw: int, n: int = 1) -> Cia402State:
    m.controlword = cw
    for _ in range(n):
        m.step(DT)
    assert decode_statusword(m.statusword) is m.state
    return m.state


def enabled(params: DriveParams | None = None) -> DriveModel:
    m = DriveModel(params)
    m.modes_of_operation = 8
    for cw in (0x00, 0x06, 0x07, 0x0F):
        step(m, cw)
    assert m.state is S.OPERATION_ENABLED
    return m


def in_state(state: Cia402State) -> DriveModel:
    m = DriveModel()
    path = {S.SWITCH_ON_DISABLED: [0x00], S.READY_TO_SWITCH_ON: [0x00, 0x06],
            S.SWITCHED_ON: [0x00, 0x06, 0x07], S.OPERATION_ENABLED: [0x00, 0x06, 0x07, 0x0F]}[state]
    for cw in path:
        step(m, cw)
    assert m.state is state
    return m


def test_power_up_goes_to_switch_on_disabled() -> None:
    m = DriveModel()
    assert m.state is S.NOT_READY_TO_SWITCH_ON
    assert decode_statusword(m.statusword) is S.NOT_READY_TO_SWITCH_ON
    assert step(m, 0x00) is S.SWITCH_ON_DISABLED                       # transition 1


# (start state, controlword, expected state, CiA 402 transition number)
TRANSITIONS = [
    (S.SWITCH_ON_DISABLED, 0x06, S.READY_TO_SWITCH_ON, 2),
    (S.READY_TO_SWITCH_ON, 0x07, S.SWITCHED_ON, 3),
    (S.SWITCHED_ON, 0x0F, S.OPERATION_ENABLED, 4),
    (S.OPERATION_ENABLED, 0x07, S.SWITCHED_ON, 5),
    (S.SWITCHED_ON, 0x06, S.READY_TO_SWITCH_ON, 6),
    (S.READY_TO_SWITCH_ON, 0x00, S.SWITCH_ON_DISABLED, 7),
    (S.READY_TO_SWITCH_ON, 0x02, S.SWITCH_ON_DISABLED, 7),
    (S.OPERATION_ENABLED, 0x06, S.READY_TO_SWITCH_ON, 8),
    (S.OPERATION_ENABLED, 0x00, S.SWITCH_ON_DISABLED, 9),
    (S.SWITCHED_ON, 0x00, S.SWITCH_ON_DISABLED, 10),
    (S.SWITCHED_ON, 0x02, S.SWITCH_ON_DISABLED, 10),
    (S.OPERATION_ENABLED, 0x02, S.QUICK_STOP_ACTIVE, 11),
    # commands that are not valid in a state leave it unchanged
    (S.SWITCH_ON_DISABLED, 0x0F, S.SWITCH_ON_DISABLED, 0),
    (S.SWITCH_ON_DISABLED, 0x07, S.SWITCH_ON_DISABLED, 0),
    (S.READY_TO_SWITCH_ON, 0x06, S.READY_TO_SWITCH_ON, 0),
    (S.OPERATION_ENABLED, 0x0F, S.OPERATION_ENABLED, 0),
]


@pytest.mark.parametrize(("start", "cw", "expected", "number"), TRANSITIONS)
def test_transition(start: Cia402State, cw: int, expected: Cia402State, number: int) -> None:
    m = in_state(start)
    assert step(m, cw) is expected


def test_ready_with_enable_goes_through_switched_on() -> None:
    m = in_state(S.READY_TO_SWITCH_ON)
    assert step(m, 0x0F) is S.SWITCHED_ON            # 3
    assert step(m, 0x0F) is S.OPERATION_ENABLED      # 4


def test_quick_stop_option_2_ramps_then_switch_on_disabled() -> None:
    m = enabled()
    m.write_object(0x6085, 0, 2_000_000)             # 200 mm/s^2 quick stop ramp
    m.target_position = 0
    for k in range(1, 300):                          # accelerate to 10 mm/s
        m.target_position = int(10_000 * 0.01 * k)
        m.step(DT)
    v0 = m.velocity_counts_s
    assert v0 > 50_000
    assert step(m, 0x02) is S.QUICK_STOP_ACTIVE      # 11
    assert m.statusword & 0x20 == 0                  # quick stop bit is active low
    decel = m.read_object(0x6085)
    n = int(np.ceil(v0 / decel / DT)) + 2
    assert step(m, 0x02, n) is S.SWITCH_ON_DISABLED  # 12 automatically when stopped
    assert m.velocity_counts_s == 0.0


def test_quick_stop_option_6_stays_and_16_reenables() -> None:
    m = enabled()
    m.write_object(0x605A, 0, 6)
    assert step(m, 0x02, 50) is S.QUICK_STOP_ACTIVE
    assert step(m, 0x0F) is S.OPERATION_ENABLED      # 16
    step(m, 0x02, 5)
    assert step(m, 0x00) is S.SWITCH_ON_DISABLED     # 12 by disable voltage


def test_fault_reaction_then_fault_then_reset_edge() -> None:
    m = enabled()
    m.inject_fault(0x2310)
    assert step(m, 0x0F) is S.FAULT_REACTION_ACTIVE  # 13
    assert m.error_code == 0x2310
    assert step(m, 0x0F, 20) is S.FAULT              # 14
    assert step(m, 0x0F, 3) is S.FAULT               # enable does not leave FAULT
    assert step(m, 0x80) is S.SWITCH_ON_DISABLED     # 15 on the rising edge of bit 7
    assert m.error_code == 0
    m.inject_fault(0x4310)
    step(m, 0x80, 20)                                # bit 7 held high: no new edge
    assert m.state is S.FAULT
    step(m, 0x00)
    assert step(m, 0x80) is S.SWITCH_ON_DISABLED


def test_fault_can_trip_from_any_state() -> None:
    for state in (S.SWITCH_ON_DISABLED, S.READY_TO_SWITCH_ON, S.SWITCHED_ON):
        m = in_state(state)
        m.inject_fault()
        assert step(m, 0x00, 20) is S.FAULT


def test_persistent_fault_survives_reset_until_cleared() -> None:
    m = enabled()
    m.inject_fault(0x7305, persistent=True)
    step(m, 0x0F, 20)
    step(m, 0x00)
    assert step(m, 0x80) is S.FAULT
    m.clear_fault()
    step(m, 0x00)
    assert step(m, 0x80) is S.SWITCH_ON_DISABLED


def smooth_move(m: DriveModel, distance_counts: float, duration_s: float) -> np.ndarray:
    """Cosine move in CSP; returns the following error (counts) of every cycle."""
    x0 = m.position_actual
    n = int(duration_s / DT)
    fe = np.zeros(n + 200)
    for k in range(n + 200):
        u = min(1.0, k / n)
        m.target_position = int(round(x0 + distance_counts * (1 - np.cos(np.pi * u)) / 2))
        m.step(DT)
        fe[k] = m.following_error_actual
    return fe


def test_csp_tracks_with_small_following_error_and_arrives() -> None:
    m = enabled()
    fe = smooth_move(m, 100_000, 0.5)                # 10 mm in 0.5 s at 10,000 counts/mm
    assert m.position_actual == m.target_position
    assert 1 <= np.abs(fe).max() < 500               # realistic: some counts, well below 0.05 mm
    assert m.statusword & SW_OP_SPECIFIC_12


def test_encoder_quantisation() -> None:
    m = enabled(DriveParams(encoder_resolution_counts=16))
    smooth_move(m, 1000, 0.1)
    assert m.position_actual % 16 == 0
    assert abs(m.motor_position_counts - 1000) < 16


def test_velocity_and_acceleration_limits() -> None:
    p = DriveParams(v_max_counts_s=50_000.0, a_max_counts_s2=1e6)
    m = enabled(p)
    speeds = []
    for k in range(1, 400):
        m.target_position = 200 * k                   # demand 200,000 counts/s: too fast
        m.step(DT)
        speeds.append(m.velocity_counts_s)
    assert max(speeds) <= 50_000.0 + 1e-6
    assert np.max(np.abs(np.diff(speeds))) <= 1e6 * DT + 1e-6


def test_following_error_window_trips_fault_after_timeout() -> None:
    m = enabled(DriveParams(following_error_window_counts=100, following_error_timeout_ms=5))
    m.set_jam(True)
    base = m.position_actual
    for k in range(1, 50):
        m.target_position = base + 40 * k
        m.step(DT)
        if m.state is not S.OPERATION_ENABLED:
            break
        if abs(m.following_error_actual) > 100:
            assert m.statusword & SW_FOLLOWING_ERROR
    assert m.state is S.FAULT_REACTION_ACTIVE
    assert m.error_code == ERROR_FOLLOWING
    # the error first exceeds the 100-count window at k = 3 (120 counts); the fault waits for
    # the 5 ms time-out (0x6066) to be exceeded: the sixth cycle over the window, k = 8
    assert k == 8


def test_following_error_within_window_no_fault() -> None:
    m = enabled(DriveParams(following_error_window_counts=1000, following_error_timeout_ms=5))
    smooth_move(m, 100_000, 0.5)
    assert m.state is S.OPERATION_ENABLED


def test_watchdog_fault() -> None:
    m = enabled()
    m.watchdog_expired()
    step(m, 0x0F, 20)
    assert m.state is S.FAULT and m.error_code == ERROR_SYNC


def test_target_ignored_when_not_enabled_and_no_jump_on_enable() -> None:
    m = DriveModel(DriveParams(initial_position_counts=5000.0))
    m.modes_of_operation = 8
    m.target_position = 0                             # stale target
    for cw in (0x00, 0x06, 0x07):
        step(m, cw)
    assert m.position_actual == 5000
    m.target_position = m.position_actual             # target := actual before enabling
    step(m, 0x0F, 50)
    assert m.position_actual == 5000


def test_homing_method_35_sets_home_offset_here() -> None:
    m = enabled(DriveParams(initial_position_counts=1234.0))
    m.write_object(0x607C, 0, 500)
    m.write_object(0x6098, 0, 35)
    m.modes_of_operation = 6
    step(m, 0x0F)
    assert m.modes_of_operation_display == 6
    step(m, 0x1F, 2)
    assert m.statusword & SW_HOMING_ATTAINED and m.statusword & SW_TARGET_REACHED
    assert m.position_actual == 500


@pytest.mark.parametrize(("method", "start"), [(17, 20_000.0), (18, -20_000.0)])
def test_homing_on_switch(method: int, start: float) -> None:
    p = DriveParams(initial_position_counts=start, home_switch_counts=0.0)
    m = enabled(p)
    m.write_object(0x6098, 0, method)
    m.write_object(0x6099, 1, 100_000)
    m.write_object(0x6099, 2, 5_000)
    m.write_object(0x609A, 0, 5_000_000)
    m.modes_of_operation = 6
    step(m, 0x0F)
    m.controlword = 0x1F
    for _ in range(3000):
        m.step(DT)
        if m.statusword & (SW_HOMING_ATTAINED | SW_HOMING_ERROR):
            break
    assert m.statusword & SW_HOMING_ATTAINED and not m.statusword & SW_HOMING_ERROR
    # position actual now counts from the switch edge (home offset 0 there)
    assert abs(m.position_actual - (m.motor_position_counts - m._offset_counts)) < 100_000
    assert abs(m.position_actual) < 200           # stopped just past the edge


def test_homing_error_when_switch_not_found() -> None:
    p = DriveParams(initial_position_counts=0.0, home_switch_counts=1e9, homing_max_travel_counts=2000.0)
    m = enabled(p)
    m.write_object(0x6098, 0, 18)                   # positive direction: never finds the switch
    m.modes_of_operation = 6
    step(m, 0x0F)
    step(m, 0x1F, 500)
    assert m.statusword & SW_HOMING_ERROR


def test_sdo_read_write_and_aborts() -> None:
    m = DriveModel(DriveParams(vendor_id=0x1234, product_code=0x5678), position=3)
    assert m.read_object(0x1018, 1) == 0x1234
    assert m.read_object(0x1018, 2) == 0x5678
    assert m.read_object(0x1000) == 0x00020192
    m.write_object(0x6065, 0, 777)
    assert m.read_object(0x6065) == 777
    m.write_object(0x6040, 0, 0x06)
    assert m.controlword == 0x06
    with pytest.raises(SdoAbortError) as exc:
        m.read_object(0x2000, 0)
    assert exc.value.abort_code == SdoAbortError.OBJECT_DOES_NOT_EXIST and exc.value.position == 3
    with pytest.raises(SdoAbortError) as exc:
        m.read_object(0x6041, 5)
    assert exc.value.abort_code == SdoAbortError.SUBINDEX_DOES_NOT_EXIST
    with pytest.raises(SdoAbortError) as exc:
        m.write_object(0x6041, 0, 1)
    assert exc.value.abort_code == SdoAbortError.READ_ONLY
    with pytest.raises(SdoAbortError) as exc:
        m.write_object(0x6060, 0, 300)
    assert exc.value.abort_code == SdoAbortError.VALUE_RANGE


def test_object_encoding() -> None:
    e = OBJECTS[(0x607A, 0)]
    assert e.size_bytes == 4 and e.signed and e.pdo_mappable
    assert encode_object(e, -2) == b"\xfe\xff\xff\xff"
    assert decode_object(e, b"\xfe\xff\xff\xff") == -2
    with pytest.raises(SdoAbortError) as exc:
        decode_object(e, b"\x01\x02")
    assert exc.value.abort_code == SdoAbortError.LENGTH_MISMATCH
    for entry in OBJECTS.values():                    # every object reads in its own range
        m = DriveModel()
        assert entry.check_range(m.read_object(entry.index, entry.subindex))


def test_position_wraps_like_int32() -> None:
    m = DriveModel(DriveParams(initial_position_counts=2**31 + 10.0))
    m.step(DT)
    assert m.read_object(0x6064) == -(2**31) + 10


@given(distance=st.floats(-50_000.0, 50_000.0), duration_s=st.floats(0.05, 0.5),
       cycle_s=st.sampled_from([0.0005, 0.001, 0.002, 0.004]))
@settings(max_examples=40)
def test_random_moves_arrive_without_nan(distance: float, duration_s: float, cycle_s: float) -> None:
    m = enabled()
    x0 = m.position_actual
    n = max(1, int(duration_s / cycle_s))
    for k in range(1, n + int(0.3 / cycle_s)):
        u = min(1.0, k / n)
        m.target_position = int(round(x0 + distance * (1 - np.cos(np.pi * u)) / 2))
        m.step(cycle_s)
        assert np.isfinite(m.motor_position_counts) and np.isfinite(m.velocity_counts_s)
    assert m.state is S.OPERATION_ENABLED
    assert abs(m.position_actual - m.target_position) <= 1
