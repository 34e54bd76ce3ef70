"""LinuxCNC-style canonical calls for a Program (``cnc-plan PROGRAM --canon OUT.jsonl``).

Schema of ../shared/gcode/README.md, one JSON object per line:
    {"line": 58, "call": "straight_feed", "args": [x, y, z, a, b, c, u, v, w]}
    {"line": 3,  "call": "straight_traverse", "args": [...]}
    {"line": 57, "call": "arc_feed", "args": [fe, se, fa, sa, rot, ae, a, b, c, u, v, w], "plane": "XY"}
Millimetres and degrees, coordinates in the work coordinate system active for the move
(machine position minus the work offset), arc centre absolute, rotation = +/- turns
(+ counter-clockwise, G03). LinuxCNC names the G18 plane "XZ" (first axis Z).
Only motion is written: zero-length moves do not exist in a Program (they are dropped).
"""

from __future__ import annotations

import json
import os
from typing import Any, BinaryIO

from planner.files import write_output
from planner.program import MoveKind, Program

__all__ = ["canon_records", "write_canon"]

_CANON_AXES = ("X", "Y", "Z", "A", "B", "C", "U", "V", "W")
_PLANE_NAMES = {"XY": "XY", "ZX": "XZ", "YZ": "YZ"}


def canon_records(program: Program) -> list[dict[str, Any]]:
    """The program's moves as canonical-call dicts, in order."""
    cols = [program.axes.index(a) if a in program.axes else -1 for a in _CANON_AXES]
    offsets = program.move_offsets
    records: list[dict[str, Any]] = []
    for i, move in enumerate(program.moves):
        end = move.end.tolist()
        off = offsets[i].tolist() if offsets is not None else [0.0] * len(end)
        wcs = [end[c] - off[c] if c >= 0 else 0.0 for c in cols]
        arc = move.arc
        if arc is None:
            call = "straight_traverse" if move.kind == MoveKind.RAPID else "straight_feed"
            records.append({"line": move.line, "call": call, "args": wcs})
            continue
        f, s, n = arc.first_axis, arc.second_axis, arc.normal_axis
        rotation = arc.turns if arc.sweep_rad > 0 else -arc.turns
        args = [
            end[f] - off[f],
            end[s] - off[s],
            arc.center[0] - off[f],
            arc.center[1] - off[s],
            rotation,
            end[n] - off[n] if n >= 0 else 0.0,
            *wcs[3:],
        ]
        records.append({"line": move.line, "call": "arc_feed", "args": args,
                        "plane": _PLANE_NAMES[arc.plane]})
    return records


def write_canon(program: Program, path: str | os.PathLike[str]) -> None:
    """Write canon_records(program) as JSONL (``planner.files``: atomically for a file, directly
    to a device, a pipe or ``-``)."""

    def write(fh: BinaryIO) -> None:
        for rec in canon_records(program):
            fh.write(json.dumps(rec).encode("utf-8"))
            fh.write(b"\n")

    write_output(path, write)
