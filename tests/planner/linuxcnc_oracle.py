"""LinuxCNC's own interpreter as an oracle: ``rs274`` (Debian's linuxcnc-uspace, installed by
`make test` as root) reads a program and prints its canonical calls; this module runs it and
turns the calls into comparable motion records (millimetres)."""

from __future__ import annotations

import re
import shutil
import subprocess
import tempfile
from dataclasses import dataclass
from pathlib import Path

from planner.canon import canon_records
from planner.program import Program
from planner.tools import ToolTable

RS274 = shutil.which("rs274")
_CALL = re.compile(r"^\s*\d+\s+N\.+\s+([A-Z_0-9]+)\((.*)\)\s*$")


@dataclass(frozen=True)
class OracleResult:
    motion: list[tuple]          # ("straight_traverse" | "straight_feed", (x, y, z)) or arcs
    error: str                   # LinuxCNC's error text, "" when the program ran to its end
    error_block: str             # the block LinuxCNC printed after the error


def _tbl_for_rs274(tools: ToolTable) -> str:
    """The stand-alone rs274 reads its tool table in inches: millimetre tools are written so."""
    lines = []
    for t in tools:
        words = [f"T{t.number}", f"P{t.pocket}"]
        words += [f"{a}{v / 25.4:.9f}" for a, v in t.offsets_mm]
        if t.diameter_mm:
            words.append(f"D{t.diameter_mm / 25.4:.9f}")
        lines.append(" ".join(words))
    return "\n".join(lines) + "\n"


def run_linuxcnc(text: str, tools: ToolTable | None = None) -> OracleResult:
    assert RS274 is not None
    with tempfile.TemporaryDirectory() as tmp:
        prog = Path(tmp) / "p.ngc"
        prog.write_text(text)
        args = [RS274, "-g"]
        if tools is not None:
            (Path(tmp) / "t.tbl").write_text(_tbl_for_rs274(tools))
            args += ["-t", str(Path(tmp) / "t.tbl")]
        # errors go to stderr: one stream keeps them where they happened
        out = subprocess.run(args + [str(prog)], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                             timeout=60, cwd=tmp, stdin=subprocess.DEVNULL).stdout
    motion: list[tuple] = []
    scale = 1.0
    error = block = ""
    lines = out.splitlines()
    for k, line in enumerate(lines):
        m = _CALL.match(line)
        if not m:
            if line.strip() and line.strip() != "executing" and not error:
                error = line.strip()
                block = lines[k + 1].strip() if k + 1 < len(lines) else ""
            continue
        if error:
            continue
        name, args_t = m.group(1), [a.strip() for a in m.group(2).split(",")] if m.group(2) else []
        if name == "USE_LENGTH_UNITS":
            scale = 25.4 if "INCHES" in args_t[0] else 1.0
        elif name in ("STRAIGHT_TRAVERSE", "STRAIGHT_FEED"):
            motion.append((name.lower(), tuple(float(v) * scale for v in args_t[:3])))
        elif name == "ARC_FEED":
            v = [float(a) for a in args_t[:6]]
            motion.append(("arc_feed", (v[0] * scale, v[1] * scale, v[2] * scale, v[3] * scale, v[4],
                                        v[5] * scale)))
    return OracleResult(_without_zero_moves(motion), error, block)


def _without_zero_moves(motion: list[tuple]) -> list[tuple]:
    """LinuxCNC writes moves to where the tool already is; a Program has none. (The generated
    programs move on a 0.1 mm grid, so no real move is this short.)"""
    out = []
    last: tuple | None = (0.0, 0.0, 0.0)       # both start at the origin
    for call, args in motion:
        if call == "arc_feed":
            out.append((call, args))
            last = (args[0], args[1], args[5])        # the end of a G17 arc (the oracle's plane)
            continue
        end = args[:3]
        # within what LinuxCNC prints (four decimals of an inch in G20): the same point
        if last is not None and max(abs(a - b) for a, b in zip(end, last)) < 0.003:
            continue
        out.append((call, args))
        last = end
    return out


def project_motion(program: Program) -> list[tuple]:
    out = []
    for rec in canon_records(program):
        a = rec["args"]
        if rec["call"] == "arc_feed":
            out.append(("arc_feed", (a[0], a[1], a[2], a[3], float(a[4]), a[5])))
        else:
            out.append((rec["call"], tuple(a[:3])))
    return out
