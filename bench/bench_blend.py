"""Path modes side by side on the shared CAM programs: G61, G61.1 and G64 P<tol>.

    python -m bench.bench_blend [--tol 0.01] [--jmax 10000] [--only NAME]
    python -m bench.bench_blend --passes NAME [--repeat 40]

Machine as in LinuxCNC's comparison runs: 100 mm/s, 1000 mm/s^2 per axis and along the path,
jerk --jmax (mm/s^3) per axis and path, 1 ms samples. Each program from ``../shared/gcode/cam``
is read once per mode with the mode's line put before its first move (the program's own G61 /
G64 words are replaced by it, so the mode holds throughout). Printed per program: cycle time
in each mode, the feed bound (each move at its programmed feed, no acceleration), the number
of corner blends, the moves before and after G64 Q joined lines (blends not counted), the
largest deviation of a blend from its programmed corner, and whether
the limit report (closed form and finite differences of every sample) found a violation -
including the jerk at joints, which G61.1 exceeds by its velocity steps and G64 P does not
where it blends. The last line printed is the JSON result.

``--passes NAME``: the time each pass of the blending takes on that program, its moves
repeated ``--repeat`` times over (51MeanderAve 40 times: 28,760 moves, 13,000 joints of arcs).
"""

from __future__ import annotations

import argparse
import json
import re
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from planner.core.errors import PlannerError, ProgramError
from planner.core.machine import MachineSpec
from planner.gcode.interpreter import parse_program
from planner.geometry.blend import blend_report
from planner.motion.blending import blend_program
from planner.motion.plan import plan_program

SHARED_CAM = Path(__file__).resolve().parents[2] / "shared" / "gcode" / "cam"
_MODE_WORD = re.compile(r"G6[14](?:\.1)?(?![0-9.])(?:\s*[PQ]\s*[-+]?[0-9.]+)*", re.IGNORECASE)
_FIRST_MOTION = re.compile(r"^\s*(?:N\d+\s*)?G0*[0-3](?![0-9.])|^\s*(?:N\d+\s*)?[XYZ][-+.0-9]", re.IGNORECASE)


def bench_machine(jmax: float) -> MachineSpec:
    base = MachineSpec.default()
    axes = tuple(replace(ax, v_max=100.0, a_max=1000.0, j_max=jmax, min_pos=-10_000.0, max_pos=10_000.0)
                 for ax in base.axes)
    return replace(base, axes=axes).with_limits(v_max_mm_s=100.0, a_max_mm_s2=1000.0, j_max_mm_s3=jmax,
                                                rapid_mm_s=100.0)


def with_mode(text: str, mode_line: str) -> str:
    """The program with ``mode_line`` before its first motion and no other path mode word."""
    out, placed = [], False
    for line in text.splitlines():
        code = line.split(";", 1)[0]
        stripped = _MODE_WORD.sub("", code) if "(" not in code else code
        if not placed and _FIRST_MOTION.search(stripped):
            out.append(mode_line)
            placed = True
        out.append(stripped if stripped != code else line)
    return "\n".join(out) + "\n"


def feed_bound_s(program) -> float:
    total = 0.0
    for m in program.moves:
        feed = 100.0 if not np.isfinite(m.feed_mm_s) else min(m.feed_mm_s, 100.0)
        total += m.length_mm / feed
    return total


def run_one(path: Path, machine: MachineSpec, tol: float) -> dict:
    text = path.read_text(errors="replace")
    row: dict = {"program": f"{path.parent.name}/{path.name}"}
    for label, mode_line in (("G61", "G61"), ("G61.1", "G61.1"), (f"G64 P{tol:g}", f"G64 P{tol:g}")):
        try:
            program = parse_program(with_mode(text, mode_line), path.name, machine)
        except (ProgramError, PlannerError) as exc:
            row[label] = f"not read: {str(exc).splitlines()[0]}"
            continue
        row[f"{label} moves"] = len(program.moves)
        if label.startswith("G64"):
            t = time.perf_counter()
            program = blend_program(program, machine)
            row["blend_s"] = time.perf_counter() - t
            rep = blend_report(program)
            row["blends"] = rep.blends
            row["max_deviation_mm"] = rep.max_corner_deviation_mm
            row["moves_after"] = len(program.moves) - rep.blends  # G64 Q joins lines
        else:
            row["feed_bound_s"] = feed_bound_s(program)
        plan = plan_program(program, machine)
        report = plan.limit_report()
        row[label] = plan.cycle_time_s
        row[f"{label} ok"] = report.ok
        row[f"{label} joint jerk x"] = report.joint_jerk.get("worst_ratio", 0.0)
        row[f"{label} contour_mm"] = report.contour_error_mm
    return row


def pass_times(path: Path, machine: MachineSpec, tol: float, repeat: int) -> dict:
    """Seconds of each blending pass on ``path``'s body (program ends left out) ``repeat`` times
    over in G64 P``tol``."""
    body = [line for line in path.read_text(errors="replace").splitlines()
            if not re.search(r"\b(M0?2|M30)\b|^\s*%", line, re.IGNORECASE)]
    text = with_mode("\n".join(body * repeat) + "\nM2\n", f"G64 P{tol:g}")
    t = time.perf_counter()
    program = parse_program(text, path.name, machine)
    row: dict = {"program": path.name, "repeat": repeat, "moves": len(program.moves),
                 "parse_s": time.perf_counter() - t}
    times: dict[str, float] = {}
    blended = blend_program(program, machine, pass_times_s=times)
    row.update({f"{name}_s": v for name, v in times.items()})
    row["moves_after"] = len(blended.moves)
    return row


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--tol", type=float, default=0.01, help="G64 P tolerance, mm")
    ap.add_argument("--jmax", type=float, default=10_000.0, help="jerk limit, mm/s^3")
    ap.add_argument("--only", help="a program name (substring)")
    ap.add_argument("--passes", metavar="NAME", help="time each blending pass on this program instead")
    ap.add_argument("--repeat", type=int, default=40, help="with --passes: its moves this many times over")
    args = ap.parse_args(argv)
    if not SHARED_CAM.is_dir():
        print(f"no shared CAM programs at {SHARED_CAM}")
        return 1
    machine = bench_machine(args.jmax)
    if args.passes:
        found = sorted(p for p in SHARED_CAM.glob("*/*") if args.passes in p.name)
        if not found:
            print(f"no shared CAM program named like {args.passes!r}")
            return 1
        row = pass_times(found[0], machine, args.tol, args.repeat)
        print(" ".join(f"{k} {v:.2f}" if isinstance(v, float) else f"{k} {v}" for k, v in row.items()))
        print(json.dumps(row))
        return 0
    rows = []
    for path in sorted(SHARED_CAM.glob("*/*")):
        if path.suffix.lower() not in (".nc", ".ngc", ".gcode", ".tap", ".cnc"):
            continue
        if args.only and args.only not in str(path):
            continue
        row = run_one(path, machine, args.tol)
        rows.append(row)
        g64 = f"G64 P{args.tol:g}"

        def fmt(v):
            return f"{v:9.2f}" if isinstance(v, float) else f"{str(v)[:9]:>9}"

        print(f"{row['program'][:40]:40} G61 {fmt(row.get('G61'))} G61.1 {fmt(row.get('G61.1'))} "
              f"{g64} {fmt(row.get(g64))} feed bound {fmt(row.get('feed_bound_s'))} "
              f"blends {row.get('blends', 0):6d} moves {row.get('G61.1 moves', 0):6d}->"
              f"{row.get('moves_after', 0):6d} dev {row.get('max_deviation_mm', 0.0):.4f} "
              f"ok {row.get('G61 ok')}/{row.get('G61.1 ok')}/{row.get(f'{g64} ok')} joint jerk x "
              f"{fmt(row.get('G61.1 joint jerk x'))}/{fmt(row.get(f'{g64} joint jerk x'))}", flush=True)
    print(json.dumps({"tol_mm": args.tol, "jmax": args.jmax, "rows": rows}))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
