"""Read folders of G-code programs with this interpreter and with LinuxCNC's rs274, side by side.

    python -m tools.against_linuxcnc FOLDER [FOLDER ...] [--subroutines DIR ...] [--json]

Every .ngc, .nc, .gcode, .tap and .cnc file below the folders is read by LinuxCNC 2.9's
interpreter (``rs274``, which ``make test`` installs as root; subroutine files are looked for
in the program's folder, then in each ``--subroutines`` folder, as LinuxCNC's SUBROUTINE_PATH)
and by ``planner.gcode.interpreter.parse_program`` on an XYZABC machine with digital input 0, both
with tools 1-99 of no length and no diameter. Each program is put in one class:

- ``same``: both read it and write the same motion, call for call, within what rs274 prints
  (four decimals of the program's unit); moves shorter than that are not compared; a curve
  (G05, G05.1, G05.2) is one call of which rs274 prints the number of control points only, so
  it is compared by that and its place, and its points with those LinuxCNC's preview module
  draws (15 a control point, within 1e-6 mm) where the module can draw the program (installed,
  and no tool words: outside AXIS it stops on them);
- ``same path``: the calls differ in number only where moves are that short: walking both
  paths in order, every point of each lies within 0.003 mm of the other path, not behind
  where the point before it was found;
- ``differ``: both read it, and the motion differs (the first difference is shown);
- ``only rs274 reads it``, ``only this reads it``, ``both refuse``: with the reasons.

It prints a line for each program that is not ``same``, then the counts and the share of the
programs rs274 reads that this interpreter reads alike (``same`` and ``same path``). An integrator
runs it on a shop's program library before the machine changes control.
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from planner.core.errors import PlannerError, ProgramError
from planner.core.machine import WORK_OFFSET_NAMES, AxisSpec, MachineSpec
from planner.core.program import Curve, Program
from planner.core.tools import parse_tbl
from planner.gcode.interpreter import parse_program
from planner.geometry.splines import nurbs_points
from tools.linuxcnc_oracle import (
    RS274,
    motion_calls,
    preview_available,
    project_motion,
    run_linuxcnc_file,
    run_linuxcnc_preview,
)

SUFFIXES = (".ngc", ".nc", ".gcode", ".tap", ".cnc")
TOOLS = parse_tbl("".join(f"T{n} P{n} Z0 D0\n" for n in range(1, 100)))
# rs274 is an XYZABC machine: so is the one this reads on (rotary axes of any travel)
_BASE = MachineSpec.default()
MACHINE = replace(
    _BASE, name="XYZABC", input_bits={0: (0, 16, "")},
    axes=_BASE.axes + tuple(AxisSpec(name=n, rotary=True, drive_position=3 + i, min_pos=-1e6, max_pos=1e6,
                                     v_max=3600.0, a_max=36_000.0, j_max=360_000.0)
                            for i, n in enumerate("ABC")),
    work_offsets={n: (0.0,) * 6 for n in WORK_OFFSET_NAMES})
TOLERANCE_MM = 0.003  # LinuxCNC prints four decimals of an inch (0.00254 mm) in G20
CLASSES = ("same", "same path", "differ", "only rs274 reads it", "only this reads it", "both refuse")


@dataclass(frozen=True)
class Verdict:
    path: str
    kind: str   # one of CLASSES
    detail: str


def without_short_moves(motion: Sequence[tuple], ends: Sequence[Sequence[float]]) -> list[tuple]:
    """The calls whose move ends at least TOLERANCE_MM from where the last kept one ended (arcs
    and rigid taps always kept): LinuxCNC writes moves to where the tool already is, which a
    Program does not hold, and rounds what it prints."""
    out, last = [], np.zeros(3)
    for call, end in zip(motion, ends, strict=True):
        here = np.asarray(end[:3], dtype=float)
        if (call[0] not in ("arc_feed", "rigid_tap", "nurbs_feed")
                and np.max(np.abs(here - last)) < TOLERANCE_MM):
            continue
        out.append(call)
        last = here
    return out


def call_ends(program: Program) -> list[np.ndarray]:
    """Where each of the program's motion calls ends (``motion_calls``)."""
    return [np.asarray(end) for _, end in motion_calls(program)]


def close(a: tuple, b: tuple) -> bool:
    return a[0] == b[0] and all(abs(u - v) <= TOLERANCE_MM for u, v in zip(a[1], b[1]))


def _ours(program: Program, inch: bool) -> tuple[list[tuple], list[tuple]]:
    """This interpreter's motion calls, rounded as rs274 prints them: without the short moves
    (compared call by call) and all (for the path)."""
    unit = 25.4 if inch else 1.0

    def rounded(v: float) -> float:
        return round(v / unit, 4) * unit

    ends = [[rounded(float(v)) for v in end[:3]] for end in call_ends(program)]
    motion = [(call, tuple(x if (call == "arc_feed" and k == 4) or call == "nurbs_feed" else rounded(x)
                           for k, x in enumerate(args)))
              for call, args in project_motion(program)]
    return without_short_moves(motion, ends), motion


AHEAD = 64  # segments of the other path searched past the last match


def _follows(points: np.ndarray, path: np.ndarray) -> bool:
    """Whether each point, in order, lies within TOLERANCE_MM of a segment of ``path`` at or
    after the segment the point before it was found on (the same path, walked the same way:
    not only the same set of points)."""
    a, d = path[:-1], path[1:] - path[:-1]
    length2 = np.maximum((d * d).sum(1), 1e-30)
    k = 0
    for p in points:
        hi = min(k + AHEAD, len(a))
        t = np.clip(((p - a[k:hi]) * d[k:hi]).sum(1) / length2[k:hi], 0.0, 1.0)
        near = np.flatnonzero(np.sqrt((((a[k:hi] + t[:, None] * d[k:hi]) - p) ** 2).sum(1)) <= TOLERANCE_MM)
        if not len(near):
            return False
        k += int(near[0])
    return True


def _same_path(ours: list[tuple], theirs: list[tuple]) -> bool:
    """Whether two straight-move paths are the same within TOLERANCE_MM, walked in order (the
    arcs and curves must then be the same calls)."""
    curved = ("arc_feed", "nurbs_feed")
    arcs = [[c for c in calls if c[0] in curved] for calls in (ours, theirs)]
    if len(arcs[0]) != len(arcs[1]) or not all(close(x, y) for x, y in zip(*arcs)):
        return False
    # both start where the tool stands: the origin (LinuxCNC writes a move to it first)
    a = np.array([(0.0, 0.0, 0.0)] + [c[1][:3] for c in ours if c[0] not in curved], float)
    b = np.array([(0.0, 0.0, 0.0)] + [c[1][:3] for c in theirs if c[0] not in curved], float)
    return _follows(a, b) and _follows(b, a)


def preview_points(curve: Curve) -> np.ndarray:
    """The points LinuxCNC's preview draws a curve through (program coordinates, mm): 15 a
    control point, stepped as its loop steps, then the last control point."""
    points = np.array(curve.points)
    n = len(points) - 1
    umax = n - curve.order + 2
    step = umax / ((n + 1) * 15)
    us = []
    u = 0.0
    while u + step < umax:
        us.append(u + step)
        u = u + step
    return np.vstack([nurbs_points(points, curve.order, np.array(us)), points[-1:, :2]])


def curves_differ(path: Path, program: Program) -> str | None:
    """"" when every curve of ``program`` is the one LinuxCNC's preview draws for ``path`` (its
    points in order, within 1e-6 mm), which curve is not, or None when the preview cannot draw
    the program (outside AXIS it stops on any tool word: T, M6, M61, G43 H)."""
    try:
        drawn = np.array([args[:2] for call, args in run_linuxcnc_preview(path.read_text(errors="replace"))
                          if call == "straight_feed"])
    except RuntimeError:
        return None
    for curve in program.splines:
        ours = preview_points(curve)
        starts = np.flatnonzero(np.max(np.abs(drawn - ours[0]), axis=1) < 1e-6) if len(drawn) else []
        if not any(len(drawn) - s >= len(ours) and np.max(np.abs(drawn[s:s + len(ours)] - ours)) < 1e-6
                   for s in starts):
            return f"the curve of moves {curve.first + 1}-{curve.end} is not LinuxCNC's preview's"
    return ""


def judge(path: Path, subroutine_dirs: Sequence[Path] = ()) -> Verdict:
    """Read ``path`` both ways and class it; subroutine files are looked for in its folder, then in
    ``subroutine_dirs`` (as LinuxCNC's SUBROUTINE_PATH)."""
    extra = tuple(str(d.resolve()) for d in subroutine_dirs)
    theirs = run_linuxcnc_file(path, TOOLS, extra)
    text = path.read_text(errors="replace")
    try:
        program = parse_program(text, str(path), machine=MACHINE, tools=TOOLS, block_delete=False,
                                subroutine_dirs=(str(path.parent), *extra))
        upper = text.upper()
        ours, every = _ours(program, "G20" in upper and "G21" not in upper)
        why = ""
    except (ProgramError, PlannerError) as exc:
        ours, every, why = None, [], str(exc).splitlines()[0]
    if ours is None:
        kind = "both refuse" if theirs.error else "only rs274 reads it"
        return Verdict(str(path), kind, why + (f" | rs274: {theirs.error}" if theirs.error else ""))
    if theirs.error:
        return Verdict(str(path), "only this reads it", f"rs274: {theirs.error} at {theirs.error_block!r}")
    first = next((k for k, (a, b) in enumerate(zip(ours, theirs.motion)) if not close(a, b)), None)
    if first is None and len(ours) == len(theirs.motion):
        if not program.splines:
            return Verdict(str(path), "same", f"{len(ours)} calls")
        why = curves_differ(path, program) if preview_available() else None
        if why is None:
            return Verdict(str(path), "same", f"{len(ours)} calls (curves by their control points' count: "
                                              "LinuxCNC's preview module cannot draw the program here)")
        if why:
            return Verdict(str(path), "differ", why)
        return Verdict(str(path), "same", f"{len(ours)} calls, {len(program.splines)} curves as LinuxCNC's "
                                          "preview draws them")
    if _same_path(every, list(theirs.every)):
        return Verdict(str(path), "same path", f"{len(ours)} and {len(theirs.motion)} calls, within "
                                               f"{TOLERANCE_MM} mm in order")
    at = first if first is not None else min(len(ours), len(theirs.motion))
    mine = ours[at] if at < len(ours) else None
    lcnc = theirs.motion[at] if at < len(theirs.motion) else None
    return Verdict(str(path), "differ", f"call {at + 1} of {len(ours)} / {len(theirs.motion)}: "
                                        f"this {mine}, rs274 {lcnc}")


def programs_in(folders: Iterable[Path]) -> list[Path]:
    """The programs below ``folders`` (a file given is taken as it is)."""
    found: list[Path] = []
    for folder in folders:
        if folder.is_file():
            found.append(folder)
        else:
            found += sorted(p for p in folder.rglob("*") if p.is_file() and p.suffix.lower() in SUFFIXES)
    return found


def summary(verdicts: Sequence[Verdict]) -> dict:
    counts = {kind: sum(v.kind == kind for v in verdicts) for kind in CLASSES}
    read = counts["same"] + counts["same path"] + counts["differ"] + counts["only rs274 reads it"]
    alike = counts["same"] + counts["same path"]
    return {"programs": len(verdicts), **counts, "rs274 reads": read,
            "read alike of those": round(100.0 * alike / read, 1) if read else None}


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m tools.against_linuxcnc",
                                     description=(__doc__ or "").split("\n")[0])
    parser.add_argument("folders", nargs="+", type=Path)
    parser.add_argument("--json", action="store_true", help="one JSON object: every verdict and the counts")
    parser.add_argument("--subroutines", type=Path, action="append", default=[], metavar="DIR",
                        help="a folder of subroutine files (o<name> call), looked for after the program's "
                             "own folder, as LinuxCNC's SUBROUTINE_PATH; may be given more than once")
    args = parser.parse_args(argv)
    if RS274 is None:
        print("rs274 (LinuxCNC's interpreter, Debian package linuxcnc-uspace) is not installed: "
              "`make test` installs it as root", file=sys.stderr)
        return 2
    missing = [str(d) for d in args.subroutines if not d.is_dir()]
    if missing:
        print(f"--subroutines: no such folder: {', '.join(missing)}", file=sys.stderr)
        return 2
    verdicts = [judge(p, args.subroutines) for p in programs_in(args.folders)]
    totals = summary(verdicts)
    if args.json:
        print(json.dumps({"verdicts": [v.__dict__ for v in verdicts], "summary": totals}, indent=1))
        return 0
    for v in verdicts:
        if v.kind != "same":
            print(f"{v.kind:20s} {v.path}: {v.detail}")
    print(json.dumps(totals))
    return 0


if __name__ == "__main__":
    sys.exit(main())
