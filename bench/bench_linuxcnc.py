"""Cycle times against LinuxCNC 2.9's trajectory planner on the shared CAM programs, G64 P0.01.

    python -m bench.bench_linuxcnc [--tol 0.01] [--only NAME] [--skip-linuxcnc]

LinuxCNC 2.9 (Debian's ``linuxcnc-uspace``) runs each program in its own simulator, headless
(``bench/linuxcnc/``: trivkins XYZ, every axis and the path 100 mm/s and 1000 mm/s^2, a 1 ms
servo period, arc blends on; a DISPLAY program of ours that turns the machine on, homes, runs
the program and waits for its end; ``halsampler`` takes the joints' commanded positions every
millisecond, times 1000 so its six decimals keep nanometres). Its time is from the first to
the last sample that moves. It runs in real time, as a user other than root (rtapi refuses
root: as root the bench runs it as ``nobody``). Nothing of LinuxCNC is part of the project.

Ours: the same program with the same mode line before its first move (``bench_blend.with_mode``)
planned at the same speed and acceleration with jerk 1e6 (LinuxCNC's dynamics, practically
unlimited jerk) and 1e4 mm/s^3, and the limit report of its samples (the largest path deviation
of the blends, the jerk at joints that are not blended). The last line is the JSON result.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import tempfile
from pathlib import Path

import numpy as np

from bench.bench_blend import SHARED_CAM, bench_machine, with_mode
from planner.core.errors import PlannerError, ProgramError
from planner.gcode.interpreter import parse_program
from planner.geometry.blend import blend_report
from planner.motion.blending import blend_program
from planner.motion.plan import plan_program

CONFIG = Path(__file__).resolve().parent / "linuxcnc"
SUFFIXES = (".nc", ".ngc", ".gcode", ".tap", ".cnc")


class LinuxCncUnavailable(RuntimeError):
    """LinuxCNC cannot run here (not installed, or no user to run it as)."""


def linuxcnc_time_s(text: str, timeout_s: float = 3600.0) -> tuple[float, np.ndarray, str]:
    """LinuxCNC 2.9's motion time of ``text`` (s), its samples (N, 3) in mm, and what it said
    ("ok", or its errors: one at the end, such as a file without M2, leaves the motion whole)."""
    if shutil.which("linuxcnc") is None or shutil.which("halsampler") is None:
        raise LinuxCncUnavailable("linuxcnc is not installed: apt-get install linuxcnc-uspace")
    with tempfile.TemporaryDirectory(prefix="bench-linuxcnc-") as tmp:
        work = Path(tmp)
        for f in CONFIG.iterdir():
            shutil.copy2(f, work / f.name)
        (work / "program.ngc").write_text(text)
        env = {"HOME": tmp, "PATH": "/usr/sbin:/usr/bin:/sbin:/bin",
               "BENCH_PROGRAM": str(work / "program.ngc"), "BENCH_DONE": str(work / "done"),
               "BENCH_SAMPLES": str(work / "samples.txt"), "BENCH_TIMEOUT_S": str(timeout_s)}
        cmd = ["linuxcnc", str(work / "sim.ini")]
        if os.geteuid() == 0:                  # rtapi refuses root
            os.chmod(tmp, 0o777)
            for f in work.iterdir():
                os.chmod(f, 0o777 if f.suffix == ".py" else 0o666)
            cmd = ["runuser", "-u", "nobody", "--", "env", *(f"{k}={v}" for k, v in env.items()), *cmd]
        done = subprocess.run(cmd, cwd=tmp, env={**os.environ, **env}, capture_output=True, text=True,
                              timeout=timeout_s + 120)
        status = (work / "done").read_text() if (work / "done").exists() else ""
        samples = work / "samples.txt"
        if not status or not samples.exists() or samples.stat().st_size == 0:
            raise LinuxCncUnavailable(f"linuxcnc: {status or done.stdout[-400:] + done.stderr[-400:]}")
        q = np.loadtxt(samples, ndmin=2)[:, :3] / 1000.0
    moving = np.flatnonzero(np.any(np.abs(np.diff(q, axis=0)) > 1e-9, axis=1))
    if not len(moving):
        return 0.0, q, status
    return float(moving[-1] - moving[0] + 1) * 1e-3, q[moving[0]:moving[-1] + 2], status


def ours(text: str, name: str, jmax: float) -> dict[str, float | bool]:
    machine = bench_machine(jmax)
    program = blend_program(parse_program(text, name, machine), machine)
    plan = plan_program(program, machine)
    report = plan.limit_report()
    return {"time_s": plan.cycle_time_s, "ok": report.ok,
            "deviation_mm": blend_report(program).max_corner_deviation_mm,
            "joint_jerk_x": float(report.joint_jerk.get("worst_ratio", 0.0))}


def jerk_ratio(q: np.ndarray, jmax: float) -> float:
    """The largest axis jerk of samples q (1 ms apart) over ``jmax``."""
    if len(q) < 4:
        return 0.0
    return float(np.max(np.abs(np.diff(q, n=3, axis=0))) / 1e-9 / jmax)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--tol", type=float, default=0.01, help="G64 P tolerance, mm")
    ap.add_argument("--only", help="a program name (substring)")
    ap.add_argument("--exclude", action="append", default=[], help="leave out a program (substring)")
    ap.add_argument("--skip-linuxcnc", action="store_true", help="ours only (LinuxCNC runs in real time)")
    args = ap.parse_args(argv)
    if not SHARED_CAM.is_dir():
        print(f"no shared CAM programs at {SHARED_CAM}")
        return 1
    rows = []
    for path in sorted(SHARED_CAM.glob("*/*")):
        if (path.suffix.lower() not in SUFFIXES or (args.only and args.only not in str(path))
                or any(x in str(path) for x in args.exclude)):
            continue
        name = f"{path.parent.name}/{path.name}"
        text = with_mode(path.read_text(errors="replace"), f"G64 P{args.tol:g}")
        row: dict[str, object] = {"program": name}
        try:
            for jmax in (1e6, 1e4):
                for key, value in ours(text, path.name, jmax).items():
                    row[f"ours J{jmax:.0e} {key}"] = value
        except (ProgramError, PlannerError) as exc:
            row["ours"] = f"not read: {str(exc).splitlines()[0]}"
        if not args.skip_linuxcnc:
            try:
                # LinuxCNC can wait for ever after an error of its own: a bound from ours
                ours_s = row.get("ours J1e+06 time_s")
                bound = 120.0 + 3.0 * ours_s if isinstance(ours_s, float) else 600.0
                t, q, said = linuxcnc_time_s(text, timeout_s=bound)
                row["linuxcnc 2.9 s"] = t
                row["linuxcnc 2.9 jerk x at 1e4"] = jerk_ratio(q, 1e4)
                row["linuxcnc 2.9 said"] = said
            except (LinuxCncUnavailable, subprocess.TimeoutExpired) as exc:
                row["linuxcnc 2.9 s"] = f"not run: {exc}"
        rows.append(row)
        lc = row.get("linuxcnc 2.9 s")
        fast, slow = row.get("ours J1e+06 time_s"), row.get("ours J1e+04 time_s")

        def fmt(v: object) -> str:
            return f"{v:9.2f}" if isinstance(v, float) else f"{str(v)[:9]:>9}"

        both = isinstance(fast, float) and isinstance(lc, float) and lc
        ratio = f"{fast / lc:6.3f}x" if both else "   -   "  # type: ignore[operator]
        print(f"{name[:44]:44} LinuxCNC 2.9 {fmt(lc)}  ours J=1e6 {fmt(fast)} ({ratio})  "
              f"J=1e4 {fmt(slow)}  dev {row.get('ours J1e+04 deviation_mm', 0.0):.4f}  joint jerk x "
              f"{row.get('ours J1e+04 joint_jerk_x', 0.0):.1f}", flush=True)
    print(json.dumps({"tol_mm": args.tol, "rows": rows}))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
