"""One configuration check for every reader: each rule at its boundary, just refused and just
accepted, gives the same verdict and the same message through ``cnc-plan --config``,
``cnc-run``, the panel's loader and (where an Axes page field sets it) the Axes page."""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from app.config_edit import validate as axes_page_validate
from app.config_edit import with_axis, with_limits, with_planner
from app.machine.config import MachineConfig, config_to_toml, load_config
from app.machine.errors import ConfigError
from cli.plan import main as plan_main

BASE = MachineConfig.default()
X = BASE.machine.axes[0]
TRAVEL_X = X.max_pos - X.min_pos
LONGEST = max(a.max_pos - a.min_pos for a in BASE.machine.axes if not a.rotary)
NEW_DRIVE = len(BASE.bus.drives)      # the index of a drive table added after the shipped ones


@dataclass(frozen=True)
class Case:
    key: str                      # the dotted key the refusal names
    edit: Callable[[str], str]    # the file's text with the rule's value
    page: Callable[[MachineConfig], MachineConfig] | None = None   # the same through the Axes page


def _set(section: str, key: str, value: str) -> Callable[[str], str]:
    def edit(text: str) -> str:
        lines = text.splitlines()
        start = lines.index(f"[{section}]") if f"[{section}]" in lines else lines.index(f"[[{section}]]")
        for i in range(start + 1, len(lines)):
            if lines[i].startswith(f"{key} ="):
                lines[i] = f"{key} = {value}"
                return "\n".join(lines) + "\n"
            if lines[i].startswith("["):
                break
        lines.insert(start + 1, f"{key} = {value}")
        return "\n".join(lines) + "\n"
    return edit


def _append(block: str) -> Callable[[str], str]:
    return lambda text: text.replace("[controller]", block + "\n[controller]", 1)


def _replace_drive(position: int, block: str) -> Callable[[str], str]:
    """The shipped table of slave ``position`` taken out (one table a drive) and ``block`` added."""
    def edit(text: str) -> str:
        lines = text.splitlines()
        start = next(i for i, line in enumerate(lines)
                     if line == "[[bus.drives]]" and lines[i + 1] == f"position = {position}")
        end = next((i for i in range(start + 1, len(lines)) if lines[i].startswith("[")), len(lines))
        return _append(block)("\n".join(lines[:start] + lines[end:]) + "\n")
    return edit


def cases(refused: bool) -> list[Case]:
    f = 0.98 if refused else 1.02
    window = (0.5 if refused else 1.0) / X.counts_per_unit
    return [
        Case("planner.ts_s", _set("planner", "ts_s", repr(9.9e-5 if refused else 1e-4)),
             lambda c: with_planner(c, ts_s=9.9e-5 if refused else 1e-4)),
        Case("axes[0].following_error_window", _set("axes", "following_error_window", repr(window)),
             lambda c: with_axis(c, 0, following_error_window=window)),
        Case("axes[0].v_max", _set("axes", "v_max", repr(TRAVEL_X / 3600.0 * f)),
             lambda c: with_axis(c, 0, v_max=TRAVEL_X / 3600.0 * f)),
        Case("limits.rapid_mm_s", _set("limits", "rapid_mm_s", repr(LONGEST / 3600.0 * f)),
             lambda c: with_limits(c, rapid_mm_s=LONGEST / 3600.0 * f)),
        Case("probe.drive", _set("probe", "drive", "3" if refused else "2")),
        Case("probe.setter_x_mm",
             _set("probe", "setter_x_mm", repr(X.min_pos - (0.001 if refused else 0.0)))),
        Case("controller.spindle_drive", _set("controller", "spindle_drive", "3" if refused else "2")),
        Case(f"bus.drives[{NEW_DRIVE}].position",
             _append(f"[[bus.drives]]\nposition = {7 if refused else 1}\n") if refused
             else _replace_drive(1, "[[bus.drives]]\nposition = 1\n")),
        Case(f"bus.drives[{NEW_DRIVE - 1}].rx[0]",
             _replace_drive(0, '[[bus.drives]]\nposition = 0\nrx = ["0x6040:0:%s", "0x607A:0:32"]\n'
                            'tx = ["0x6041:0:16", "0x6064:0:32"]\n' % ("17" if refused else "16"))),
        Case("opcua.host", _set("opcua", "host", '"bad host!"' if refused else '"cnc-7.shop.local"')),
    ]


def _verdicts(case: Case, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> dict[str, str]:
    """Each reader's verdict: "" accepted, else its message from the key on."""
    from app.run_cli import main as run_main

    text = case.edit(config_to_toml(BASE))
    config = tmp_path / "machine.toml"
    config.write_text(text)
    program = tmp_path / "p.ngc"
    program.write_text("G0 X1\nM30\n")

    def tail(message: str) -> str:
        found = re.search(re.escape(case.key) + r".*", message)
        return found.group(0) if found else f"(no {case.key} in) {message}"

    out: dict[str, str] = {}
    capsys.readouterr()
    code = plan_main([str(program), "--config", str(config)])
    out["cnc-plan"] = tail(capsys.readouterr().err) if code == 2 else ""
    code = run_main([str(program), "--config", str(config), "--sim", "--worker", "manual", "--json"])
    err = capsys.readouterr().err
    out["cnc-run"] = tail(err) if code == 2 else ""
    try:
        load_config(config)
        out["panel"] = ""
    except ConfigError as exc:
        out["panel"] = tail(str(exc))
    if case.page is not None:
        message = axes_page_validate(case.page(BASE))
        out["axes page"] = tail(message) if message else ""
    return out


@pytest.mark.parametrize("index", range(len(cases(True))), ids=[c.key for c in cases(True)])
def test_every_reader_refuses_a_rule_broken_at_its_boundary_with_the_same_message(
        qapp: object, tmp_path: Path, capsys: pytest.CaptureFixture[str], index: int) -> None:
    verdicts = _verdicts(cases(True)[index], tmp_path, capsys)
    messages = set(verdicts.values())
    assert "" not in messages, verdicts
    assert len(messages) == 1, verdicts
    assert not next(iter(messages)).startswith("(no ")


@pytest.mark.parametrize("index", range(len(cases(False))), ids=[c.key for c in cases(False)])
def test_every_reader_accepts_the_rule_just_kept(qapp: object, tmp_path: Path,
                                                  capsys: pytest.CaptureFixture[str], index: int) -> None:
    verdicts = _verdicts(cases(False)[index], tmp_path, capsys)
    assert set(verdicts.values()) == {""}, verdicts


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(rule=st.sampled_from(["ts_s", "window", "v_max", "rapid"]), factor=st.floats(0.5, 2.0))
def test_fuzz_values_about_each_boundary_get_one_verdict_from_every_reader(
        qapp: object, tmp_path_factory: pytest.TempPathFactory, capsys: pytest.CaptureFixture[str], rule: str,
        factor: float) -> None:
    boundary = {"ts_s": 1e-4, "window": 1.0 / X.counts_per_unit, "v_max": TRAVEL_X / 3600.0,
                "rapid": LONGEST / 3600.0}[rule]
    value = boundary * factor
    case = {
        "ts_s": Case("planner.ts_s", _set("planner", "ts_s", repr(value)), lambda c: with_planner(c,
                                                                                                  ts_s=value)),
        "window": Case("axes[0].following_error_window", _set("axes", "following_error_window", repr(value)),
                       lambda c: with_axis(c, 0, following_error_window=value)),
        "v_max": Case("axes[0].v_max", _set("axes", "v_max", repr(value)), lambda c: with_axis(c, 0,
                                                                                               v_max=value)),
        "rapid": Case("limits.rapid_mm_s", _set("limits", "rapid_mm_s", repr(value)),
                      lambda c: with_limits(c, rapid_mm_s=value)),
    }[rule]
    verdicts = _verdicts(case, tmp_path_factory.mktemp("fuzz"), capsys)
    assert len(set(verdicts.values())) == 1, verdicts
    refused = next(iter(verdicts.values())) != ""
    assert refused == (value < boundary), (value, boundary, verdicts)
