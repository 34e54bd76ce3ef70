"""CiA 402 master-side logic: statusword decoding, controlword tables, scaling."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from ethercat import cia402
from ethercat.cia402 import (
    DISABLE_LUT,
    ENABLE_LUT,
    QUICK_STOP_LUT,
    STATE_STATUSWORD,
    AxisScale,
    Cia402State,
    decode_statusword,
)
from ethercat.drive_model import DriveModel
from ethercat.errors import ConfigurationError, EtherCATError

S = Cia402State


@pytest.mark.parametrize(("statusword", "state"), [
    (0x0000, S.NOT_READY_TO_SWITCH_ON),
    (0x0040, S.SWITCH_ON_DISABLED),
    (0x0250, S.SWITCH_ON_DISABLED),          # voltage + remote bits do not matter
    (0x0021, S.READY_TO_SWITCH_ON),
    (0x0231, S.READY_TO_SWITCH_ON),
    (0x0023, S.SWITCHED_ON),
    (0x0027, S.OPERATION_ENABLED),
    (0x1637, S.OPERATION_ENABLED),           # with target reached, follows command, etc.
    (0x0007, S.QUICK_STOP_ACTIVE),
    (0x000F, S.FAULT_REACTION_ACTIVE),
    (0x002F, S.FAULT_REACTION_ACTIVE),
    (0x0008, S.FAULT),
    (0x0228, S.FAULT),
])
def test_decode_statusword(statusword: int, state: Cia402State) -> None:
    assert decode_statusword(statusword) is state


def test_state_codes_roundtrip() -> None:
    for state, sw in STATE_STATUSWORD.items():
        assert decode_statusword(sw) is state
        assert decode_statusword(sw | 0xFF00) is state       # high bits never change the state


def test_vectorised_decode_matches_scalar() -> None:
    rng = np.random.default_rng(1)
    sw = rng.integers(0, 0x10000, size=5000).astype(np.uint16)
    out = np.zeros(sw.shape, dtype=np.int8)
    scratch = np.zeros(sw.shape, dtype=np.int64)
    cia402.decode_states(sw, out, scratch)
    expected = np.array([decode_statusword(int(x)) for x in sw], dtype=np.int8)
    np.testing.assert_array_equal(out, expected)


def _model_in(state: Cia402State) -> DriveModel:
    """A drive model brought into `state` through the standard transitions."""
    m = DriveModel()
    m.step(0.001)                                     # -> SWITCH ON DISABLED
    path = {
        S.SWITCH_ON_DISABLED: [],
        S.READY_TO_SWITCH_ON: [0x06],
        S.SWITCHED_ON: [0x06, 0x07],
        S.OPERATION_ENABLED: [0x06, 0x07, 0x0F],
        S.QUICK_STOP_ACTIVE: [0x06, 0x07, 0x0F],
        S.FAULT: [],
    }[state]
    for cw in path:
        m.controlword = cw
        m.step(0.001)
    if state is S.QUICK_STOP_ACTIVE:
        m.write_object(0x605A, 0, 6)                  # stay in QUICK STOP ACTIVE
        m.controlword = 0x02
        m.step(0.001)
    if state is S.FAULT:
        m.inject_fault()
        for _ in range(20):
            m.step(0.001)
    assert m.state is state
    return m


@pytest.mark.parametrize("start", [S.SWITCH_ON_DISABLED, S.READY_TO_SWITCH_ON, S.SWITCHED_ON,
                                   S.OPERATION_ENABLED, S.QUICK_STOP_ACTIVE])
def test_enable_lut_reaches_operation_enabled_from_every_state(start: Cia402State) -> None:
    m = _model_in(start)
    for _ in range(10):
        m.controlword = int(ENABLE_LUT[decode_statusword(m.statusword)])
        m.step(0.001)
    assert m.state is S.OPERATION_ENABLED


@pytest.mark.parametrize("start", [S.SWITCH_ON_DISABLED, S.READY_TO_SWITCH_ON, S.SWITCHED_ON,
                                   S.OPERATION_ENABLED, S.QUICK_STOP_ACTIVE])
def test_disable_lut_reaches_ready_to_switch_on(start: Cia402State) -> None:
    m = _model_in(start)
    for _ in range(10):
        m.controlword = int(DISABLE_LUT[decode_statusword(m.statusword)])
        m.step(0.001)
    assert m.state is S.READY_TO_SWITCH_ON


def test_quick_stop_lut_from_operation_enabled() -> None:
    m = _model_in(S.OPERATION_ENABLED)
    m.controlword = int(QUICK_STOP_LUT[decode_statusword(m.statusword)])
    m.step(0.001)
    assert m.state in (S.QUICK_STOP_ACTIVE, S.SWITCH_ON_DISABLED)
    assert cia402.quick_stop_controlword(S.OPERATION_ENABLED) == cia402.CW_QUICK_STOP


def test_enable_lut_never_resets_a_fault() -> None:
    m = _model_in(S.FAULT)
    for _ in range(10):
        m.controlword = cia402.enable_controlword(decode_statusword(m.statusword))
        m.step(0.001)
    assert m.state is S.FAULT


def test_fault_reset_is_a_rising_edge() -> None:
    m = _model_in(S.FAULT)
    m.controlword = cia402.fault_reset_controlword(0)         # 0x00
    m.step(0.001)
    assert m.state is S.FAULT
    m.controlword = cia402.fault_reset_controlword(1)         # 0x80: rising edge
    m.step(0.001)
    assert m.state is S.SWITCH_ON_DISABLED
    assert m.error_code == 0


def test_helpers() -> None:
    assert cia402.is_enabled(0x0237)
    assert not cia402.is_enabled(0x0233)
    assert cia402.is_fault(0x0208)
    assert cia402.disable_controlword(S.OPERATION_ENABLED) == cia402.CW_SHUTDOWN
    assert int(cia402.CSP) == 8 and int(cia402.HOMING) == 6


@pytest.mark.parametrize(("cpu", "direction", "q", "counts"), [
    (10_000.0, 1, 1.0, 10_000),
    (10_000.0, -1, 1.0, -10_000),
    (131_072 / 360.0, 1, 90.0, 32_768),         # rotary axis, 17-bit encoder per turn, degrees
    (1000.0, 1, -0.0004, 0),
    (1000.0, 1, 0.0006, 1),
])
def test_scale_to_counts(cpu: float, direction: int, q: float, counts: int) -> None:
    s = AxisScale(cpu, direction)
    assert s.to_counts(q) == counts
    assert s.to_units(counts) == pytest.approx(counts / (cpu * direction))


@given(st.floats(-1000.0, 1000.0), st.sampled_from([1, -1]), st.floats(1.0, 1e6))
def test_scale_roundtrip_within_one_count(q: float, direction: int, cpu: float) -> None:
    s = AxisScale(cpu, direction, offset_counts=123.0)
    assert abs(s.to_units(s.to_counts(q)) - q) <= 0.5 / cpu + 1e-9


def test_vectorised_scaling() -> None:
    scales = (AxisScale(10_000.0, 1), AxisScale(500.0, -1, 7.0))
    gain, offset = cia402.scale_arrays(scales)
    q = np.array([1.23456, -2.5])
    out = np.zeros(2, dtype=np.int32)
    cia402.units_to_counts(q, gain, offset, out, np.zeros(2))
    assert out.tolist() == [scales[0].to_counts(1.23456), scales[1].to_counts(-2.5)]
    back = np.zeros(2)
    cia402.counts_to_units(out, gain, offset, back)
    assert back == pytest.approx(q, abs=1e-3)


@pytest.mark.parametrize(("cpu", "direction"), [(0.0, 1), (-1.0, 1), (float("nan"), 1), (1.0, 0), (1.0, 2)])
def test_bad_scale_rejected(cpu: float, direction: int) -> None:
    with pytest.raises(ConfigurationError) as exc:
        AxisScale(cpu, direction)
    assert isinstance(exc.value, ValueError) and isinstance(exc.value, EtherCATError)
