"""Machine configuration: the shipped files load, and bad values are refused with the file,
the key and the value in the message (never silently replaced by defaults)."""

from __future__ import annotations

import pytest

from planner.errors import PlannerError
from planner.machine import MachineSpec, load_machine, machine_from_dict
from resources import shipped_machine


def test_shipped_xyz_mill_loads() -> None:
    m = load_machine(shipped_machine("xyz_mill"))
    assert m.axis_names == ("X", "Y", "Z")
    assert m.rotary == (False, False, False)
    assert m.limits.v_max_mm_s == 30.0 and m.limits.a_max_mm_s2 == 1000.0
    assert m.limits.j_max_mm_s3 == 10_000.0
    assert m.planner.mode == "lookahead" and m.planner.ts_s == 0.001
    assert set(m.work_offsets) == {"G54", "G55", "G56", "G57", "G58", "G59"}


def test_shipped_paper_machine_is_y_z_c_a() -> None:
    m = load_machine(shipped_machine("paper_yzca"))
    assert m.axis_names == ("Y", "Z", "C", "A")
    assert m.rotary == (False, False, True, True)
    assert m.axes[2].unit == "deg"


def test_default_machine() -> None:
    m = MachineSpec.default()
    assert m.axis_names == ("X", "Y", "Z")
    assert m.offset("G55") == (0.0, 0.0, 0.0)


def _axis(**over):
    a = {"name": "X", "min": -10.0, "max": 10.0, "v_max": 10.0, "a_max": 100.0, "j_max": 1000.0}
    a.update(over)
    return a


@pytest.mark.parametrize("axis, fragment", [
    (_axis(name="Q"), "name must be one of"),
    (_axis(min=5.0, max=1.0), "min (5.0) must be below max (1.0)"),
    (_axis(v_max=-1.0), "'v_max' must be greater than 0"),
    (_axis(a_max="fast"), "'a_max' must be a number"),
    (_axis(direction=2), "direction must be 1 or -1"),
    (_axis(kind="spiral"), "kind must be 'linear' or 'rotary'"),
])
def test_bad_axis_values_are_refused(axis, fragment) -> None:
    with pytest.raises(PlannerError, match="m.toml") as info:
        machine_from_dict({"axes": [axis]}, "m.toml")
    assert fragment in str(info.value)


def test_bad_planner_mode_is_refused() -> None:
    with pytest.raises(PlannerError, match="planner mode must be one of"):
        machine_from_dict({"axes": [_axis()], "planner": {"mode": "fast"}}, "m.toml")


def test_offset_with_wrong_axis_count_is_refused() -> None:
    with pytest.raises(PlannerError, match=r"\[offsets\] G54 needs 1 numbers"):
        machine_from_dict({"axes": [_axis()], "offsets": {"G54": [1.0, 2.0]}}, "m.toml")


def test_damaged_file_says_so(tmp_path) -> None:
    path = tmp_path / "broken.toml"
    path.write_text("[[axes]]\nname = \"X\"\nmin = ", encoding="utf-8")
    with pytest.raises(PlannerError, match="not a valid TOML file"):
        load_machine(path)


def test_missing_file_says_so(tmp_path) -> None:
    with pytest.raises(PlannerError, match="not found"):
        load_machine(tmp_path / "nope.toml")
