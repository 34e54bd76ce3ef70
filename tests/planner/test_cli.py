"""`cnc-plan`: every flag (samples, CSV, plot, canonical calls, JSON report); bad programs."""

from __future__ import annotations

import json
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from cli.plan import build_machine, main
from resources import shipped_machine, shipped_program

ROOT = Path(__file__).resolve().parents[2]
FIG7 = shipped_program("fig7_circle.nc")
FIG9 = shipped_program("fig9_helix.nc")
PAPER_MACHINE = shipped_machine("paper_yzca")


def run_json(capsys, *args) -> dict:
    assert main([*map(str, args), "--json"]) == 0
    out = capsys.readouterr().out
    return json.loads(out)


def test_json_report_has_every_field(capsys):
    rep = run_json(capsys, FIG9)
    for key in ("program", "lines", "moves", "cycle_time_s", "samples", "plan_s", "interp_s",
                "tangential", "axes", "contour_error_mm", "violations", "move_list"):
        assert key in rep, key
    assert rep["moves"] == 7 and rep["lines"] >= 12
    assert set(rep["tangential"]) == {"v", "a", "j"}
    assert set(rep["axes"]) == {"X", "Y", "Z"}
    assert rep["tangential"]["v"] <= 30.0 + 1e-9
    assert rep["violations"] == {} and rep["ok"] is True
    assert rep["contour_error_mm"] <= 1e-9
    mv = rep["move_list"][1]
    assert set(mv) == {"line", "kind", "length", "vs", "ve", "vpeak", "t0", "t1"}
    assert mv["kind"] == "arc" and mv["line"] == 6
    assert rep["samples"] == int(np.ceil(rep["cycle_time_s"] / 0.001 - 1e-9)) + 1


def test_a_probing_program_says_its_path_assumes_the_result(capsys, tmp_path):
    prog = tmp_path / "probe.ngc"
    prog.write_text("G21 G90\nG0 X10 Z5\nG38.2 Z-20 F100\nG0 Z[#5063 + 2]\nG38.5 Z10\nM2\n")
    assert run_json(capsys, prog)["probes"] == [{"line": 3, "code": "G38.2", "assumed": True},
                                                {"line": 5, "code": "G38.5", "assumed": True}]
    assert main([str(prog)]) == 0
    assert "probing (G38.x) at line(s) 3, 5: planned as running to the" in capsys.readouterr().out
    assert run_json(capsys, FIG9)["probes"] == []


def test_block_delete_is_off_unless_asked_as_in_linuxcnc(capsys, tmp_path):
    prog = tmp_path / "skip.ngc"
    prog.write_text("G21 G1 X5 F600\n/G1 Y20\nG1 X10\nM2\n")
    assert run_json(capsys, prog)["moves"] == 3
    assert run_json(capsys, prog, "--block-delete")["moves"] == 2


def test_a_threading_program_says_the_machine_refuses_to_run_it(capsys, tmp_path):
    prog = tmp_path / "thread.ngc"
    prog.write_text("G21 M3 S500\nG0 X10 Z5\nG76 P1.5 Z-20 I-1 J0.1 K0.9\nG0 Z5\nG33 Z-2 K1\nM2\n")
    rep = run_json(capsys, prog)
    assert rep["synchronised"] == [{"line": 3, "code": "G76"}, {"line": 5, "code": "G33"}]
    assert rep["ok"] is True and rep["moves"] == 1 + 9 * 4 + 1 + 1
    assert main([str(prog)]) == 0
    assert ("spindle-synchronised motion (G76 at 3, G33 at 5): planned at the pitch times the programmed "
            "speed; the machine refuses to run it" in capsys.readouterr().out)
    assert run_json(capsys, FIG9)["synchronised"] == []


def test_a_program_setting_analog_outputs_says_the_machine_refuses_it(capsys, tmp_path):
    prog = tmp_path / "laser.ngc"
    prog.write_text("G21 F600\nM68 E0 Q40\nG1 X10\nM68 E0 Q0\nM2\n")
    assert run_json(capsys, prog)["analog_outputs"] == [
        {"line": 2, "code": "M68", "index": 0, "value": 40.0},
        {"line": 4, "code": "M68", "index": 0, "value": 0.0}]
    assert main([str(prog)]) == 0
    out = capsys.readouterr().out
    assert "analog outputs (M68 at 2, M68 at 4): read; the machine refuses to run them" in out


def test_limits_mode_interp_and_ts_flags(capsys):
    slow = run_json(capsys, FIG9, "--vmax", 10, "--amax", 500, "--jmax", 5000, "--ts", 0.002)
    assert slow["tangential"]["v"] <= 10 + 1e-9 and slow["ts_s"] == 0.002
    assert slow["tangential"]["a"] <= 500 + 1e-9 and slow["tangential"]["j"] <= 5000 + 1e-9
    paper = run_json(capsys, FIG7, "--mode", "paper", "--interp", "classic")
    assert paper["mode"] == "paper" and paper["interpolation"] == "classic"
    assert "axis_a" in paper["violations"]
    taylor = run_json(capsys, FIG7, "--interp", "taylor")
    assert taylor["interpolation"] == "taylor"


def test_config_machine(capsys, tmp_path):
    prog = tmp_path / "yz.nc"
    prog.write_text("G21 G90 G19 F1200\nG01 Y10 Z5\nG02 Y20 Z5 R5\nG01 C90 A10\nM30\n")
    rep = run_json(capsys, prog, "--config", PAPER_MACHINE)
    assert set(rep["axes"]) == {"Y", "Z", "C", "A"}
    assert rep["violations"] == {}


def test_samples_csv_canon_and_plot_files(tmp_path):
    npz, csv, canon, png = (tmp_path / n for n in ("s.npz", "s.csv", "c.jsonl", "p.png"))
    assert main([str(FIG9), "--samples", str(npz), "--csv", str(csv), "--canon", str(canon),
                 "--plot", str(png)]) == 0
    data = np.load(npz)
    assert set(data.files) == {"t", "q", "axes", "s", "line"}
    n = data["t"].shape[0]
    assert data["q"].shape == (n, 3) and list(data["axes"]) == ["X", "Y", "Z"]
    assert data["s"].shape == (n,) and data["line"].shape == (n,)
    rows = csv.read_text().splitlines()
    assert rows[0] == "t,X,Y,Z,s,line" and len(rows) == n + 1
    calls = [json.loads(x) for x in canon.read_text().splitlines()]
    offsets = ["set_g5x_offset", "set_g92_offset", "set_xy_rotation", "tool_offset"]   # at the start
    assert [c["call"] for c in calls] == offsets + ["straight_traverse"] + ["arc_feed"] * 6
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert png.stat().st_size > 10_000
    assert not list(tmp_path.glob("*.tmp*"))


def test_bad_program_exit_2_errors_on_stderr_nothing_written(tmp_path):
    bad = tmp_path / "bad.nc"
    bad.write_text("G21 G90 F600\nG01 X10\nG02 X20 Y0 R2\nG01 Q5\n")
    outs = [tmp_path / n for n in ("s.npz", "s.csv", "c.jsonl", "p.png")]
    result = subprocess.run(
        [sys.executable, "-m", "cli", str(bad), "--samples", str(outs[0]), "--csv", str(outs[1]),
         "--canon", str(outs[2]), "--plot", str(outs[3]), "--json"],
        cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert result.returncode == 2
    assert result.stdout == ""
    assert f"{bad}:3:" in result.stderr and "error:" in result.stderr
    assert f"{bad}:4:" in result.stderr
    assert not any(p.exists() for p in outs)
    assert sorted(tmp_path.iterdir()) == [bad]


def test_missing_file_and_bad_flags_exit_2(tmp_path, capsys):
    assert main([str(tmp_path / "nope.nc")]) == 2
    assert "nope.nc" in capsys.readouterr().err
    assert main([str(FIG9), "--vmax", "-3"]) == 2
    with pytest.raises(SystemExit) as exc:
        main([str(FIG9), "--mode", "fast"])
    assert exc.value.code == 2


@pytest.mark.parametrize(("option", "value"), [("--vmax", "1e100"), ("--amax", "1e8"), ("--jmax", "1e11"),
                                               ("--ts", "0.00001"), ("--vmax", "0.0001")])
def test_a_limit_beyond_the_configuration_s_range_is_refused_and_planning_ends(
        tmp_path, capsys, option: str, value: str) -> None:
    program = tmp_path / "p.ngc"
    program.write_text("G21 G90\nG0 X100\nG1 X0 Y50 F1000\nG2 X10 Y60 I5 J5\nM30\n")
    started = time.perf_counter()
    assert main([str(program), option, value]) == 2
    assert time.perf_counter() - started < 10
    assert f"{option} {float(value):g} is out of range" in capsys.readouterr().err


def test_the_first_sample_of_a_time_past_a_float_s_whole_samples_is_found_at_once() -> None:
    from planner.motion.interpolate import first_sample_at

    assert first_sample_at(8.464383728825633e47, 0.001) > 8e50        # looped for ever
    assert first_sample_at(0.0025, 0.001) == 3 and first_sample_at(0.003, 0.001) == 3


def test_default_machine_has_axis_limits_equal_to_path_limits():
    m = build_machine(None, 20.0, 800.0, 9000.0, None)
    assert all((a.v_max, a.a_max, a.j_max) == (20.0, 800.0, 9000.0) for a in m.axes)
    assert m.limits.v_max_mm_s == 20.0 and m.planner.ts_s == 0.001
    cfg = build_machine(str(PAPER_MACHINE), 25.0, None, None, 0.002)
    assert cfg.limits.v_max_mm_s == 25.0 and cfg.limits.a_max_mm_s2 == 1000.0
    assert cfg.axes[0].v_max == 60.0 and cfg.planner.ts_s == 0.002


def test_plain_summary_and_canon_alone(tmp_path, capsys):
    assert main([str(FIG9)]) == 0
    assert "7 moves" in capsys.readouterr().out
    out = tmp_path / "c.jsonl"
    assert main([str(FIG9), "--canon", str(out)]) == 0  # no planning needed for --canon alone
    assert len(out.read_text().splitlines()) == 4 + 7        # the offsets at the start, the moves


def test_config_soft_limits_are_checked_on_the_whole_path(tmp_path, capsys) -> None:
    """With a machine configuration, cnc-plan refuses a program that leaves the travel, as
    the controller does: an arc bulging past X max is caught at its extreme, not its ends."""
    prog = tmp_path / "arc.nc"
    prog.write_text("G0 X245 Y0\nG1 F600\nG3 X245 Y20 I0 J10\nM30\n")   # X max 250; the arc reaches 255
    assert main([str(prog), "--config", str(shipped_machine("xyz_mill"))]) == 2
    err = capsys.readouterr().err
    assert f"{prog}:3: error: axis X reaches 255.0000 (arc extreme), beyond its soft limit max 250" in err
    assert main([str(prog)]) == 0           # no configuration: no travel to check against
    inside = tmp_path / "ok.nc"
    inside.write_text("G0 X235 Y0\nG1 F600\nG3 X235 Y20 I0 J10\nM30\n")
    assert main([str(inside), "--config", str(shipped_machine("xyz_mill"))]) == 0


@pytest.mark.parametrize("text", ["G1 X10 F0.0001\nM30\n", "G1 F600\nG2 X0 Y0 I1000000 J0\nM30\n",
                                  "G0 X999999999\nM30\n", "G1 F600\nG2 X0 Y0 I50 J0 P10000\nM30\n"])
def test_a_run_over_the_cycle_bound_is_reported_not_interpolated(tmp_path, capsys, text: str) -> None:
    prog = tmp_path / "long.nc"
    prog.write_text(text)
    out = tmp_path / "s.npz"
    started = time.perf_counter()
    assert main([str(prog), "--json", "--samples", str(out)]) == 2
    assert time.perf_counter() - started < 10
    captured = capsys.readouterr()
    report = json.loads(captured.out)
    assert report["ok"] is False and report["cycle_time_s"] > 24 * 3600
    assert "more than --max-cycle-h 24: not interpolated" in captured.err
    assert not out.exists()


def test_a_program_longer_than_the_bound_is_reported_with_its_cycle_time_when_no_samples_are_asked(
        tmp_path, capsys) -> None:
    prog = tmp_path / "finish.nc"
    prog.write_text("G21 G90\nG1 X10 F0.005\nM30\n")        # 2,000 min: 33.3 h
    assert main([str(prog), "--json"]) == 0
    captured = capsys.readouterr()
    report = json.loads(captured.out)
    assert report["ok"] is True and report["sampled"] is False
    assert report["cycle_time_s"] == pytest.approx(2000 * 60, rel=1e-3)
    assert "the cycle time is 33.3 h, more than --max-cycle-h 24: not interpolated" in report["note"]
    assert main([str(prog)]) == 0
    assert "cycle time 120000" in capsys.readouterr().out


@pytest.mark.parametrize("value", ["0", "-1", "nan", "inf"])
def test_max_cycle_bound_must_be_a_positive_number(tmp_path, capsys, value: str) -> None:
    prog = tmp_path / "p.nc"
    prog.write_text("G1 X1 F100\n")
    assert main([str(prog), "--max-cycle-h", value]) == 2
    assert "--max-cycle-h must be a positive number of hours" in capsys.readouterr().err
