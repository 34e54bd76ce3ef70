"""The headless scenario runner (``cnc-run --script``) and, through it, what the operator's
actions do to the machine: safe restart, the spindle after stop/reset/M6/E-stop, the override."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from app import run_cli
from app.machine.errors import MachineError
from app.machine.program.scenario import OPS, parse_op, read_script

CUT = ("G21 G90 G17\nG0 Z5\nG0 X-20 Y0\nM3 S1200\nG1 Z-1 F600\nG1 X40 F1200\nG1 Y30\nG0 Z5\n"
       "G0 X60 Y60\nG1 Z-2 F600\nG1 X0 F1200\nG0 Z5\nM5\nM30\n")


def run(tmp_path: Path, capsys, program: str, ops: list[dict], *extra: str) -> tuple[int, dict, dict]:
    prog = tmp_path / "p.nc"
    prog.write_text(program)
    script = tmp_path / "ops.jsonl"
    script.write_text("".join(json.dumps(o) + "\n" for o in ops))
    trace = tmp_path / "trace.npz"
    code = run_cli.main([str(prog), "--sim", "--worker", "manual", "--json", "--state-dir",
                         str(tmp_path / "s"), "--script", str(script), "--trace", str(trace), *extra])
    out = json.loads(capsys.readouterr().out)
    with np.load(trace) as z:
        data = {k: z[k] for k in z.files}
    return code, out, data


def test_run_from_line_after_a_stop_while_cutting(tmp_path: Path, capsys) -> None:
    code, out, tr = run(tmp_path, capsys, CUT, [
        {"at_line": 7, "op": "stop"},
        {"after_s": 1.0, "op": "run_from_line", "line": 11},
    ])
    assert code == 0, out
    assert [a["ok"] for a in out["actions"]] == [True, True]
    assert out["completed"] and out["final_state"] == "idle"
    t, ref, rpm, line = tr["t"], tr["reference"], tr["spindle_rpm"], tr["line"]
    assert set(tr["axes"]) == {"X", "Y", "Z"} and len(t) == len(ref) == len(rpm) == len(line) > 1000
    stop_at = t[np.argmax(line == 7)]
    after = t > stop_at + 0.9                                    # the restart, not the first run
    top = ref[:, 2].max()
    assert top == pytest.approx(100.0)                           # the top of the Z travel by default
    sideways = np.abs(np.diff(ref[:, :2], axis=0)).max(axis=1) > 1e-3   # counts: 1e-4 mm
    low = np.maximum(ref[:-1, 2], ref[1:, 2]) < top - 1e-9
    # the approach: from the restart until the tool first stands at line 11's start point
    arrive = int(np.argmax(after & (np.abs(ref - (60.0, 60.0, -2.0)).max(axis=1) < 1e-9)))
    approach = after & (np.arange(len(t)) <= arrive)
    assert arrive > 0 and approach.sum() > 1000
    assert not (sideways & low & approach[1:]).any()
    # the spindle runs at the programmed speed before Z goes below the program's retract plane
    going_down = approach & (np.arange(len(t)) > np.argmax(ref[:, 2]))
    assert (going_down & (ref[:, 2] < 5.0)).any()
    assert (rpm[going_down & (ref[:, 2] < 5.0)] == 1200.0).all()


def test_after_a_stop_cycle_start_is_refused_and_restart_runs_from_the_beginning(tmp_path: Path,
                                                                               capsys) -> None:
    code, out, tr = run(tmp_path, capsys, CUT, [
        {"at_line": 7, "op": "stop"},
        {"after_s": 1.0, "op": "cycle_start"},
        {"after_s": 0.5, "op": "restart"},
    ])
    assert code == 1, out                         # an action was refused: said in the exit code
    stopped, again, restart = out["actions"]
    assert stopped["ok"] and restart["ok"]
    assert not again["ok"] and "stopped at line 7" in again["reason"]
    assert out["completed"]
    t, line = tr["t"], tr["line"]
    after = (t > restart["t_s"]) & (line > 0)
    assert line[after][0] < 7                     # from the beginning, as chosen


@pytest.mark.parametrize("op", ["stop", "estop", "reset"])
def test_the_spindle_is_off_within_a_second(tmp_path: Path, capsys, op: str) -> None:
    ops = [{"at_line": 7, "op": op}, {"after_s": 1.5, "op": "feed_hold"}] if op != "reset" else [
        {"at_line": 7, "op": "feed_hold"}, {"after_s": 0.5, "op": "reset"}, {"after_s": 1.5, "op": "stop"}]
    code, out, tr = run(tmp_path, capsys, CUT, ops)
    fired = out["actions"][1 if op == "reset" else 0]
    assert fired["ok"], fired
    t, rpm = tr["t"], tr["spindle_rpm"]
    assert (rpm == 1200.0).any()
    changes = out["spindle"]
    assert changes[0]["rpm"] == 1200.0 and changes[-1]["rpm"] == 0.0
    assert fired["t_s"] <= changes[-1]["t_s"] <= fired["t_s"] + 1.0
    if op != "estop":              # the trace has no samples while the drives are disabled
        later = t >= fired["t_s"] + 1.0
        assert later.any() and (rpm[later] == 0.0).all()


def test_a_tool_change_stops_the_spindle_until_the_programs_own_m3(tmp_path: Path, capsys) -> None:
    """LinuxCNC's M6 (STOP_SPINDLE_TURNING, CHANGE_TOOL): after the operator's tool_changed the
    spindle stays at 0 rpm until the program's M3 S6000, then turns at 6000: never at the old
    tool's 8000."""
    program = "G21 G90\nM3 S8000\nG0 X10 Y0\nT2 M6\nM3 S6000\nG1 X20 F600\nM30\n"
    (tmp_path / "t.tbl").write_text("T2 P2 Z0 D6 ;6 mm flat\n")
    code, out, tr = run(tmp_path, capsys, program, [{"after_s": 6.0, "op": "tool_changed"}],
                        "--tools", str(tmp_path / "t.tbl"))
    assert code == 0 and out["completed"], out
    text = "tool change (M06, line 4): insert tool T2 (6 mm flat) and press cycle start"
    assert out["prompts"] == [{"line": 4, "kind": "tool_change", "tool": 2, "text": text}]
    t, rpm, line = tr["t"], tr["spindle_rpm"], tr["line"]
    fired = out["actions"][0]["t_s"]
    waiting = np.flatnonzero((line == 4) & (t < fired))   # the M6 line stays highlighted meanwhile
    assert len(waiting) > 3000
    assert (rpm[waiting[1000:]] == 0.0).all()     # the spindle is off (after it stopped)
    after = t >= fired
    first_on = int(np.flatnonzero(after & (rpm > 0.0))[0])
    assert (rpm[after & (t < t[first_on])] == 0.0).all()      # off until the program's M3
    assert line[first_on] >= 5                                 # which is what starts it
    assert set(np.unique(rpm[after & (rpm > 0.0)])) == {6000.0}   # at its speed, never the old
    assert (rpm[after & (line == 6)] == 6000.0).all()


def test_a_tool_changed_at_the_m6_s_own_line_waits_for_the_change_stop(tmp_path: Path, capsys) -> None:
    """``{"at_line": 4, "op": "tool_changed"}`` on the M6's line: the line is reached while the
    motion still slows down to the stop; the action is the operator's, taken at the stop."""
    program = "G21 G90\nG0 X10 Y0\nG1 X30 F3000\nT2 M6\nG1 X20 F600\nM30\n"
    (tmp_path / "t.tbl").write_text("T2 P2 Z0 D6 ;6 mm flat\n")
    code, out, _ = run(tmp_path, capsys, program, [{"at_line": 4, "op": "tool_changed"}],
                       "--tools", str(tmp_path / "t.tbl"))
    assert code == 0 and out["completed"], out
    assert out["actions"][0]["ok"] is True, out["actions"]


def test_150_percent_override_ends_a_feed_bound_program_a_quarter_sooner(tmp_path: Path, capsys) -> None:
    program = "G21 G90\nG1 X50 F600\nG1 Y50\nG1 X0\nG1 Y0\nM30\n"
    code, base, _ = run(tmp_path, capsys, program, [])
    assert code == 0
    code, fast, _ = run(tmp_path, capsys, program, [{"after_s": 0, "op": "feed_override", "percent": 150}])
    assert code == 0 and fast["completed"]
    assert fast["cycle_time_s"] <= 0.75 * base["cycle_time_s"], (fast["cycle_time_s"], base["cycle_time_s"])


@pytest.mark.parametrize("line, words", [
    ('{"op": "stop"}', "exactly one of at_line or after_s"),
    ('{"op": "fly", "after_s": 1}', "op must be one of"),
    ('{"op": "stop", "after_s": 1, "line": 3}', "unknown key 'line'"),
    ('{"op": "run_from_line", "after_s": 1}', 'needs "line"'),
    ('{"op": "run_from_line", "after_s": 1, "line": 2.5}', "whole number"),
    ('{"op": "feed_override", "at_line": 3, "percent": NaN}', "percent must be a number"),
    ('{"op": "stop", "after_s": -1}', "must not be negative"),
    ("[1, 2]", "not a JSON object"),
    ("stop at 3", "not a JSON object"),
    ('{"op": "input", "after_s": 1, "signal": "door_closed"}', 'input needs "signal"'),
    ('{"op": "input", "after_s": 1, "signal": "door_closed", "value": 1}', "value must be true"),
])
def test_a_bad_script_line_is_named(tmp_path: Path, line: str, words: str) -> None:
    script = tmp_path / "ops.jsonl"
    script.write_text('# the operator\n{"op": "stop", "at_line": 2}\n\n' + line + "\n")
    with pytest.raises(MachineError) as exc:
        read_script(script)
    assert f"{script}:4:" in str(exc.value) and words in str(exc.value)


_JSON = st.recursive(
    st.none() | st.booleans() | st.integers(-10**20, 10**20) | st.text(max_size=8)
    | st.sampled_from([float("nan"), float("inf"), 1e308, -0.5, 2.5, 150]),
    lambda inner: st.lists(inner, max_size=3) | st.dictionaries(st.text(max_size=6), inner, max_size=3),
    max_leaves=6)
_KEYS = st.sampled_from(["op", "at_line", "after_s", "line", "percent", "when", "Op", "signal", "value"])
_OPS = st.sampled_from([*OPS, "jump", ""]) | _JSON


@settings(max_examples=300, deadline=None)
@given(st.dictionaries(_KEYS, _JSON, max_size=4), _OPS)
def test_any_script_line_is_an_action_or_refused_with_its_line(data: dict, op: object) -> None:
    if "op" in data or op != "":
        data = {**data, "op": op}
    try:
        parse_op(json.dumps(data), "ops.jsonl:7")
    except MachineError as exc:
        assert str(exc).startswith("ops.jsonl:7: "), str(exc)


def test_a_script_opens_and_closes_the_door_and_the_program_waits_for_it(tmp_path: Path, capsys) -> None:
    """The door opened mid-move holds the program (no motion while it is open, cycle start
    refused); closed again, cycle start finishes it."""
    code, out, tr = run(tmp_path, capsys, "G21 G90\nG1 X40 F600\nM30\n", [
        {"after_s": 1.0, "op": "input", "signal": "door_closed", "value": False},
        {"after_s": 1.0, "op": "cycle_start"},
        {"after_s": 1.0, "op": "input", "signal": "door_closed", "value": None},
        {"after_s": 0.2, "op": "cycle_start"},
    ])
    assert code == 1, out                  # a refused action: the script did not run as written
    assert [a["ok"] for a in out["actions"]] == [True, False, True, True]
    assert "the door is open" in out["actions"][1]["reason"]
    assert out["completed"] and out["end_position"][0] == pytest.approx(40.0, abs=2e-4)
    t, x = tr["t"], tr["reference"][:, 0]
    t_open = out["actions"][0]["t_s"]
    t_close = out["actions"][2]["t_s"]
    still = (t > t_open + 0.5) & (t < t_close)
    assert still.sum() > 500 and np.ptp(x[still]) == 0.0


def test_cnc_run_refuses_a_bad_script_before_running(tmp_path: Path, capsys) -> None:
    prog = tmp_path / "p.nc"
    prog.write_text("G0 X1\nM30\n")
    script = tmp_path / "ops.jsonl"
    script.write_text('{"op": "stop"}\n')
    assert run_cli.main([str(prog), "--sim", "--worker", "manual", "--script", str(script)]) == 2
    assert f"{script}:1: give exactly one of at_line or after_s" in capsys.readouterr().err


def test_every_row_of_the_trace_carries_its_own_set_point_s_line(tmp_path: Path, capsys) -> None:
    """Each row of the headless trace is tagged with the line of the set-point it sent (not the
    line shown when its chunk was drained): the lines only ever go forward through a program
    without jumps back, a row at rest at the M6 is the M6's line, and every motion line has
    rows whose set-points lie on it."""
    program = ("G21 G90\nG0 X10 Y0\nG1 X30 F3000\nG1 Y10\nT2 M6\nG1 X20 F600\nG1 Y0\nG0 X0\nM30\n")
    (tmp_path / "t.tbl").write_text("T2 P2 Z0 D6 ;6 mm flat\n")
    code, out, tr = run(tmp_path, capsys, program, [{"at_line": 5, "op": "tool_changed"}],
                        "--tools", str(tmp_path / "t.tbl"))
    assert code == 0 and out["completed"], out
    line, ref = tr["line"], tr["reference"]
    moving = np.flatnonzero(line > 0)
    assert np.all(np.diff(line[moving]) >= 0), np.unique(line[moving])     # never back
    assert set(np.unique(line[moving])) >= {2, 3, 4, 5, 6, 7, 8}
    # where the set-points of each line lie: line 4 (G1 Y10) at X30, line 6 (G1 X20) at Y10
    assert np.allclose(ref[line == 4][:, 0], 30.0, atol=1e-9)
    assert np.allclose(ref[line == 6][:, 1], 10.0, atol=1e-9)
    assert np.allclose(ref[line == 7][:, 0], 20.0, atol=1e-9)
