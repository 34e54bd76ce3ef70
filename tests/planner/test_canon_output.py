"""--canon output: LinuxCNC-style canonical calls in the JSONL schema of ../shared/gcode/README.md."""

from __future__ import annotations

import json
import math
from dataclasses import replace

import pytest

from planner.core.machine import MachineSpec, load_machine
from planner.gcode.canon import canon_records, write_canon
from planner.gcode.interpreter import parse_program
from resources import shipped_machine


def test_schema_and_file(tmp_path):
    p = parse_program("G0 X1 Y2\nG1 Z-1 F60\nG2 X3 Y2 I1 J0\nG18 G3 X5 Z-3 R2\n")
    out = tmp_path / "o.jsonl"
    write_canon(p, out)
    lines = out.read_text().splitlines()
    recs = [json.loads(line) for line in lines]
    assert recs == canon_records(p, offsets=True)
    assert [r["call"] for r in recs[:4]] == ["set_g5x_offset", "set_g92_offset", "set_xy_rotation",
                                             "tool_offset"]
    recs = recs[4:]                  # the offsets at the start; the motion follows
    assert not list(tmp_path.glob("*.tmp"))
    assert [r["call"] for r in recs] == ["straight_traverse", "straight_feed", "arc_feed", "arc_feed"]
    assert [r["line"] for r in recs] == [1, 2, 3, 4]
    assert recs[0]["args"] == [1.0, 2.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]
    arc = recs[2]
    assert set(arc) == {"line", "call", "args", "plane"} and len(arc["args"]) == 12
    # first_end, second_end, first_centre, second_centre, rotation, axis_end, a, b, c, u, v, w
    assert arc["plane"] == "XY" and arc["args"][:6] == [3.0, 2.0, 2.0, 2.0, -1, -1.0]
    g18 = recs[3]
    assert g18["plane"] == "XZ"  # LinuxCNC's name; first axis Z
    z_end, x_end, z_c, x_c, rot, y_end = g18["args"][:6]
    assert (z_end, x_end, rot, y_end) == (-3.0, 5.0, 1, 2.0)
    assert math.hypot(z_end - z_c, x_end - x_c) == pytest.approx(2.0)


def test_turns_give_rotation():
    recs = canon_records(parse_program("G0 X10\nG2 X10 I-10 P3 F60\nG3 X10 I-10 P2\n"))
    assert [r["args"][4] for r in recs[1:]] == [-3, 2]


def test_work_coordinates_not_machine():
    m = MachineSpec.default()
    offs = dict(m.work_offsets)
    offs["G54"] = (100.0, 50.0, -20.0)
    m = replace(m, work_offsets=offs)
    p = parse_program("G0 X1 Y1 Z1\nG2 X3 Y1 I1 F60\nG53 G0 Z0\n", machine=m)
    recs = canon_records(p)
    assert recs[0]["args"][:3] == [1.0, 1.0, 1.0]
    assert recs[1]["args"][:4] == [3.0, 1.0, 2.0, 1.0]
    # G53 move: machine Z0 is Z20 in G54
    assert recs[2]["args"][:3] == [3.0, 1.0, 20.0]


def test_rotary_axes_columns():
    m = load_machine(shipped_machine("paper_yzca"))
    p = parse_program("G0 Y1 Z2 C30 A-10\nG19 G2 Y3 Z2 R1 C60 F60\n", machine=m)
    r0, r1 = canon_records(p)
    # x y z a b c u v w; this machine has no X
    assert r0["args"] == [0.0, 1.0, 2.0, -10.0, 0.0, 30.0, 0.0, 0.0, 0.0]
    assert r1["plane"] == "YZ" and r1["args"][5] == 0.0  # normal axis X does not exist
    assert r1["args"][6:] == [-10.0, 0.0, 60.0, 0.0, 0.0, 0.0]


def test_offset_calls_where_the_offsets_change_motion_in_program_coordinates():
    p = parse_program("G21 G90\nG10 L2 P2 X100 Y5\nG55 G0 X1\nG92 X0\nG0 X2\nG43.1 Z5\nG0 Z1\nG54 G0 X0\n")
    recs = [(r["line"], r["call"], r["args"][:4]) for r in canon_records(p, offsets=True) if r["line"]]
    assert recs == [
        (3, "set_g5x_offset", [2, 100.0, 5.0, 0.0]),
        (3, "straight_traverse", [1.0, -5.0, 0.0, 0.0]),     # Y stays where the machine is
        (4, "set_g92_offset", [1.0, 0.0, 0.0, 0.0]),
        (5, "straight_traverse", [2.0, -5.0, 0.0, 0.0]),
        (6, "tool_offset", [0.0, 0.0, 5.0, 0.0]),
        (7, "straight_traverse", [2.0, -5.0, 1.0, 0.0]),
        (8, "set_g5x_offset", [1, 0.0, 0.0, 0.0]),
        (8, "straight_traverse", [0.0, 0.0, 1.0, 0.0]),
    ]
    machine = [m.end.tolist() for m in p.moves]
    assert machine == [[101.0, 0.0, 0.0], [103.0, 0.0, 0.0], [103.0, 0.0, 6.0], [1.0, 0.0, 6.0]]


def test_a_long_program_is_written_in_batches_line_for_line(tmp_path):
    """write_canon streams the calls a few thousand at a time: the file holds exactly the calls
    of canon_records, one per line, across the batches' seams."""
    lines, x = ["G10 L2 P1 X1 Y2", "G1 F600"], 0.0
    for i in range(1, 9000):
        x += 0.01
        lines.append(f"X{x:.2f} Y{i % 5}")
        if i % 97 == 0:  # a half circle to the right now and then
            x += 1.0
            lines.append(f"G2 X{x:.2f} Y{i % 5} I0.5 J0\nG1")
    text = "\n".join(lines) + "\n"
    program = parse_program(text, "long.nc")
    out = tmp_path / "c.jsonl"
    write_canon(program, out)
    rows = out.read_text().splitlines()
    want = canon_records(program, offsets=True)
    assert len(rows) == len(want) > 8192
    assert [json.loads(r) for r in rows] == want
