"""G38.2-G38.5 run on the machine (real CyclicWorker + SimBus in manual mode; the shipped XYZ
mill's probe on bit 16 of Z's drive, its simulated stylus touching at Z <= -50 machine):
stop at the contact, the result in #5061-#5070, the rest of the program read again and run
from where the machine stands; the failures an operator must see."""

from __future__ import annotations

import re
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

from app.machine.controller import MachineController
from app.machine.model import MachineState, Severity
from planner.core.tools import Tool
from tests.machine.conftest import make_controller, refused_load, run_to_idle, trace

SURFACE_Z = -50.0
FEED_MM_MIN = 300.0


def _messages(ctl: MachineController) -> list[str]:
    out: list[str] = []
    ctl.message.connect(out.append)
    return out


def _run(ctl: MachineController, text: str) -> None:
    r = ctl.load_program(text, wait=True)
    assert r, r.reason
    assert ctl.cycle_start(wait=True)
    assert ctl.state is MachineState.RUNNING


PROBE_Z = f"""G21 G90 G54
G0 X10 Y5 Z-40
G38.2 Z-70 F{FEED_MM_MIN:g}
(DEBUG,touched #5063 #5070)
G0 Z[#5063 + 5]
G1 X20 F600
M2
"""


def test_the_probe_stops_at_the_contact_and_the_program_goes_on_from_its_result(
        ctl: MachineController) -> None:
    said = _messages(ctl)
    _run(ctl, PROBE_Z)
    run_to_idle(ctl)
    assert ctl.last_run is not None and ctl.last_run.completed, ctl.last_run
    debug = [m for m in said if m.startswith("touched")]
    assert len(debug) == 1, said
    z5063, tripped = (float(v) for v in re.findall(r"-?\d+\.\d+", debug[0]))
    step = FEED_MM_MIN / 60.0 * 0.001                  # travel in one 1 ms cycle
    assert tripped == 1.0
    # the actual position of the first cycle that reads the contact
    assert SURFACE_Z - 3 * step <= z5063 <= SURFACE_Z + 1e-4
    # the operator is told where it touched
    assert any(m.startswith("G38.2 (line 3): contact at X10.0000 Y5.0000 Z-50.00") for m in said), said
    t = trace(ctl)
    z_ref = t["reference"][:, 2]
    overtravel = SURFACE_Z - float(z_ref.min())
    # past the contact: the feed for the reaction (the feeder sees the latch within 10 ms
    # here, the stop is spliced a few cycles ahead of the drives), then the jerk-limited stop
    # along the path, v sqrt(v / J) from v = 5 mm/s at J = 10,000 mm/s^3 (0.11 mm)
    v, jerk = FEED_MM_MIN / 60.0, ctl.config.machine.limits.j_max_mm_s3
    stop_mm = v * np.sqrt(v / jerk)
    assert stop_mm < overtravel < stop_mm + v * 0.015, overtravel
    # what followed read the result: up 5 mm from the contact, then across
    assert ctl.machine_position[2] == pytest.approx(z5063 + 5.0, abs=1e-3)
    assert ctl.machine_position[0] == pytest.approx(20.0, abs=1e-3)
    assert ctl.last_run.limits and max(ctl.last_run.limits[k] for k in ("axis_a", "axis_j")) <= 1.0 + 1e-6


def test_no_contact_on_g38_2_is_an_alarm_and_the_program_stops_there(ctl: MachineController) -> None:
    _run(ctl, "G21 G90\nG0 X0 Y0 Z-10\nG38.2 Z-30 F600\nG0 Z0\nM2\n")
    assert ctl.run_until(lambda: ctl.state is MachineState.ALARM, 20.0), ctl.state_reason
    run_to_idle_or_alarm(ctl)
    alarm = [a for a in ctl.active_alarms if a.source == "probe"]
    assert len(alarm) == 1 and alarm[0].severity is Severity.STOP
    assert "G38.2 (line 3): the probe move ended without contact" in alarm[0].cause
    assert ctl.machine_position[2] == pytest.approx(-30.0, abs=1e-3)     # not the G0 Z0 after it
    assert ctl.last_run is not None and not ctl.last_run.completed
    assert ctl.run.resume_point is None          # nothing after a failed probe may be resumed


def run_to_idle_or_alarm(ctl: MachineController) -> None:
    assert ctl.run_until(lambda: ctl.stream.job is None and ctl.worker.buffer_level() == 0, 10.0)


def test_no_contact_on_g38_3_reads_5070_zero_and_goes_on(ctl: MachineController) -> None:
    said = _messages(ctl)
    _run(ctl, "G21 G90\nG0 Z-10\nG38.3 Z-30 F600\n(DEBUG,#5070 #5063)\nG0 Z[#5063 + 2]\nM2\n")
    run_to_idle(ctl)
    assert ctl.last_run is not None and ctl.last_run.completed
    assert "0.000000 -30.000000" in [m.strip() for m in said], said
    assert ctl.machine_position[2] == pytest.approx(-28.0, abs=1e-3)


def test_a_probe_touching_where_g38_2_starts_is_refused_before_it_moves(ctl: MachineController) -> None:
    _run(ctl, "G21 G90\nG0 Z-55\nG38.2 Z-60 F100\nM2\n")
    assert ctl.run_until(lambda: ctl.state is MachineState.ALARM, 20.0), ctl.state_reason
    run_to_idle_or_alarm(ctl)
    (alarm,) = [a for a in ctl.active_alarms if a.source == "probe"]
    assert "G38.2 (line 3): the probe already touches where the move starts" in alarm.cause
    assert ctl.machine_position[2] == pytest.approx(-55.0, abs=1e-3)


def test_g38_4_moves_until_the_contact_is_lost(ctl: MachineController) -> None:
    said = _messages(ctl)
    _run(ctl, "G21 G90\nG0 Z-40\nG1 Z-55 F600\nG38.4 Z-40 F120\n(DEBUG,#5063)\nM2\n")
    run_to_idle(ctl)
    assert ctl.last_run is not None and ctl.last_run.completed
    (value,) = [float(m) for m in said if re.fullmatch(r"\s*-?\d+\.\d+\s*", m)]
    assert SURFACE_Z < value <= SURFACE_Z + 3 * 120 / 60 * 0.001
    assert any("contact lost at" in m for m in said)


def test_the_rest_is_checked_against_the_soft_limits_with_the_result(ctl: MachineController) -> None:
    """Checked with the contact assumed at Z-70 the program stays inside the travel; with the
    contact at Z-50 it would go to X2000: an alarm, and the machine stays where it probed."""
    _run(ctl, "G21 G90\nG0 Z-40\nG38.2 Z-70 F600\nG0 X[[#5063 + 70] * 100]\nM2\n")
    assert ctl.run_until(lambda: ctl.state is MachineState.ALARM, 20.0), ctl.state_reason
    run_to_idle_or_alarm(ctl)
    (alarm,) = [a for a in ctl.active_alarms if a.source == "probe"]
    assert "G38.2 (line 3): with the result" in alarm.cause and "axis X" in alarm.cause
    assert ctl.machine_position[0] == pytest.approx(0.0, abs=1e-6)


def test_probing_in_mdi_stops_at_the_contact(ctl: MachineController) -> None:
    said = _messages(ctl)
    # the probe (only it may probe), its length 0 here: the tip is at the spindle's gauge line
    assert ctl.set_tool(Tool(99, 99, (("Z", 0.0),), 2.0, "3-D probe")) and ctl.set_tool_in_spindle(99)
    assert ctl.mdi("G0 Z-45")
    run_to_idle(ctl)
    assert ctl.mdi("G38.2 Z-60 F60")
    run_to_idle(ctl)
    assert abs(ctl.machine_position[2] - SURFACE_Z) < 0.05
    assert any("G38.2 (line 1): contact at" in m for m in said), said


def test_a_machine_without_a_probe_refuses_probing_programs_with_their_place(
        qapp, config_path: Path, state_dir: Path) -> None:
    text = config_path.read_text().replace("drive = 2                      # axis index", "# drive = 2")
    config_path.write_text(text)
    ctl = make_controller(config_path, state_dir)
    try:
        line, col, _, _ = refused_load(ctl, "G21 F100\nG0 Z-1\nN30 G38.3 Z-5\nM2\n", "needs a probe input")
        assert (line, col) == (3, 5)
        r = ctl.mdi("G38.2 Z-5 F100")
        assert not r and "needs a probe input" in r.reason
    finally:
        ctl.shutdown()


def test_a_stop_during_the_probe_move_disarms_the_probe(ctl: MachineController) -> None:
    _run(ctl, "G21 G90\nG0 Z-40\nG38.2 Z-70 F60\nM2\n")
    assert ctl.run_until(lambda: ctl.prober.run is not None, 10.0)
    assert ctl.stop()
    run_to_idle(ctl)
    assert ctl.prober.run is None
    assert ctl.worker.snapshot().probe.latch.name == "OFF"
    assert np.isfinite(ctl.machine_position[2])


def test_a_feed_hold_during_the_probe_move_holds_and_cycle_start_probes_on(ctl: MachineController) -> None:
    """Held just before the surface: the stop along the path crosses it, so the contact comes
    while holding. The program is read again with the result, but nothing moves until cycle
    start, and then it goes on from the contact."""
    said = _messages(ctl)
    _run(ctl, PROBE_Z)
    assert ctl.run_until(lambda: ctl.reference_position[2] < SURFACE_Z + 0.05, 20.0)
    assert ctl.feed_hold()
    ctl.advance(0.5)
    assert ctl.state is MachineState.HOLD
    held = ctl.reference_position
    assert held[2] < SURFACE_Z                                  # stopped past the surface
    ctl.advance(1.0)
    assert ctl.reference_position == held                       # the rest waits for cycle start
    assert ctl.resume()
    run_to_idle(ctl)
    assert ctl.last_run is not None and ctl.last_run.completed
    debug = [m for m in said if m.startswith("touched")]
    z5063 = float(debug[0].split()[1])
    assert ctl.machine_position[2] == pytest.approx(z5063 + 5.0, abs=1e-3)


def test_a_feed_hold_before_the_contact_keeps_the_probe_armed(ctl: MachineController) -> None:
    _run(ctl, PROBE_Z)
    assert ctl.run_until(lambda: ctl.prober.run is not None and ctl.reference_position[2] < -45.0, 20.0)
    assert ctl.feed_hold()
    ctl.advance(0.5)
    assert ctl.state is MachineState.HOLD and ctl.prober.run is not None
    assert ctl.reference_position[2] > SURFACE_Z
    assert ctl.resume()
    run_to_idle(ctl)
    assert ctl.last_run is not None and ctl.last_run.completed
    assert ctl.machine_position[0] == pytest.approx(20.0, abs=1e-3)


TWO_PROBES = f"""G21 G90 G54
G0 X10 Y5 Z-40
G38.2 Z-70 F{FEED_MM_MIN:g}
#<first> = #5063
G0 Z[#<first> + 5]
G1 X30 F600
G1 X60
G38.2 Z-70 F{FEED_MM_MIN:g}
(DEBUG,both #<first> #5063)
G0 Z[#5063 + 10]
M2
"""


def test_run_from_a_line_after_a_probe_is_refused_and_from_the_probe_line_probes_again(
        ctl: MachineController) -> None:
    said = _messages(ctl)
    assert ctl.load_program(TWO_PROBES, wait=True)
    r = ctl.run_from_line(6)
    assert not r and "line 6 comes after the probe at line 3" in r.reason and "run from line 3" in r.reason
    assert ctl.run_from_line(3, wait=True)
    run_to_idle(ctl, 40)
    assert ctl.last_run is not None and ctl.last_run.completed
    assert sum(m.startswith("G38.2 (line 3): contact at") for m in said) == 1
    assert sum(m.startswith("G38.2 (line 8): contact at") for m in said) == 1


def _estop_and_resume(ctl: MachineController, in_estop: Callable[[], bool] = lambda: True) -> None:
    """E-stop now (``in_estop`` must hold then), released, the alarm acknowledged, resume, run
    to the end."""
    assert ctl.estop("test")
    assert ctl.run_until(lambda: ctl.state is MachineState.ESTOP, 2.0)
    assert in_estop()
    assert ctl.estop_release()
    assert ctl.run_until(lambda: ctl.state is MachineState.IDLE, 5)
    assert ctl.acknowledge_alarm()
    assert ctl.resume(), ctl.state_reason
    run_to_idle(ctl, 40)


def test_an_estop_during_the_probe_move_resumes_from_its_start_with_the_probe_armed(
        ctl: MachineController) -> None:
    said = _messages(ctl)
    _run(ctl, PROBE_Z)
    assert ctl.run_until(lambda: ctl.prober.run is not None and ctl.reference_position[2] < -44.0, 20.0)
    _estop_and_resume(ctl, lambda: ctl.prober.run is None)     # disarmed with the job
    assert ctl.last_run is not None and ctl.last_run.completed, ctl.last_run
    assert any(m.startswith("G38.2 (line 3): contact at") for m in said), said
    assert ctl.machine_position[0] == pytest.approx(20.0, abs=1e-3)


def test_a_fault_after_a_probe_resumes_with_its_result_for_the_next_probe(ctl: MachineController) -> None:
    said = _messages(ctl)
    _run(ctl, TWO_PROBES)
    assert ctl.run_until(lambda: ctl.current_line == 7, 40.0)
    ctl.advance(0.3)
    _estop_and_resume(ctl)
    assert ctl.last_run is not None and ctl.last_run.completed, ctl.last_run
    (both,) = [m for m in said if m.startswith("both")]
    first, second = (float(v) for v in both.split()[1:])
    assert first == pytest.approx(SURFACE_Z, abs=0.01) and second == pytest.approx(SURFACE_Z, abs=0.01)
    assert ctl.machine_position[2] == pytest.approx(second + 10.0, abs=1e-3)


def test_a_probe_faster_than_the_stylus_allows_is_refused_with_its_place(ctl: MachineController) -> None:
    """Past the contact the stylus travels on for the reaction and the stop: at F3000 that is
    about 4 mm; the shipped mill allows up to 1000 mm/min ([probe] max_feed_mm_min)."""
    line, col, message, _ = refused_load(ctl, "G21 G90\nG0 Z-40\nN40 G38.2 Z-70 F3000\nM2\n",
                                      "F3000 mm/min is faster than the probe allows")
    assert (line, col) == (3, 5) and "max_feed_mm_min = 1000" in message
    r = ctl.mdi("G38.2 Z-70 F1200")
    assert not r and "F1200 mm/min is faster than the probe allows" in r.reason
    assert ctl.load_program("G21 G90\nG0 Z-40\nG38.2 Z-70 F1000\nM2\n", wait=True)


def test_a_stop_pressed_as_the_probe_touches_ends_the_program_there(ctl: MachineController) -> None:
    """The contact's own stop and the operator's come together: the program read again with the
    result must not set the machine moving after Stop."""
    _run(ctl, PROBE_Z)
    run = ctl.prober
    assert ctl.run_until(lambda: run.run is not None and run.run.trip_position is not None, 20.0)
    assert ctl.stop()
    run_to_idle(ctl)
    assert ctl.last_run is not None and not ctl.last_run.completed
    here = ctl.machine_position
    ctl.advance(1.0)
    assert ctl.machine_position == here and here[2] < SURFACE_Z


class _Waker:
    """A thread that waits 2 ms in a loop, as the feeder does, and keeps its longest wake-up
    gap: what the scheduler gave a 2 ms thread in this run (a shared box stretches it)."""

    def __init__(self) -> None:
        import threading

        self.longest_s = 0.0
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._main, daemon=True)
        self._thread.start()

    def _main(self) -> None:
        import time

        last = time.monotonic()
        while not self._stop.wait(0.002):
            now = time.monotonic()
            self.longest_s = max(self.longest_s, now - last)
            last = now

    def close(self) -> float:
        self._stop.set()
        self._thread.join(timeout=2.0)
        return self.longest_s


def test_the_probe_stops_in_real_time_as_in_simulated_time(qapp, config_path: Path, state_dir: Path) -> None:
    """The worker's own thread at 1 ms and the feeder thread every 2 ms (not the manual clock):
    the contact is latched and the motion stopped. Past the contact the axis runs on at the
    feed for the reaction (the feeder sees the latch, the stop is spliced a few cycles ahead of
    the drives), then stops jerk-limited. The reaction is bounded by what this run's scheduler
    gave a 2 ms thread (a shared box stretches it), never the queued lead."""
    import time

    ctl = MachineController(config_path, state_dir=state_dir, worker_mode="thread")
    said = _messages(ctl)
    waker = _Waker()
    try:
        assert ctl.connect_bus() and ctl.set_machine_zero_here()
        assert ctl.load_program(PROBE_Z, wait=True) and ctl.cycle_start(wait=True)
        t_end = time.monotonic() + 30.0
        while not (ctl.last_run is not None and ctl.state is MachineState.IDLE) and time.monotonic() < t_end:
            time.sleep(0.01)
            qapp.processEvents()
        longest_gap_s = waker.close()
        assert ctl.last_run is not None and ctl.last_run.completed, ctl.state_reason
        ts = ctl.config.machine.planner.ts_s
        z = trace(ctl)["reference"][:, 2]
        v, jerk = FEED_MM_MIN / 60.0, ctl.config.machine.limits.j_max_mm_s3
        step = v * ts
        contact = int(np.flatnonzero(z <= SURFACE_Z)[0])
        slower = np.flatnonzero(np.abs(np.diff(z[contact:])) < step * (1 - 1e-6))
        assert len(slower), "the axis never slowed down past the contact"
        reaction_s = float(slower[0]) * ts
        lowest = int(np.argmin(z))
        # the stop itself: jerk-limited from the feed, v sqrt(v / J) (0.11 mm)
        stop_mm = v * np.sqrt(v / jerk)
        assert float(z[contact + slower[0]] - z[lowest]) == pytest.approx(stop_mm, abs=2 * step)
        # the reaction: the feeder's wake-ups (two of this run's longest), then the stop takes
        # effect as far ahead of the drives as its splice went (the time to plan it, ~10 ms on an
        # idle machine, as this run's splices say on a busy one); the queued lead is 500 ms
        splices = [s for s in ctl.stream.recent_splices if s.serial >= 0]
        ahead_s = max((s.serial - s.consumed) * ts for s in splices)
        assert reaction_s <= 2 * longest_gap_s + ahead_s + 0.010, (reaction_s, longest_gap_s, ahead_s)
        assert any(m.startswith("G38.2 (line 3): contact at") for m in said), said
        assert ctl.machine_position[2] == pytest.approx(SURFACE_Z + 5.0, abs=0.01)   # up 5 from the contact
    finally:
        waker.close()
        ctl.shutdown()
