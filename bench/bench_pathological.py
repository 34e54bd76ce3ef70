"""Pathological inputs read within stated bounds of time and memory.

    python -m bench.bench_pathological

Each input is what a careless or hostile user has given the commands: a program of repeated
points, a NURBS of 20,000 control points, a 30 MB comment line, a 20 MB line of words, a
configuration from /dev/zero, a limit of 1e100, a G7x profile with a coordinate of 1e300.
Each runs ``cnc-plan`` in a process of its own; its wall time and peak resident memory are
measured (``wait4`` of the child) and held to the bound stated beside it. Prints one line a
case and, last, one JSON object; exits 1 when a case is over its bound or ends otherwise than
stated.
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def _repeated(n: int) -> str:
    return "G21 G90 G1 F1000\nX1\n" + "G1 X0\n" * n + "M2\n"


def _nurbs(n: int) -> str:
    body = "".join(f"X{i * 0.1:.3f} Y{10 * math.sin(i * 0.05):.3f} P1\n" for i in range(1, n))
    return "G21 G90 G17 F600\nG0 X0 Y0\nG5.2 X0 Y0 P1 L3\n" + body + "G5.3\nM2\n"


def _g7x(value: str) -> str:
    return ("G21 G18 G90 F300\nO100 SUB\nG0 X0 Z3\nG1 X2 Z0\n" f"G1 X[{value}] Z-5\nG1 Z-10\nG0 X12\n"
            "O100 ENDSUB\nG71 Q100 X12 Z3 D0.3 I0.7 R0.3\nM2\n")


#: name: (program text, extra arguments, the exit status it ends with, seconds, MB at most)
CASES: dict[str, tuple[str, list[str], int, float, float]] = {
    "600,000 repeated points": (_repeated(600_000), [], 0, 10.0, 300.0),
    "NURBS of 20,000 points": (_nurbs(20_000), [], 0, 30.0, 600.0),
    "30 MB comment line": ("G21 G90\n(" + "x" * 30_000_000 + ")\nG1 X1 F100\nM2\n", [], 0, 10.0, 800.0),
    "20 MB line of words": ("G21 G90 F100 G1 " + " ".join("X1" for _ in range(5_000_000)) + "\nM2\n", [], 2,
                            10.0, 800.0),
    "configuration /dev/zero": ("G21\nG1 X1 F100\nM2\n", ["--config", "/dev/zero"], 2, 15.0, 300.0),
    "--vmax 1e100": ("G21\nG0 X100\nG1 X0 Y50 F1000\nM2\n", ["--vmax", "1e100"], 2, 15.0, 300.0),
    "G71 profile X 1e300": (_g7x("10**300"), [], 2, 15.0, 300.0),
    "G71 profile X inf": (_g7x("10**308*10"), [], 2, 15.0, 300.0),
}


def run_case(text: str, args: list[str]) -> tuple[int, float, float, str]:
    """(exit status, wall seconds, peak MB, the last line said) of ``cnc-plan`` on ``text``:
    the child's own peak resident memory, from ``wait4``."""
    with tempfile.TemporaryDirectory() as folder:
        program = Path(folder) / "p.ngc"
        program.write_text(text)
        out, err = Path(folder) / "out", Path(folder) / "err"
        started = time.perf_counter()
        with out.open("w") as fo, err.open("w") as fe:
            proc = subprocess.Popen([sys.executable, "-m", "cli.plan", str(program), *args], cwd=ROOT,
                                    stdout=fo, stderr=fe)
            _, status, usage = os.wait4(proc.pid, 0)
        wall = time.perf_counter() - started
        proc.returncode = os.waitstatus_to_exitcode(status)
        said = (err.read_text().strip().splitlines() or out.read_text().strip().splitlines() or [""])[-1]
    return proc.returncode, wall, usage.ru_maxrss / 1024.0, said[:120]


def main() -> int:
    results = {}
    over = 0
    for name, (text, args, status, seconds, mb) in CASES.items():
        code, wall, peak, said = run_case(text, args)
        ok = code == status and wall <= seconds and peak <= mb
        over += not ok
        results[name] = {"exit": code, "s": round(wall, 2), "peak_mb": round(peak), "bound_s": seconds,
                         "bound_mb": mb, "ok": ok}
        print(f"{'ok  ' if ok else 'OVER'} {name:28} exit {code} (stated {status})  {wall:6.2f} s "
              f"(<= {seconds:g})  {peak:7.0f} MB (<= {mb:g})  {said}", flush=True)
    print(json.dumps(results))
    return 1 if over else 0


if __name__ == "__main__":
    sys.exit(main())
