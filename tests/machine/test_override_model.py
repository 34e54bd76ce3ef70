"""The override model: the three knobs with their ranges (a value outside refused with the
reason, the knob as it was), the program's spindle lock and the spindle's cap; the controller's
commands and the spindle read it."""

from __future__ import annotations

import pytest

from app.machine.controller import MachineController
from app.machine.state.overrides import Override, Overrides


@pytest.mark.parametrize("override, good, bad, words", [
    (Override.FEED, 200.0, 200.5, "feed override must be 0-200 %, got 200.5"),
    (Override.RAPID, 0.0, 101.0, "rapid override must be 0-100 %, got 101"),
    (Override.SPINDLE, 50.0, 49.0, "spindle override must be 50-150 %, got 49"),
])
def test_each_knob_takes_its_range_and_refuses_the_rest(override: Override, good: float, bad: float,
                                                         words: str) -> None:
    o = Overrides()
    assert o.set(override, good) == ""
    assert o.set(override, bad) == words
    knobs = {Override.FEED: o.feed_pct, Override.RAPID: o.rapid_pct, Override.SPINDLE: o.spindle_pct}
    assert knobs[override] == good


def test_the_spindle_takes_the_knob_unless_locked_and_never_beyond_its_maximum() -> None:
    o = Overrides()
    assert o.set(Override.SPINDLE, 150.0) == ""
    assert o.spindle_pct_at(1000.0, 24000.0) == 150.0
    assert o.spindle_pct_at(20000.0, 24000.0) == pytest.approx(120.0)      # 20,000 x 1.2 = the top
    assert o.lock_spindle(True) and not o.lock_spindle(True)
    assert o.spindle_pct_at(1000.0, 24000.0) == 100.0                       # the program's S
    assert o.lock_spindle(False) and o.spindle_pct_at(1000.0, 24000.0) == 150.0


def test_the_controller_s_commands_set_the_model_the_spindle_turns_by(ctl: MachineController) -> None:
    assert ctl.set_feed_override(150) and ctl.set_rapid_override(25) and ctl.set_spindle_override(120)
    model = ctl.overrides
    assert (model.feed_pct, model.rapid_pct, model.spindle_pct) == (150.0, 25.0, 120.0)
    assert (ctl.feed_override_pct, ctl.rapid_override_pct) == (150.0, 25.0)
    refused = ctl.set_spindle_override(200)
    assert not refused and "spindle override must be 50-150 %, got 200" in refused.reason
    assert ctl.overrides.spindle_pct == 120.0
    assert ctl.mdi("S1000 M3")
    assert ctl.snapshot().spindle.commanded_rpm == pytest.approx(1200.0)
