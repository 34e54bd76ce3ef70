"""A spindle run by a VFD through the real controller on simulated drives (manual clock): its
run and direction on the spindle's output bits, its speed on an analog output terminal's
channel (0-10 V for 0 to ``analog_rpm_at_10v``), S x the override sent as the terminal's INT16
and never beyond 10 V; ``[spindle] analog_out`` read and checked at its line."""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest

from app.machine.config import config_from_dict, config_to_toml, load_config
from app.machine.errors import ConfigError
from ethercat.terminals import ANALOG_FULL_SCALE, analog_channels
from resources import shipped_machine
from tests.machine.conftest import TEST_LEAD_S, make_controller

MILL = shipped_machine("xyz_mill").read_text(encoding="utf-8")
EL4002 = '[[bus.terminals]]\nposition = 8\ntype = "EL4002"\nname = "spindle speed"\n'
VFD = '[spindle]\nanalog_out = "8:1"\nanalog_rpm_at_10v = 20000.0\n'
AOUT = 5                      # the EL4002's index among the mill's terminals (after 3 .. 7)


def _config(tmp_path: Path, spindle: str = VFD, terminal: str = EL4002) -> Path:
    p = tmp_path / "machine.toml"
    p.write_text(MILL + f"\n{terminal}\n{spindle}\n[controller]\nlead_s = {TEST_LEAD_S}\n", encoding="utf-8")
    return p


def _volts(c) -> float:  # type: ignore[no-untyped-def]
    """Channel 1 of the EL4002 as the bus carries it, in volts."""
    word = c.worker.snapshot().terminal_outputs[AOUT]
    return analog_channels(word, 2)[1] * 10.0 / ANALOG_FULL_SCALE


def test_the_vfd_gets_s_times_the_override_as_volts_and_its_bits(qapp, tmp_path: Path) -> None:
    state = tmp_path / "state"
    state.mkdir()
    c = make_controller(_config(tmp_path), state)
    try:
        assert c.mdi("M3 S6000")
        c.advance(0.05)
        assert _volts(c) == pytest.approx(3.0, abs=5e-4)            # 6000 of 20000 rpm at 10 V
        assert c.worker.snapshot().digital_outputs[0] & 0b11 == 0b01  # run, clockwise
        assert c.set_spindle_override(150)
        c.advance(0.05)
        assert _volts(c) == pytest.approx(4.5, abs=5e-4)
        assert c.mdi("M4 S20000")                       # 150 % capped at 24000 rpm: beyond 10 V, 10 V
        c.advance(0.05)
        assert _volts(c) == pytest.approx(10.0, abs=5e-4)
        assert c.worker.snapshot().digital_outputs[0] & 0b11 == 0b11  # run, counter-clockwise
        # channel 0 of the terminal is left as it was
        assert analog_channels(c.worker.snapshot().terminal_outputs[AOUT], 2)[0] == 0
        assert c.mdi("M5")
        c.advance(0.05)
        assert _volts(c) == 0.0 and c.worker.snapshot().digital_outputs[0] & 0b11 == 0
        assert c.mdi("M3 S8000")
        c.advance(0.05)
        assert _volts(c) > 0.0
        c.estop("test")
        c.advance(0.05)
        assert _volts(c) == 0.0                                     # E-stop: no speed either
    finally:
        c.shutdown()


def test_the_analog_output_is_read_round_trip_and_refused_at_its_line(tmp_path: Path) -> None:
    cfg = load_config(_config(tmp_path))
    assert (cfg.spindle.analog_out, cfg.spindle.analog_rpm_at_10v) == ("8:1", 20000.0)
    again = config_from_dict(tomllib.loads(config_to_toml(cfg)), str(tmp_path / "machine.toml"))
    assert again.spindle == cfg.spindle
    for spindle, why in (('[spindle]\nanalog_out = "4:1"\n', "slave 4 is a EL1008, not an analog output"),
                         ('[spindle]\nanalog_out = "8:2"\n', "a EL4002 has channels 0..1, not 2"),
                         ('[spindle]\nanalog_out = "!8:0"\n', "no normally closed contact"),
                         ('[spindle]\nanalog_out = "8:0"\ndrive = 9\n', "one or the other")):
        p = _config(tmp_path, spindle)
        with pytest.raises(ConfigError, match=why) as err:
            load_config(p)
        line = next(k for k, s in enumerate(p.read_text().splitlines(), 1) if s.startswith("analog_out"))
        assert f"machine.toml:{line}: spindle.analog_out" in str(err.value)
