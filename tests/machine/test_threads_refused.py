"""What this machine reads as LinuxCNC reads it but cannot run: G33 and G76 (the spindle has no
encoder to start every pass of a thread at the same angle), M67/M68 (no analog outputs). The
refusal names the line and the word, in a program, in MDI, and where a probe's result leads a
program to one."""

from __future__ import annotations

import pytest

from app.machine.controller import MachineController
from app.machine.model import MachineState
from tests.machine.conftest import refused_load, run_to_idle
from tests.machine.test_probing_run import run_to_idle_or_alarm

REASON = "spindle-synchronised motion"


def test_a_threading_program_is_refused_at_its_line_and_no_program_is_kept(ctl: MachineController) -> None:
    line, col, message, _ = refused_load(ctl, "G21 M3 S500\nG0 X10 Z5\nN30 G76 P1.5 Z-20 I-1 J0.1 K0.9\nM2\n",
                                         REASON)
    assert (line, col) == (3, 5) and message.startswith("G76 is spindle-synchronised")
    assert "no encoder" in message
    assert ctl.program_info is None
    assert not ctl.cycle_start(wait=True)
    assert ctl.machine_position == pytest.approx([0.0, 0.0, 0.0])


def test_a_modal_g33_line_is_refused_where_it_is(ctl: MachineController) -> None:
    line, col, _, reason = refused_load(ctl, "G21 M3 S500\nG0 Z5\nG1 X1 F100\nG33 Z-5 K1\nM4\nZ5 K1\nM2\n",
                                        "G33 is spindle-synchronised")
    assert (line, col) == (4, 1) and reason.startswith("line 4: G33 is spindle-synchronised")
    r = ctl.load_program("G21 M3 S500\nG0 Z5\nG33 Z-5 K1 X1\nM4\nX0 Z5 K1\nM2\n", wait=True)
    assert not r and r.reason.startswith("line 3: G33 is spindle-synchronised")


def test_g33_in_mdi_is_refused_and_nothing_moves(ctl: MachineController) -> None:
    r = ctl.mdi("G21 M3 S500 G33 Z-5 K1")
    assert not r and REASON in r.reason
    assert ctl.state is MachineState.IDLE
    assert ctl.machine_position == pytest.approx([0.0, 0.0, 0.0])


def test_a_probe_result_that_leads_to_a_thread_stops_the_run_with_the_reason(ctl: MachineController) -> None:
    """Checked with no contact (as LinuxCNC's preview reads a probe) the program never reaches
    its G33; the contact at Z-50 leads it there: an alarm, and the machine stays where it probed."""
    program = ("G21 G90\nG0 Z-40\nG38.3 Z-70 F600\no1 if [#5070 EQ 1]\nM3 S500\nG33 Z-45 K1\no1 endif\n"
               "M2\n")
    assert ctl.load_program(program, wait=True)
    assert ctl.cycle_start(wait=True)
    assert ctl.run_until(lambda: ctl.state is MachineState.ALARM, 20.0), ctl.state_reason
    run_to_idle_or_alarm(ctl)
    (alarm,) = [a for a in ctl.active_alarms if a.source == "probe"]
    assert "G38.3 (line 3): with the result, line 6: G33 is spindle-synchronised" in alarm.cause
    assert -51.0 < ctl.machine_position[2] < -50.0          # the contact, and the stop past it


def test_rigid_tapping_still_runs(ctl: MachineController) -> None:
    assert ctl.load_program("G21 M3 S500\nG0 X10 Z5\nG33.1 Z-5 K1\nM2\n", wait=True)
    assert ctl.cycle_start(wait=True)
    run_to_idle(ctl)
    assert ctl.last_run is not None and ctl.last_run.completed


def test_analog_outputs_are_refused_at_their_line_in_a_program_and_in_mdi(ctl: MachineController) -> None:
    line, col, _, _ = refused_load(ctl, "G21 F600\nG1 X5\nN30 M68 E0 Q50\nG1 X10\nM2\n",
                                "M68 E0 sets an analog output, and this machine has none")
    assert (line, col) == (3, 5)
    assert ctl.program_info is None
    r = ctl.mdi("M67 E1 Q3 G1 X1 F100")
    assert not r and "M67 E1 sets an analog output" in r.reason
    assert ctl.machine_position == pytest.approx([0.0, 0.0, 0.0])
