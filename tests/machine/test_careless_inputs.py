"""Inputs a careless user gives, each refused or read as it should be: a drive table twice, a
feed override out of range, lines split only at line ends, tools set by G10 without a table."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from app import run_cli
from cli.plan import main as plan_main
from resources import shipped_machine

PROGRAM = "G21 G90\nG1 X5 Y3 F600\nM30\n"


@pytest.fixture
def program(tmp_path: Path) -> Path:
    p = tmp_path / "p.ngc"
    p.write_text(PROGRAM)
    return p


def test_two_drive_tables_for_one_slave_position_are_refused_by_every_reader(
        qapp: object, tmp_path: Path, program: Path, capsys: pytest.CaptureFixture[str]) -> None:
    config = tmp_path / "machine.toml"
    config.write_text(shipped_machine("xyz_mill").read_text()
                      + "\n[[bus.drives]]\nposition = 1\nvendor_id = 0x2\nproduct_code = 0x12345678\n")
    why = "slave position 1 already has a [[bus.drives]] table (the 2nd): one table a drive"
    assert plan_main([str(program), "--config", str(config)]) == 2
    assert why in capsys.readouterr().err
    assert run_cli.main([str(program), "--sim", "--worker", "manual", "--config", str(config)]) == 2
    assert why in capsys.readouterr().err


@pytest.mark.parametrize("value", ["nan", "-5", "1e308", "200.5"])
def test_a_feed_override_out_of_range_is_refused_before_the_run(qapp: object, program: Path, value: str,
                                                                capsys: pytest.CaptureFixture[str]) -> None:
    argv = [str(program), "--sim", "--worker", "manual", "--feed-override", value, "--json"]
    assert run_cli.main(argv) == 2
    captured = capsys.readouterr()
    assert captured.out == "" and "the feed override is 0 to 200 %" in captured.err


def test_a_feed_override_in_range_runs_at_it(qapp: object, program: Path,
                                             capsys: pytest.CaptureFixture[str]) -> None:
    assert run_cli.main([str(program), "--sim", "--worker", "manual", "--feed-override", "50", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["completed"] and out["cycle_time_s"] > 1.5 * out["estimated_cycle_time_s"]


def test_a_tool_table_and_a_script_split_lines_only_at_line_ends(qapp: object, tmp_path: Path, program: Path,
                                                                  capsys: pytest.CaptureFixture[str]) -> None:
    """A form feed or U+0085 in a comment is text of that line (str.splitlines would start a
    new line there: a tool read from a comment, the lines after it numbered wrong)."""
    from planner.core.errors import PlannerError
    from planner.core.tools import read_tbl

    table = tmp_path / "tools.tbl"
    table.write_text("T1 P1 Z1 D2 ;first\fT5 P5 Z9\nT2 P2 Z3 ;second\u0085T6 P6\nT3 P3 Z4\n",
                     encoding="utf-8")
    assert [t.number for t in read_tbl(table)] == [1, 2, 3]
    table.write_text("T1 P1 Z1 ;a\fb\nT2 P2 ZZ\n", encoding="utf-8")
    with pytest.raises(PlannerError, match=r"tools\.tbl:2:7: "):
        read_tbl(table)
    script = tmp_path / "ops.jsonl"
    # one line of the file, a form feed inside it: read as one line, so its error is at line 1
    script.write_text('{"after_s": 0.1, "op": "feed_hold"}\f{"after_s": "x", "op": "stop"}\n',
                      encoding="utf-8")
    assert run_cli.main([str(program), "--sim", "--worker", "manual", "--script", str(script)]) == 2
    assert f"{script}:1:" in capsys.readouterr().err


def test_without_a_tool_table_g10_sets_a_tool_and_every_other_tool_is_still_known(
        program: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    prog = tmp_path / "g10.ngc"
    prog.write_text("G21 G90\nG10 L1 P1 Z5\nT2 M6\nG43 H2\nG0 X1\nT1 M6\nG43\nG0 Z0\nM2\n")
    assert plan_main([str(prog), "--canon", "-"]) == 0
    calls = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    offsets = [c["args"][2] for c in calls if c["call"] == "tool_offset"]
    assert offsets[-1] == 5.0                         # T1's length, set by the G10 L1
