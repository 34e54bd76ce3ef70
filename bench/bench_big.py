"""Programs of any size: ``cnc-plan`` against LinuxCNC's own interpreter, side by side.

    python -m bench.bench_big [--lines 2000000] [--repeat 2] [--keep DIR]

Writes three programs (cached in a temporary folder, or DIR): a raster finishing program of
``--lines`` 0.1 mm G01 lines over a wavy surface (the tyre-mould finishing of the paper's
machine), the same raster with 16,000 lines, the 35,000-line sphere finishing program of G01
chords and the 35,000-line one of helical arcs (``bench.gen_programs``).
Each is run as a whole process, ``cnc-plan PROG`` (read, plan, report the cycle time) and
``rs274 -g PROG`` (LinuxCNC's C++ interpreter alone, when it is installed: ``make test`` installs
it as root), alternately ``--repeat`` times; the best wall time of each and the peak memory of
that run (the kernel's maximum resident set of the child, which includes the ~15 MB of this
process that forks it) are reported. The sphere programs are also run with ``--json`` (the
full limit report of every sample): how many times faster than real time.

Prints one JSON object; the goals are in README's figures table.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def raster(lines: int, step_mm: float = 0.1, width_mm: float = 100.0) -> str:
    """Zig-zag rows of G01 lines ``step_mm`` apart along X over z = f(x, y), 0.2 mm stepover."""
    per_row = max(2, round(width_mm / step_mm))
    rows = max(1, math.ceil(lines / per_row))
    out = ["G21 G90 G17 G64", "G0 Z5", "G0 X0 Y0", "G1 Z0 F3000"]
    written = 0
    for r in range(rows):
        y = 0.2 * r
        cols = range(per_row) if r % 2 == 0 else range(per_row - 1, -1, -1)
        for c in cols:
            if written >= lines:
                break
            x = c * step_mm
            z = 0.5 * math.sin(x / 7.0) * math.cos(y / 11.0)
            out.append(f"X{x:.3f} Y{y:.3f} Z{z:.4f}")
            written += 1
    out += ["G0 Z5", "M2", ""]
    return "\n".join(out)


def _programs(folder: Path, lines: int) -> dict[str, Path]:
    from bench.gen_programs import sphere_finishing, sphere_helical

    folder.mkdir(parents=True, exist_ok=True)
    wanted = {f"raster_{lines}": lambda: raster(lines), "raster_16000": lambda: raster(16_000),
              "sphere_finishing": sphere_finishing, "sphere_helical": sphere_helical}
    paths = {}
    for name, make in wanted.items():
        path = folder / f"{name}.ngc"
        if not path.is_file():
            path.write_text(make(), encoding="utf-8")
        paths[name] = path
    return paths


def _run(cmd: list[str]) -> tuple[float, float, str]:
    """(wall seconds, peak resident memory in MB, stdout) of one whole process. rs274's output
    (its canonical calls, hundreds of MB) is thrown away: read here, it would grow this process,
    whose size every later child's peak would then count."""
    started = time.perf_counter()
    keep = "rs274" not in Path(cmd[0]).name
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE if keep else subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL, text=True)
    out = proc.stdout.read() if proc.stdout is not None else ""
    _, status, usage = os.wait4(proc.pid, 0)  # the child's own peak memory (KB on Linux)
    wall = time.perf_counter() - started
    proc.returncode = os.waitstatus_to_exitcode(status)
    if proc.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)}: exit status {proc.returncode}")
    return wall, usage.ru_maxrss / 1024.0, out


def measure(cmds: list[list[str]], repeat: int) -> list[dict]:
    """Each command run ``repeat`` times, taking turns (so that the machine's load falls on all
    alike); per command the best run: its wall time, its peak memory, its output."""
    runs: list[list[tuple[float, float, str]]] = [[] for _ in cmds]
    for _ in range(repeat):
        for cmd, got in zip(cmds, runs):
            got.append(_run(cmd))
    best = [min(got, key=lambda r: r[0]) for got in runs]
    return [{"wall_s": round(w, 3), "peak_mb": round(p), "stdout": o} for w, p, o in best]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--lines", type=int, default=2_000_000)
    ap.add_argument("--repeat", type=int, default=2)
    ap.add_argument("--keep", help="folder for the generated programs (default: a temporary one, kept)")
    ap.add_argument("--generate", action="store_true", help="only write the programs")
    args = ap.parse_args(argv)
    folder = Path(args.keep) if args.keep else Path(tempfile.gettempdir()) / "cnc-bench-big"
    if args.generate:
        _programs(folder, args.lines)
        return 0
    # written by a process of its own: a child's peak memory counts the pages of the process
    # that forks it (the kernel keeps the larger of the two at exec), so this one stays small
    subprocess.run([sys.executable, "-m", "bench.bench_big", "--generate", "--lines", str(args.lines),
                    "--keep", str(folder)], check=True, cwd=ROOT)
    paths = _programs(folder, args.lines)
    cnc_plan = [sys.executable, "-m", "cli.plan"]
    rs274 = shutil.which("rs274")
    result: dict[str, object] = {"rs274": rs274 or "not installed"}
    for name in (f"raster_{args.lines}", "raster_16000"):
        path = str(paths[name])
        got = measure([[*cnc_plan, path]] + ([[rs274, "-g", path]] if rs274 else []), args.repeat)
        ours = got[0]
        with open(path, "rb") as fh:
            n_lines = sum(1 for _ in fh)
        row: dict[str, object] = {"lines": n_lines, "summary": ours["stdout"].strip(),
                                  "cnc_plan": {k: v for k, v in ours.items() if k != "stdout"}}
        if rs274:
            theirs = got[1]
            row["rs274"] = {k: v for k, v in theirs.items() if k != "stdout"}
            row["time_ratio"] = round(ours["wall_s"] / theirs["wall_s"], 2)
        result[name] = row
        print(json.dumps({name: row}), flush=True)
    for name in ("sphere_finishing", "sphere_helical"):
        sphere = measure([[*cnc_plan, str(paths[name]), "--json"]], args.repeat)[0]
        report = json.loads(sphere["stdout"])
        result[f"{name}_json"] = {
            "wall_s": sphere["wall_s"], "peak_mb": sphere["peak_mb"], "cycle_time_s": report["cycle_time_s"],
            "samples": report["samples"], "ok": report["ok"],
            "times_real_time": round(report["cycle_time_s"] / sphere["wall_s"])}
    print(json.dumps(result))
    return 0


if __name__ == "__main__":
    sys.exit(main())
