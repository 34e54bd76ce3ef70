"""Homing to the encoder's index past the home switch (LinuxCNC's HOME_USE_INDEX): the drive's
touch probe 1 latches the zero impulse (0x60B8 = 0x15, 0x60B9 bits 0-1, 0x60BA), so the home
is the same count whatever the cycle time, the latch velocity or where the axis started."""

from __future__ import annotations

import math

import numpy as np
import pytest

from ethercat.bus import DriveSpec
from ethercat.cia402 import TP_ENABLED, TP_INDEX_FIRST_POSITIVE, TP_POSITIVE_STORED
from ethercat.drive_model import DriveModel, DriveParams
from ethercat.errors import WorkerError
from ethercat.sim_io import SimSwitch
from ethercat.terminals import TerminalSpec
from ethercat.worker import (
    AlarmCode,
    CyclicWorker,
    HomingState,
    HomingStep,
    SwitchHoming,
    WorkerConfig,
    WorkerState,
)
from tests.ethercat.test_terminals import _home, _home_traced

TERMINALS = (TerminalSpec(2, "EK1100"), TerminalSpec(3, "EL1008"))
DRIVES = (DriveSpec(0, "X"), DriveSpec(1, "Z", direction=-1))
IN = 2 + 1                   # the EL1008's input word (after the two drives)
COUNTS = 10_000.0            # counts per mm (DriveSpec's default)
PITCH = 2.0                  # mm between index pulses
EDGE = 5.0                   # the home switch closes from X = 5 on


def _index_positions(pitch: float = PITCH) -> np.ndarray:
    """Where the simulated drive's index pulses are, mm (a third of a pitch from count 0)."""
    return np.array([round((pitch / 3.0 + pitch * k) * COUNTS) / COUNTS for k in range(-10, 10)])


def _worker(spec: SwitchHoming, x0: float, pitch: float = PITCH, **options: object) -> CyclicWorker:
    switch = SimSwitch(0, 3, EDGE, 1e9, terminal=1)
    bus_options = (("switches", (switch,)), ("initial_positions_counts", (x0 * COUNTS, 0.0)),
                   ("index_pitch_units", (pitch, 0.0)), *options.items())
    cfg = WorkerConfig(DRIVES, mode="manual", terminals=TERMINALS, switch_homing=(spec,),
                       bus_options=bus_options)
    w = CyclicWorker(cfg)
    w.start()
    w.step(3)
    return w


def _spec(latch_vel: float, travel: float = 40.0) -> SwitchHoming:
    return SwitchHoming(0, IN, 3, True, 20.0, latch_vel, travel, 2000.0, 400_000.0, use_index=True)


@pytest.mark.parametrize("latch_vel, expected", [(-2.0, "below"), (2.0, "above")])
def test_the_home_is_the_index_past_the_switch_edge_to_one_count_from_random_starts(
        latch_vel: float, expected: str) -> None:
    """12 random starts (some on the switch), a latch velocity 20 times the switch homing's:
    the latched position is always the first index past the edge in the latch direction,
    within one count (a latch in the loop at 2 mm/s could be off by up to 20 counts)."""
    index = _index_positions()
    want = index[index < EDGE].max() if expected == "below" else index[index > EDGE].min()
    rng = np.random.default_rng(11)
    for x0 in rng.uniform(-20.0, 9.0, 12):
        w = _worker(_spec(latch_vel), float(x0))
        try:
            _home(w)
            s = w.snapshot()
            assert s.homing[0] is HomingState.DONE and s.homing_steps[0] is HomingStep.DONE, (x0, s.alarms)
            assert abs(s.home_latched[0] - want) <= 1.0 / COUNTS + 1e-12, (x0, s.home_latched[0], want)
            # the drive's touch probe is switched off again
            assert int(w._loop.bus.touch_probe_function[0]) == 0    # type: ignore[union-attr]
        finally:
            w.stop()


def test_the_index_step_is_shown_and_every_set_point_keeps_the_limits() -> None:
    w = _worker(_spec(-2.0), 0.0)
    try:
        refs, steps = _home_traced(w, 20_000)
        assert w.snapshot().homing[0] is HomingState.DONE
    finally:
        w.stop()
    assert HomingStep.INDEX in steps and HomingStep.LATCH in steps
    x = np.array(refs)
    v = np.diff(x) / 0.001
    a = np.diff(v) / 0.001
    j = np.diff(a) / 0.001
    assert np.abs(v).max() <= 20.0 * (1 + 1e-9)
    assert np.abs(a).max() <= 2000.0 * (1 + 1e-6)
    assert np.abs(j).max() <= 400_000.0 * (1 + 1e-6)


def test_no_index_within_the_search_travel_is_an_alarm_naming_the_index_step() -> None:
    w = _worker(_spec(-2.0, travel=6.0), 0.0, pitch=0.0)        # an encoder without index
    try:
        _home(w)
        s = w.snapshot()
        assert s.state is WorkerState.QUICK_STOP and s.homing[0] is HomingState.ERROR
        alarm = s.alarms[-1]
        assert alarm.code is AlarmCode.HOMING_SWITCH
        assert "at step 'index': no index pulse within the search travel" in alarm.message
    finally:
        w.stop()


def test_a_drive_without_touch_probe_objects_refuses_index_homing_saying_why() -> None:
    w = _worker(_spec(-2.0), 0.0, unmapped_objects=(0x60B8, 0x60B9, 0x60BA))
    try:
        w.enable()
        w.step(20)
        x_before = w.snapshot().actual_position[0]
        with pytest.raises(WorkerError, match="no touch probe") as refused:
            w.home_to_switches([0])
        w.step(50)
        s = w.snapshot()
        assert s.homing[0] is not HomingState.DONE
        assert "no touch probe (0x60B8, 0x60B9, 0x60BA)" in s.alarms[-1].message, (refused.value, s.alarms)
        assert s.actual_position[0] == x_before                      # nothing moved
    finally:
        w.stop()


def test_the_drive_models_touch_probe_latches_the_zero_impulse_first_or_every_time() -> None:
    """CiA 402 touch probe 1 on the model: off -> status 0; armed on the zero impulse's positive
    edge -> enabled, then the edge stored with the index' position actual; first event kept
    until re-armed, continuous mode takes every index; re-arming clears the stored edge."""
    pitch = 50_000.0
    m = DriveModel(DriveParams(index_pitch_counts=pitch, index_phase_counts=1234.0))
    m.modes_of_operation = 8
    for cw in (0x06, 0x07, 0x0F):                  # shutdown, switch on, enable operation
        m.controlword = cw
        m.step(0.001)
        m.step(0.001)
    assert m.touch_probe_status == 0
    m.touch_probe_function = TP_INDEX_FIRST_POSITIVE
    target = 0.0
    seen = []
    for _ in range(400):                 # 250 counts a cycle: 100,000 counts, past two indexes
        target += 250.0
        m.target_position = int(target)
        m.step(0.001)
        seen.append((m.touch_probe_status, m.touch_probe_value))
    assert seen[0][0] == TP_ENABLED
    assert m.touch_probe_status == TP_ENABLED | TP_POSITIVE_STORED
    assert m.touch_probe_value == 1234                                # the first index passed
    assert m.read_object(0x60BA) == m.touch_probe_value and m.read_object(0x60B9) == 3
    first = m.touch_probe_value
    for _ in range(400):                  # past the next index: the first event is kept
        target += 250.0
        m.target_position = int(target)
        m.step(0.001)
    assert m.touch_probe_value == first
    m.touch_probe_function = 0
    m.step(0.001)
    assert m.touch_probe_status == 0
    m.write_object(0x60B8, 0, TP_INDEX_FIRST_POSITIVE | 0x02)      # continuous, by SDO
    values = set()
    for _ in range(1200):
        target += 250.0
        m.target_position = int(target)
        m.step(0.001)
        if m.touch_probe_status & TP_POSITIVE_STORED:
            values.add(m.touch_probe_value)
    assert len(values) >= 2 and all((v - 1234) % int(pitch) == 0 for v in values)
    assert math.isclose(sorted(values)[1] - sorted(values)[0], pitch)
