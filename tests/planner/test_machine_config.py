"""Machine configuration: the shipped files load, and bad values are refused with the file,
the key and the value in the message (never silently replaced by defaults)."""

from __future__ import annotations

from datetime import timedelta

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from planner.core.errors import PlannerError
from planner.core.machine import MachineSpec, load_machine, machine_from_dict
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
    (_axis(name="Q"), "axes[0].name: must be one of 'X', 'Y', 'Z', 'A', 'B', 'C', got 'Q'"),
    (_axis(min=5.0, max=1.0), "min (5.0) must be below max (1.0)"),
    (_axis(v_max=-1.0), "axes[0].v_max: must be within [0.001, 100000], got -1.0"),
    (_axis(a_max="fast"), "axes[0].a_max: must be a number, got 'fast'"),
    (_axis(direction=2), "axes[0].direction: must be one of 1, -1, got 2"),
    (_axis(direction=1.5), "axes[0].direction: must be a whole number, got 1.5"),
    (_axis(drive_position=0.7), "axes[0].drive_position: must be a whole number, got 0.7"),
    (_axis(kind="spiral"), "axes[0].kind: must be one of 'linear', 'rotary', got 'spiral'"),
    (_axis(counts_per_unit=1e300), "axes[0].counts_per_unit: must be within [0.001, 1e+09], got 1e+300"),
    (_axis(j_max=1e-300), "axes[0].j_max: must be within [0.001, 1e+10], got 1e-300"),
    (_axis(counts_per_unit=10_000_000.0, min=-250.0, max=250.0),
     "beyond what the drive's 32-bit position holds"),
    (_axis(following_error_windw=1.0), "axes[0].following_error_windw: unknown key (did you mean "
                                       "'following_error_window'?)"),
])
def test_bad_axis_values_are_refused(axis, fragment) -> None:
    with pytest.raises(PlannerError, match="m.toml") as info:
        machine_from_dict({"axes": [axis]}, "m.toml")
    assert fragment in str(info.value)


def test_bad_planner_mode_is_refused() -> None:
    with pytest.raises(PlannerError, match="planner.mode: must be one of 'lookahead', 'paper', got 'fast'"):
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


@pytest.mark.parametrize("data, fragment", [
    ({"planner": "fast"}, "planner: must be a table"),
    ({"limits": 5}, "limits: must be a table"),
    ({"axes": [1, 2]}, "axes: must be [[axes]] tables"),
    ({"bus": {"drives": "abc"}}, "bus.drives: must be [[bus.drives]] tables"),
    ({"limitz": {}}, "limitz: unknown section (did you mean 'limits'?)"),
    ({"limits": {"vmax_mm_s": 5.0}}, "limits.vmax_mm_s: unknown key (did you mean 'v_max_mm_s'?)"),
    ({"planner": {"ts": 0.001}}, "planner.ts: unknown key (did you mean 'ts_s'?)"),
    ({"offsets": {"G60": [0.0]}}, "offsets.G60: unknown key"),
    ({"planner": {"ts_s": True}}, "planner.ts_s: must be a number, got True"),
    ({"limits": {"a_max_mm_s2": float("nan")}}, "limits.a_max_mm_s2: must be a finite number"),
])
def test_strict_schema_refuses_with_the_key(data, fragment) -> None:
    """Wrong shapes and misspelled keys are errors naming the key, never a traceback and
    never silently ignored in favour of a default."""
    with pytest.raises(PlannerError) as info:
        machine_from_dict({"axes": [_axis()], **data}, "m.toml")
    assert fragment in str(info.value)


def test_errors_carry_the_line_of_the_key(tmp_path) -> None:
    path = tmp_path / "m.toml"
    path.write_text(shipped_machine("xyz_mill").read_text(encoding="utf-8")
                    .replace("following_error_window = 1.0", "following_error_windw = 1.0", 2)
                    .replace("following_error_windw = 1.0", "following_error_window = 1.0", 1),
                    encoding="utf-8")
    line = [n for n, t in enumerate(path.read_text().splitlines(), 1) if "windw" in t][0]
    with pytest.raises(PlannerError) as info:
        load_machine(path)
    assert str(info.value).startswith(f"{path}:{line}: axes[1].following_error_windw: unknown key")


def test_a_directory_or_unreadable_file_is_a_clear_error(tmp_path) -> None:
    with pytest.raises(PlannerError, match="is a folder, not a machine configuration"):
        load_machine(tmp_path)


@settings(max_examples=150, deadline=None)
@given(st.recursive(st.none() | st.booleans() | st.integers() | st.floats() | st.text(max_size=8),
                    lambda children: st.lists(children, max_size=4)
                    | st.dictionaries(st.sampled_from(["axes", "limits", "planner", "offsets", "name", "min",
                                                       "max", "v_max", "a_max", "j_max", "G54", "bus",
                                                       "drives", "kind", "x"]), children, max_size=5),
                    max_leaves=25))
def test_any_parsed_structure_is_accepted_or_refused_with_a_planner_error(data) -> None:
    """Fuzz: whatever structure a TOML file parses to, reading it gives a machine or a
    PlannerError, nothing else."""
    try:
        machine_from_dict(data if isinstance(data, dict) else {"axes": data}, "f.toml")
    except PlannerError:
        pass


def test_a_truncated_panel_written_file_is_refused_by_cnc_plan_too(tmp_path) -> None:
    """The panel marks the end of the files it writes; cut short, the rest may still parse,
    and then cnc-plan refuses it as the panel does."""
    from app.machine.config import load_config, save_config

    path = tmp_path / "m.toml"
    path.write_text(shipped_machine("xyz_mill").read_text(encoding="utf-8"), encoding="utf-8")
    save_config(load_config(path), path)
    text = path.read_text(encoding="utf-8")
    cut = text[: text.index("[controller]")]            # still a valid configuration
    path.write_text(cut, encoding="utf-8")
    with pytest.raises(PlannerError, match="damaged file, truncated"):
        load_machine(path)


def test_a_work_offset_outside_the_travel_is_refused() -> None:
    with pytest.raises(PlannerError, match=r"offsets\.G55: X 30 is outside the axis travel \[-10, 10\]"):
        machine_from_dict({"axes": [_axis()], "offsets": {"G55": [30.0]}}, "m.toml")


_SHIPPED = shipped_machine("xyz_mill").read_text(encoding="utf-8")


def _read_or_refused(path, text: str) -> None:
    """Both readers (cnc-plan's and the panel's) give a machine or their error naming the file."""
    from app.machine.config import load_config
    from app.machine.errors import ConfigError

    path.write_text(text, encoding="utf-8")
    try:
        load_machine(path)
    except PlannerError as exc:
        assert str(exc).startswith(str(path))
    try:
        load_config(path)
    except ConfigError as exc:
        assert str(path) in str(exc)


# broken characters, and whole values (a string, an array, an inline table); the structured fuzz
# below puts values of every kind at every key
_INSERTS = ["", "0", "1.5", "-", "x", "=", "[", "]", "\"", "\n", "#", "1e400", "nan", "inf", "true", "0x",
            ".", "[[axes]]\n", "[limits]\n", "é", '"fast"', "[1, 2]", "{ a = 1 }", "[[bus.drives]]\n"]


@settings(max_examples=300, deadline=timedelta(seconds=2))
@given(st.lists(st.tuples(st.integers(0, len(_SHIPPED)), st.integers(0, 8), st.sampled_from(_INSERTS)),
                max_size=6))
def test_mutated_configuration_files_read_or_fail_with_the_file_named(tmp_path_factory, edits) -> None:
    """Fuzz: a configuration file damaged anywhere gives a machine or a PlannerError naming the
    file (and a ConfigError from the panel's reader), never another exception, in bounded time."""

    text = _SHIPPED
    for pos, cut, ins in edits:
        pos = min(pos, len(text))
        text = text[:pos] + ins + text[pos + cut:]
    _read_or_refused(tmp_path_factory.mktemp("fuzz") / "m.toml", text)



def _paths(data, prefix=()):
    """Every (path, value) of a parsed TOML document, tables and arrays of tables descended."""
    if isinstance(data, dict):
        for k, v in data.items():
            yield (*prefix, k), v
            yield from _paths(v, (*prefix, k))
    elif isinstance(data, list) and data and all(isinstance(v, dict) for v in data):
        for i, v in enumerate(data):
            yield from _paths(v, (*prefix, i))


_PARSED = __import__("tomllib").loads(_SHIPPED)
_KEY_PATHS = [p for p, _ in _paths(_PARSED)]
_VALUES = st.recursive(
    st.none().map(lambda _: "x") | st.booleans() | st.integers(-2**40, 2**40)
    | st.floats(allow_nan=True, allow_infinity=True) | st.text(max_size=6),
    lambda inner: st.lists(inner, max_size=3) | st.dictionaries(st.sampled_from(["a", "name", "min"]), inner,
                                                               max_size=2),
    max_leaves=6)


@settings(max_examples=300, deadline=timedelta(seconds=2))
@given(st.lists(st.tuples(st.sampled_from(_KEY_PATHS), _VALUES), min_size=1, max_size=3))
def test_a_value_of_any_kind_at_any_key_is_read_or_refused_with_its_key(tmp_path_factory, changes) -> None:
    """Structured fuzz: the shipped configuration with values of every kind put at its keys,
    written as TOML: a machine or an error naming the file, never another exception."""
    import copy

    import tomlkit


    data = copy.deepcopy(_PARSED)
    for path, value in changes:
        node = data
        try:                          # an earlier change may have replaced a table on this path
            for part in path[:-1]:
                node = node[part]
            node[path[-1]] = value
        except (KeyError, IndexError, TypeError):
            continue
    try:
        text = tomlkit.dumps(data)
    except Exception:  # noqa: BLE001 - not expressible as TOML (e.g. a nested None): nothing to read
        return
    _read_or_refused(tmp_path_factory.mktemp("fuzz") / "m.toml", text)
