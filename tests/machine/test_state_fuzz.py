"""The state folder after a power cut, a full disk or a hand edit: each file the controller
keeps (position and homed state, work offsets, G-code parameters, tools, alarms) damaged at
random. Whatever a file holds, the controller starts, says what it did not take, and never
starts from a position or an offset that is not a number."""

from __future__ import annotations

import json
import math
import shutil
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tests.machine.conftest import make_controller

FILES = ("state.json", "offsets.json", "parameters.json", "tool.json", "alarms.json", "tools.tbl")
json_values = st.recursive(
    st.none() | st.booleans() | st.integers(-10**20, 10**20) | st.text(max_size=6)
    | st.sampled_from([float("nan"), float("inf"), -float("inf"), 1e308, -0.0, 2.5]),
    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=5), inner, max_size=3),
    max_leaves=8)


@pytest.fixture(scope="module")
def saved_state(tmp_path_factory, qapp) -> Path:
    """A state folder as a controller leaves it: moved, offsets and a G92 set, a tool in, an
    E-stop in the alarm log."""
    from planner.core.tools import Tool
    from resources import shipped_machine

    root = tmp_path_factory.mktemp("saved")
    config = root / "machine.toml"
    shutil.copyfile(shipped_machine("xyz_mill"), config)
    ctl = make_controller(config, root / "state")
    try:
        assert ctl.jog_increment("X", 1.0)
        ctl.advance(0.5)
        assert ctl.set_work_offset("G55", (10.0, 20.0, -5.0))
        assert ctl.set_tool(Tool(3, 3, (("Z", 12.5),), 6.0, "six"))
        assert ctl.set_tool_in_spindle(3)
        assert ctl.mdi("G92 X0 Y0")
        ctl.advance(0.2)
        assert ctl.estop()                                  # an alarm in the log
        assert ctl.estop_release()
    finally:
        ctl.shutdown()
    return root


@st.composite
def damage(draw) -> tuple[str, str]:
    name = draw(st.sampled_from(FILES))
    how = draw(st.sampled_from(["value", "truncate", "garbage", "whole"]))
    return name, how + ":" + json.dumps(draw(json_values)) + ":" + str(draw(st.integers(0, 10_000)))


def _damaged(text: str, name: str, how: str, value: object, cut: int) -> str:
    if how == "truncate":
        return text[:cut % (len(text) + 1)]
    if how == "garbage":
        return text[:cut % (len(text) + 1)] + "\x00{]]" + text[cut % (len(text) + 1):]
    if how == "whole" or not name.endswith(".json"):
        return json.dumps(value) if name.endswith(".json") else f"T{value}\n"
    data = json.loads(text)
    if isinstance(data, dict) and data:                  # one value of the file replaced
        key = sorted(data)[cut % len(data)]
        data[key] = value
    elif isinstance(data, list) and data and isinstance(data[0], dict):
        item = data[cut % len(data)]
        if item:
            item[sorted(item)[cut % len(item)]] = value
    return json.dumps(data)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(case=damage())
def test_any_damaged_state_file_is_named_and_never_a_position(qapp, saved_state, tmp_path_factory,
                                                              case) -> None:
    name, spec = case
    how, rest = spec.split(":", 1)
    value_text, cut = rest.rsplit(":", 1)
    root = tmp_path_factory.mktemp("damaged")
    shutil.copytree(saved_state, root, dirs_exist_ok=True)
    path = root / "state" / name
    assert path.exists(), name
    path.write_text(_damaged(path.read_text(encoding="utf-8"), name, how, json.loads(value_text), int(cut)),
                    encoding="utf-8")
    ctl = make_controller(root / "machine.toml", root / "state", zero=False)
    try:
        assert all(math.isfinite(v) for v in ctl.machine_position), ctl.machine_position
        assert all(math.isfinite(v) for v in ctl.work_position), ctl.work_position
        for offset in ctl.work_offsets.values():
            assert all(math.isfinite(v) for v in offset), offset
        g92 = ctl.g92_offset
        if g92 is not None:
            assert all(math.isfinite(v) for v in g92), g92
        said = [a.cause for a in ctl.alarms if name in a.cause]
        if name == "state.json" and said:
            assert not any(ctl.homed), said              # a position not taken: home again
    finally:
        ctl.shutdown()


@pytest.mark.parametrize(("name", "spec"), [
    # each stopped the panel from starting once
    ("offsets.json", "value:[null, null, null]:0"),
    ("alarms.json", "value:Infinity:2208"),
    ("state.json", "value:null:1"),                      # axes
    # a position that is not a number, and a homed state that is not true/false: not taken
    ("state.json", "value:[NaN, 0, 0]:4"),               # raw_position
    ("state.json", 'value:"yes":3'),                     # homed
])
def test_damage_found_before(qapp, saved_state, tmp_path_factory, name: str, spec: str) -> None:
    test_any_damaged_state_file_is_named_and_never_a_position.hypothesis.inner_test(
        qapp, saved_state, tmp_path_factory, (name, spec))


def test_a_damaged_alarm_is_left_out_and_said(qapp, saved_state, tmp_path) -> None:
    shutil.copytree(saved_state, tmp_path, dirs_exist_ok=True)
    path = tmp_path / "state" / "alarms.json"
    data = json.loads(path.read_text(encoding="utf-8"))
    assert len(data) >= 1
    data[0]["severity"] = "high"
    path.write_text(json.dumps(data), encoding="utf-8")
    ctl = make_controller(tmp_path / "machine.toml", tmp_path / "state", zero=False)
    try:
        assert any("alarms.json: 1 damaged alarm(s) left out" in a.cause for a in ctl.alarms)
    finally:
        ctl.shutdown()


def test_a_homed_state_that_is_not_true_or_false_is_not_taken(qapp, saved_state, tmp_path) -> None:
    shutil.copytree(saved_state, tmp_path, dirs_exist_ok=True)
    path = tmp_path / "state" / "state.json"
    data = json.loads(path.read_text(encoding="utf-8"))
    assert data["homed"] == [True, True, True] and not data["running"]      # homed, shut down cleanly
    data["homed"] = "yes"
    path.write_text(json.dumps(data), encoding="utf-8")
    ctl = make_controller(tmp_path / "machine.toml", tmp_path / "state", zero=False)
    try:
        assert ctl.homed == (False, False, False)
        assert any("state.json" in a.cause and "homed" in a.cause for a in ctl.alarms)
    finally:
        ctl.shutdown()
