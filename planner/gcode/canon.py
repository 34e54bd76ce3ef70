"""LinuxCNC-style canonical calls for a Program (``cnc-plan PROGRAM --canon OUT.jsonl``).

Schema of ../shared/gcode/README.md, one JSON object per line:
    {"line": 58, "call": "straight_feed", "args": [x, y, z, a, b, c, u, v, w]}
    {"line": 3,  "call": "straight_traverse", "args": [...]}
    {"line": 57, "call": "arc_feed", "args": [fe, se, fa, sa, rot, ae, a, b, c, u, v, w], "plane": "XY"}
Millimetres and degrees, coordinates in the work coordinate system active for the move
(machine position minus the work offset), arc centre absolute, rotation = +/- turns
(+ counter-clockwise, G03). LinuxCNC names the G18 plane "XZ" (first axis Z).
Zero-length moves do not exist in a Program (they are dropped). ``cnc-plan --canon`` also writes
LinuxCNC's offset calls, where the offsets change:
    {"line": 12, "call": "set_g5x_offset", "args": [system 1-9, x, y, z, a, b, c, u, v, w]}
    {"line": 13, "call": "set_g92_offset", "args": [x, y, z, a, b, c, u, v, w]}
    {"line": 0,  "call": "set_xy_rotation", "args": [0.0]}
    {"line": 14, "call": "tool_offset", "args": [x, y, z, a, b, c, u, v, w]}
in machine units; the motion stays in program coordinates (the offsets taken off), as LinuxCNC's.
"""

from __future__ import annotations

import json
import os
from collections.abc import Iterator, Sequence
from typing import Any, BinaryIO

import numpy as np

from planner.core.files import write_output
from planner.core.frames import Frame
from planner.core.program import EventKind, MoveKind, Program, TableRef, turn_xy

__all__ = ["canon_records", "iter_canon_records", "write_canon"]

_CANON_AXES = ("X", "Y", "Z", "A", "B", "C", "U", "V", "W")
_PLANE_NAMES = {"XY": "XY", "ZX": "XZ", "YZ": "YZ"}
# the plane's first, second and normal axis as places in the canonical order (X Y Z ...)
_PLANE_CANON = {"XY": (0, 1, 2), "ZX": (2, 0, 1), "YZ": (1, 2, 0)}


def _offset_records(program: Program, cols: list[int]) -> dict[int, list[dict[str, Any]]]:
    """LinuxCNC's offset calls by the move they come before: set_g5x_offset (system 1-9 and
    nine values), set_g92_offset, set_xy_rotation, tool_offset, each when it changes (all of
    them at the start)."""
    out: dict[int, list[dict[str, Any]]] = {}
    last: tuple[Any, ...] | None = None

    def nine(values: tuple[float, ...]) -> list[float]:
        return [float(values[c]) if c >= 0 else 0.0 for c in cols]

    for change in program.frames:
        f = change.frame
        line, system, work, g92, tlo, rotation = change.line, f.system, f.g5x, f.g92, f.tool, f.rotation_deg
        recs = out.setdefault(change.first, [])
        if last is None or (system, work) != (last[0], last[1]):
            recs.append({"line": line, "call": "set_g5x_offset", "args": [system, *nine(work)]})
        if last is None or g92 != last[2]:
            recs.append({"line": line, "call": "set_g92_offset", "args": nine(g92)})
        if last is None or rotation != last[4]:
            recs.append({"line": line, "call": "set_xy_rotation", "args": [float(rotation)]})
        if last is None or tlo != last[3]:
            recs.append({"line": line, "call": "tool_offset", "args": nine(tlo)})
        last = (system, work, g92, tlo, rotation)
    return out


def _to_program(pos: Sequence[float], cols: list[int], frame: Frame) -> list[float]:
    """Program coordinates of a machine position in the canonical axis order (``Frame.to_program``;
    an axis the machine lacks reads 0)."""
    prog = frame.point_to_program(pos)
    return [prog[c] if c >= 0 else 0.0 for c in cols]


def canon_records(program: Program, offsets: bool = False) -> list[dict[str, Any]]:
    """The program's moves as canonical-call dicts, in order; with ``offsets`` also LinuxCNC's
    offset calls (set_g5x_offset, set_g92_offset, set_xy_rotation, tool_offset) where they change.
    Motion in program coordinates: the offsets taken off and an XY rotation undone."""
    return list(iter_canon_records(program, offsets))


def iter_canon_records(program: Program, offsets: bool = False) -> Iterator[dict[str, Any]]:
    """``canon_records`` one by one (a program of millions of moves is never held as dicts)."""
    cols = [program.axes.index(a) if a in program.axes else -1 for a in _CANON_AXES]
    offsets_before = _offset_records(program, cols) if offsets else {}
    frames = [c.frame for c in program.frames] or [Frame.identity(program.axes)]
    move_frames = program.move_frames
    # G38.x: LinuxCNC's call names the programmed end point; the move ends where the probe stopped
    # (by the PROBE event, which follows the move when blending renumbers the moves)
    probes = [(e.after_move, program.probes[e.payload_as(TableRef).index]) for e in program.events
              if e.kind is EventKind.PROBE]
    probe_targets = {after: probe.target for after, probe in probes if probe.move_index >= 0}
    taps = set(program.taps)
    back_out = {i + 1 for i in taps}
    for i, move in enumerate(program.moves):
        yield from offsets_before.pop(i, ())
        if i in back_out:                   # G33.1 back out: part of its RIGID_TAP call
            continue
        end = move.end.tolist()
        frame = frames[int(move_frames[i])] if move_frames is not None else frames[0]
        wcs = _to_program(end, cols, frame)
        arc = move.arc
        if i in taps:
            yield {"line": move.line, "call": "rigid_tap", "args": wcs}
            continue
        if probe_targets and i in probe_targets:
            wcs = _to_program(probe_targets[i], cols, frame)
            yield {"line": move.line, "call": "straight_probe", "args": wcs}
            continue
        if arc is None:
            call = "straight_traverse" if move.kind == MoveKind.RAPID else "straight_feed"
            yield {"line": move.line, "call": call, "args": wcs}
            continue
        f, s = arc.first_axis, arc.second_axis
        rotation = arc.turns if arc.sweep_rad > 0 else -arc.turns
        # the centre as a machine point, in program coordinates as the end is. A G18/G19 arc's
        # centre in a rotated system is in its turned frame: put there and turned back, the
        # frame's X (or Y) becomes the program's; the other of X and Y, the plane's normal, is
        # not read
        centre = np.array([end])
        centre[0, f], centre[0, s] = arc.center
        turned = arc.turned_xy
        if turned is not None:
            turn_xy(centre, turned[0], turned[1], arc.xy_turn_rad)
        cprog = _to_program(centre[0].tolist(), cols, frame)
        fi, si, ni = _PLANE_CANON[arc.plane]
        first_c, second_c = cprog[fi], cprog[si]
        first_e, second_e, normal_e = wcs[fi], wcs[si], wcs[ni]
        args = [
            first_e,
            second_e,
            first_c,
            second_c,
            rotation,
            normal_e,
            *wcs[3:],
        ]
        yield {"line": move.line, "call": "arc_feed", "args": args, "plane": _PLANE_NAMES[arc.plane]}
    for rest in offsets_before.values():       # changes after the last move
        yield from rest


def write_canon(program: Program, path: str | os.PathLike[str], offsets: bool = True) -> None:
    """Write canon_records(program, offsets) as JSONL (``planner.core.files``: atomically for a file,
    directly to a device, a pipe or ``-``)."""

    def write(fh: BinaryIO) -> None:
        batch: list[str] = []
        for rec in iter_canon_records(program, offsets):
            batch.append(json.dumps(rec))
            if len(batch) >= 4096:  # a few thousand lines a write: memory bounded, few calls
                fh.write(("\n".join(batch) + "\n").encode("utf-8"))
                batch = []
        if batch:
            fh.write(("\n".join(batch) + "\n").encode("utf-8"))

    write_output(path, write)
