"""Cycle times against LinuxCNC's trajectory planners on the shared CAM programs, G64 P0.01.

    python -m bench.bench_linuxcnc [--tol 0.01] [--only NAME] [--program FILE ...] [--skip-linuxcnc]
                                   [--skip-210] [--linuxcnc-210 DIR]

LinuxCNC 2.9 (Debian's ``linuxcnc-uspace``) runs each program in its own simulator, headless
(``bench/linuxcnc/``: trivkins XYZ, every axis and the path 100 mm/s and 1000 mm/s^2, a 1 ms
servo period, arc blends on; a DISPLAY program of ours that turns the machine on, homes, runs
the program and waits for its end; ``halsampler`` takes the joints' commanded positions every
millisecond, times 1000 so its six decimals keep nanometres). Its time is from the first to
the last sample that moves; its largest path acceleration is reported (over the 1000 mm/s^2 of
its configuration: it takes a straight move's acceleration from the axes, and overlaps moves
in its parabolic blends). It runs in real time, as a user other than root (rtapi refuses
root: as root the bench runs it as ``nobody``). Nothing of LinuxCNC is part of the project.

LinuxCNC 2.10's S-curve planner (``[TRAJ] PLANNER_TYPE = 1``, the jerk 1e4 mm/s^3 on the path,
every axis and joint) runs the same way from a run-in-place build of its development branch
(``../shared/linuxcnc/BUILD-2.10.md``; ``--linuxcnc-210`` or ``$LINUXCNC_210`` names the tree),
compared with ours at the same jerk; its axis jerk on the samples is reported (largest ratio to
1e4 and how many stencils exceed it by more than 1 %). Where no build is found, its column says so.

Ours: the same program with the same mode line before its first move (``bench_blend.with_mode``)
planned at the same speed and acceleration with jerk 1e6 (LinuxCNC's dynamics, practically
unlimited jerk) and 1e4 mm/s^3, also with the path's acceleration and jerk taken from the axes
as LinuxCNC takes them (``axis_rule``: the path limits hold in ours, not in it), and the limit
report of its samples (the largest path deviation of the blends, the largest axis jerk over the
limit, inside moves and across joints, and the joints crossed with a velocity step). The last
line is the JSON result.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import shutil
import subprocess
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from bench.bench_blend import SHARED_CAM, bench_machine, with_mode
from planner.core.errors import PlannerError, ProgramError
from planner.core.machine import MachineSpec
from planner.gcode.interpreter import parse_program
from planner.geometry.blend import blend_report
from planner.motion.blending import blend_program
from planner.motion.plan import plan_program

CONFIG = Path(__file__).resolve().parent / "linuxcnc"
SUFFIXES = (".nc", ".ngc", ".gcode", ".tap", ".cnc")


class LinuxCncUnavailable(RuntimeError):
    """LinuxCNC cannot run here (not installed, or no user to run it as)."""


@dataclass(frozen=True, slots=True)
class Reference:
    """A LinuxCNC to compare with: the installed one (``root`` None) or a run-in-place build
    (``root`` its source tree, run through its ``scripts/rip-environment``); trapezoidal
    (``jerk_mm_s3`` None) or its S-curve planner at that jerk (``[TRAJ] PLANNER_TYPE = 1``)."""

    label: str
    root: Path | None = None
    jerk_mm_s3: float | None = None


LINUXCNC_29 = Reference("LinuxCNC 2.9")
# where BUILD-2.10.md's build is put by default; LINUXCNC_210 names another tree
LINUXCNC_210_ROOT = Path(os.environ.get("LINUXCNC_210", "/var/tmp/linuxcnc-2.10/src"))


def ini_text(ref: Reference) -> str:
    """The bench configuration for ``ref``: for the S-curve planner, ``PLANNER_TYPE = 1`` and
    the jerk on the path (``MAX_LINEAR_JERK``) and on every axis and joint (``MAX_JERK``: a
    move over an axis without it falls back to trapezoidal planning)."""
    text = (CONFIG / "sim.ini").read_text()
    if ref.jerk_mm_s3 is None:
        return text
    jerk = f"{ref.jerk_mm_s3:g}"
    out = []
    for line in text.splitlines():
        out.append(line)
        if line == "[TRAJ]":
            out += ["PLANNER_TYPE = 1", f"MAX_LINEAR_JERK = {jerk}"]
        elif line.startswith(("[AXIS_", "[JOINT_")):
            out.append(f"MAX_JERK = {jerk}")
    return "\n".join(out) + "\n"


def linuxcnc_time_s(text: str, timeout_s: float = 3600.0,
                    ref: Reference = LINUXCNC_29) -> tuple[float, np.ndarray, str]:
    """LinuxCNC's motion time of ``text`` (s), its samples (N, 3) in mm, and what it said
    ("ok", or its errors: one at the end, such as a file without M2, leaves the motion whole)."""
    if ref.root is None:
        if shutil.which("linuxcnc") is None or shutil.which("halsampler") is None:
            raise LinuxCncUnavailable("linuxcnc is not installed: apt-get install linuxcnc-uspace")
        launch = ["linuxcnc"]
    else:
        rip = ref.root / "scripts" / "rip-environment"
        if not (rip.is_file() and (ref.root / "bin" / "milltask").is_file()):
            raise LinuxCncUnavailable(f"no LinuxCNC build at {ref.root} "
                                      "(see ../shared/linuxcnc/BUILD-2.10.md)")
        launch = [str(rip), "linuxcnc"]
    with tempfile.TemporaryDirectory(prefix="bench-linuxcnc-") as tmp:
        work = Path(tmp)
        for f in CONFIG.iterdir():
            shutil.copy2(f, work / f.name)
        (work / "sim.ini").write_text(ini_text(ref))
        (work / "program.ngc").write_text(text)
        env = {"HOME": tmp, "PATH": "/usr/sbin:/usr/bin:/sbin:/bin",
               "BENCH_PROGRAM": str(work / "program.ngc"), "BENCH_DONE": str(work / "done"),
               "BENCH_SAMPLES": str(work / "samples.txt"), "BENCH_TIMEOUT_S": str(timeout_s)}
        cmd = [*launch, str(work / "sim.ini")]
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


def axis_rule(machine: MachineSpec) -> MachineSpec:
    """``machine`` with the path's acceleration and jerk as LinuxCNC 2.9 takes them on a straight
    move, from the axes alone (``emccanon``'s getStraightAcceleration: each axis at its limit
    over its share of the move): the path limits raised to what the linear axes allow together,
    so that they never bind before an axis does. The path speed stays."""
    linear = [a for a in machine.axes if not a.rotary]
    a_all = math.sqrt(sum(a.a_max ** 2 for a in linear))
    j_all = math.sqrt(sum(a.j_max ** 2 for a in linear))
    return machine.with_limits(v_max_mm_s=machine.limits.v_max_mm_s, a_max_mm_s2=a_all, j_max_mm_s3=j_all,
                               rapid_mm_s=machine.limits.rapid_mm_s)


def ours(text: str, name: str, jmax: float, path_rule: bool = False) -> dict[str, float | bool]:
    """Our plan of ``text`` on the bench machine at jerk ``jmax`` (``path_rule``: with the path's
    acceleration and jerk taken from the axes, LinuxCNC 2.9's rule, ``axis_rule``)."""
    machine = bench_machine(jmax)
    if path_rule:
        machine = axis_rule(machine)
    program = blend_program(parse_program(text, name, machine), machine)
    plan = plan_program(program, machine)
    report = plan.limit_report()
    j_axis = {a.name: a.j_max for a in machine.axes}
    return {"time_s": plan.cycle_time_s, "ok": report.ok,
            "deviation_mm": blend_report(program).max_corner_deviation_mm,
            # the largest axis jerk of the samples (inside moves and across joints) over the limit
            "axis_jerk_x": max(max(v["j"], v["j_joint"]) / j_axis[name] for name, v in report.axes.items()),
            "joint_jerk_x": max(v["j_joint"] / j_axis[name] for name, v in report.axes.items()),
            "corner_steps": int(report.corner_steps["count"])}  # type: ignore[call-overload]


def jerk_ratio(q: np.ndarray, jmax: float) -> float:
    """The largest axis jerk of samples q (1 ms apart) over ``jmax``."""
    if len(q) < 4:
        return 0.0
    return float(np.max(np.abs(np.diff(q, n=3, axis=0))) / 1e-9 / jmax)


def jerk_over(q: np.ndarray, jmax: float, factor: float) -> int:
    """How many third differences of samples q (axis by axis) exceed ``factor`` times ``jmax``."""
    if len(q) < 4:
        return 0
    return int(np.count_nonzero(np.abs(np.diff(q, n=3, axis=0)) / 1e-9 > factor * jmax))


def path_accel_ratio(q: np.ndarray, amax: float) -> tuple[float, int]:
    """The largest path acceleration of samples q (1 ms apart) over ``amax``, and how many
    second differences exceed it by more than 1 %: LinuxCNC takes a straight move's
    acceleration from its axes (up to sqrt(3) ``amax`` on a diagonal at equal axis limits) and
    overlaps two moves in its parabolic blends, past ``[TRAJ] MAX_LINEAR_ACCELERATION``."""
    if len(q) < 3:
        return 0.0, 0
    a = np.sqrt((np.diff(q, n=2, axis=0) ** 2).sum(axis=1)) / 1e-6
    return float(a.max() / amax), int(np.count_nonzero(a > 1.01 * amax))


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--tol", type=float, default=0.01, help="G64 P tolerance, mm")
    ap.add_argument("--only", help="a program name (substring)")
    ap.add_argument("--exclude", action="append", default=[], help="leave out a program (substring)")
    ap.add_argument("--program", action="append", type=Path, default=[],
                    help="another program to run beside the shared CAM programs (repeatable), such as "
                         "those of LinuxCNC's tests/trajectory-planner/circular-arcs/nc_files/performance")
    ap.add_argument("--skip-linuxcnc", action="store_true", help="ours only (LinuxCNC runs in real time)")
    ap.add_argument("--skip-210", action="store_true", help="not LinuxCNC 2.10's S-curve planner")
    ap.add_argument("--linuxcnc-210", type=Path, default=LINUXCNC_210_ROOT,
                    help="the run-in-place LinuxCNC 2.10 tree (BUILD-2.10.md), default %(default)s")
    args = ap.parse_args(argv)
    references: list[tuple[Reference, str]] = []
    if not args.skip_linuxcnc:
        references.append((LINUXCNC_29, "linuxcnc 2.9"))
        if not args.skip_210:
            scurve = Reference("LinuxCNC 2.10 S-curve", args.linuxcnc_210, 1e4)
            references.append((scurve, "linuxcnc 2.10 J1e4"))
    if not SHARED_CAM.is_dir() and not args.program:
        print(f"no shared CAM programs at {SHARED_CAM}")
        return 1
    missing = [str(p) for p in args.program if not p.is_file()]
    if missing:
        print(f"no such program: {', '.join(missing)}")
        return 1
    shared = sorted(SHARED_CAM.glob("*/*")) if SHARED_CAM.is_dir() else []
    rows = []
    for path in shared + list(args.program):
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
            for jmax in (1e6, 1e4):
                for key, value in ours(text, path.name, jmax, path_rule=True).items():
                    row[f"ours J{jmax:.0e} axis rule {key}"] = value
        except (ProgramError, PlannerError) as exc:
            row["ours"] = f"not read: {str(exc).splitlines()[0]}"
        # LinuxCNC can wait for ever after an error of its own: a bound from ours
        ours_s = row.get("ours J1e+06 time_s")
        bound = 120.0 + 3.0 * ours_s if isinstance(ours_s, float) else 600.0
        for ref, key in references:
            try:
                t, q, said = linuxcnc_time_s(text, timeout_s=bound, ref=ref)
                row[f"{key} s"] = t
                row[f"{key} jerk x at 1e4"] = jerk_ratio(q, 1e4)
                row[f"{key} jerk stencils over 1.01x"] = jerk_over(q, 1e4, 1.01)
                ratio_a, over_a = path_accel_ratio(q, 1000.0)
                row[f"{key} path accel x"] = ratio_a
                row[f"{key} path accel samples over 1.01x"] = over_a
                row[f"{key} said"] = said
            except (LinuxCncUnavailable, subprocess.TimeoutExpired) as exc:
                row[f"{key} s"] = f"not run: {exc}"
        rows.append(row)
        lc, lc10 = row.get("linuxcnc 2.9 s"), row.get("linuxcnc 2.10 J1e4 s")
        fast, slow = row.get("ours J1e+06 time_s"), row.get("ours J1e+04 time_s")

        def fmt(v: object) -> str:
            return f"{v:9.2f}" if isinstance(v, float) else f"{str(v)[:9] if v is not None else '-':>9}"

        both = isinstance(fast, float) and isinstance(lc, float) and lc
        ratio = f"{fast / lc:6.3f}x" if both else "   -   "  # type: ignore[operator]
        both10 = isinstance(slow, float) and isinstance(lc10, float) and lc10
        ratio10 = f"{slow / lc10:6.3f}x" if both10 else "   -   "  # type: ignore[operator]
        rule = row.get("ours J1e+06 axis rule time_s")
        both_rule = isinstance(rule, float) and isinstance(lc, float) and lc
        ratio_rule = f"{rule / lc:6.3f}x" if both_rule else "   -   "  # type: ignore[operator]
        rule10 = row.get("ours J1e+04 axis rule time_s")
        both_rule10 = isinstance(rule10, float) and isinstance(lc10, float) and lc10
        ratio_rule10 = f"{rule10 / lc10:6.3f}x" if both_rule10 else "   -   "  # type: ignore[operator]
        print(f"{name[:40]:40} 2.9 {fmt(lc)} (path accel x {row.get('linuxcnc 2.9 path accel x', 0.0):.2f}) "
              f"ours J=1e6 {fmt(fast)} ({ratio}), axis rule {fmt(rule)} ({ratio_rule}) "
              f"| 2.10 J=1e4 {fmt(lc10)} "
              f"(jerk x {row.get('linuxcnc 2.10 J1e4 jerk x at 1e4', 0.0):.2f}) ours J=1e4 {fmt(slow)} "
              f"({ratio10}), axis rule {fmt(rule10)} ({ratio_rule10}) "
              f"dev {row.get('ours J1e+04 deviation_mm', 0.0):.4f} axis jerk x "
              f"{row.get('ours J1e+04 axis_jerk_x', 0.0):.4f}", flush=True)
    print(json.dumps({"tol_mm": args.tol, "rows": rows}))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
