"""An operator who presses anything at any time: random sequences of cycle start, hold,
resume, stop, reset, E-stop and its release, overrides, single block, run from line, MDI,
jog steps and the spindle by hand, at random moments of a program with arcs, a dwell, a tap,
M49/M48 and M0, on the simulated
drives. Whatever happens: every command is done or refused with a reason, nothing escapes,
no set-point the drives received exceeds a limit, the spindle is off once a stop, a reset
or an E-stop has brought the axes to rest, and the machine ends idle or in E-stop."""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st

from app.machine.model import MachineState, RunSummary
from tests.machine.conftest import make_controller

PROGRAM = """G21 G90 G0 X0 Y0 Z5
S1200 M3
G1 X30 F1200
G3 X30 Y20 R10
G4 P0.2
M49
G1 X10 Y20
M48
G84 X40 Y10 Z-4 R1 F1500
G80
M0
G0 Z5
G1 X0 Y0 F900
M5
M30
"""
LIMIT_KEYS = ("tangential_v", "tangential_a", "tangential_j", "axis_v", "axis_a", "axis_j")

ACTIONS = st.one_of(
    st.sampled_from(["cycle_start", "hold", "resume", "stop", "reset", "estop", "release",
                     "single_on", "single_off"]),
    st.tuples(st.just("feed"), st.sampled_from([0, 10, 50, 100, 150, 200])),
    st.tuples(st.just("spindle"), st.sampled_from([50, 100, 150])),
    st.tuples(st.just("from_line"), st.integers(1, 15)),
    # between runs, at a hold or a stop: MDI, a jog step, the spindle by hand
    st.tuples(st.just("mdi"), st.sampled_from(["G91 G1 X2 F600", "G0 Z6", "M3 S3000", "M5", "G91 G0 Y-1"])),
    st.tuples(st.just("jog"), st.sampled_from(["X", "Y", "Z"])),
    st.sampled_from(["spindle_on", "spindle_off"]),
)
DELAYS_S = st.sampled_from([0.0, 0.01, 0.05, 0.2, 0.6, 1.5])
STEPS = st.lists(st.tuples(DELAYS_S, ACTIONS), min_size=1, max_size=12)


def act(ctl, action) -> object:
    if isinstance(action, tuple):
        what, value = action
        if what == "jog":
            return ctl.jog_increment(value, 1.0)
        return {"feed": ctl.set_feed_override, "spindle": ctl.set_spindle_override,
                "from_line": ctl.run_from_line, "mdi": ctl.mdi}[what](value)
    return {"cycle_start": ctl.cycle_start, "hold": ctl.feed_hold, "resume": ctl.resume, "stop": ctl.stop,
            "reset": ctl.reset, "estop": ctl.estop, "release": ctl.estop_release,
            "single_on": lambda: ctl.set_single_block(True),
            "spindle_on": ctl.spindle_on, "spindle_off": ctl.spindle_off,
            "single_off": lambda: ctl.set_single_block(False)}[action]()


# each example runs a machine for seconds of simulated time: few of them, and not shrunk (the
# failing sequence is printed as drawn)
@settings(max_examples=25, deadline=None, phases=[Phase.explicit, Phase.generate],
          suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(steps=STEPS, windowed=st.booleans())
def test_any_sequence_of_operator_actions_keeps_the_machine_safe(qapp, tmp_path_factory, steps,
                                                                 windowed: bool) -> None:
    """``windowed``: the program runs as a long one does, from a plan made as it runs (in
    segments of a few moves here)."""
    from app.machine.motion import plans
    from planner.motion import window

    saved = plans.WINDOWED_RUN_MOVES, window.WINDOW_SEGMENT_MOVES
    if windowed:
        plans.WINDOWED_RUN_MOVES, window.WINDOW_SEGMENT_MOVES = 0, 4
    try:
        _operate(qapp, tmp_path_factory, steps)
    finally:
        plans.WINDOWED_RUN_MOVES, window.WINDOW_SEGMENT_MOVES = saved


def _operate(qapp, tmp_path_factory, steps) -> None:
    from resources import shipped_machine

    root = tmp_path_factory.mktemp("op")
    config = root / "machine.toml"
    config.write_text(Path(shipped_machine("xyz_mill")).read_text(encoding="utf-8"), encoding="utf-8")
    ctl = make_controller(config, root / "state")
    runs: list[RunSummary] = []
    ctl.programFinished.connect(runs.append)
    try:
        assert ctl.load_program(PROGRAM, "fuzz.ngc", wait=True)
        assert ctl.cycle_start(wait=True)
        for delay, action in steps:
            ctl.advance(delay)
            r = act(ctl, action)
            if not r:
                assert r.reason, f"{action} refused without a reason"
            ctl.loader.wait_run_plan(None)     # a single-block plan made in the background
            if r and action in ("stop", "reset", "estop"):
                # the axes come to rest along the path (a stop) or at once (E-stop); then the
                # spindle is off
                assert ctl.run_until(lambda: ctl.state is not MachineState.RUNNING, 10)
                ctl.advance(0.3)
                if ctl.state in (MachineState.IDLE, MachineState.ESTOP):
                    assert not ctl.spindle.on, f"spindle on after {action} in {ctl.state}"
        # leave: stop whatever runs, and the machine ends idle (or in E-stop)
        ctl.stop()
        ctl.run_until(lambda: ctl.state in (MachineState.IDLE, MachineState.ESTOP), 15)
        ctl.reset()                                          # a prompt (M0) or an alarm left
        ctl.run_until(lambda: ctl.state in (MachineState.IDLE, MachineState.ESTOP), 15)
        assert ctl.state in (MachineState.IDLE, MachineState.ESTOP), (ctl.state, ctl.state_reason)
        assert runs, "the run started first never ended"
        for run in runs:
            for key in LIMIT_KEYS:
                assert run.limits[key] <= 1.0 + 1e-6, (key, run.limits[key], steps)
    finally:
        ctl.shutdown()


@pytest.mark.parametrize("steps", [
    [(0.6, "hold"), (0.2, "single_on"), (0.2, "resume"), (1.5, "cycle_start"), (0.2, ("feed", 200)),
     (0.6, "stop")],
    [(0.6, ("feed", 150)), (1.5, "estop"), (0.2, "release"), (0.2, ("from_line", 9)), (0.6, "hold"),
     (0.2, "reset")],
    # run from line twice while running: refused; the stop at the end takes its time
    [(0.2, ("spindle", 50)), (0.6, ("feed", 50)), (0.2, ("feed", 100)), (1.5, ("from_line", 3)),
     (1.5, ("spindle", 150)), (1.5, ("from_line", 10)), (1.5, ("feed", 150)), (0.05, ("spindle", 150))],
])
@pytest.mark.parametrize("windowed", [False, True])
def test_known_sequences(qapp, tmp_path_factory, steps, windowed: bool) -> None:
    test_any_sequence_of_operator_actions_keeps_the_machine_safe.hypothesis.inner_test(
        qapp, tmp_path_factory, steps, windowed)
