"""``cnc-plan``: plan a G-code program and report, export or plot its set-points.

    cnc-plan PROGRAM [--vmax 30] [--amax 1000] [--jmax 10000] [--ts 0.001]
             [--mode lookahead|paper] [--interp exact|taylor|classic] [--config MACHINE.toml]
             [--samples OUT.npz] [--csv OUT.csv] [--plot OUT.png] [--canon OUT.jsonl] [--json]

Units mm, s (F in the program in mm/min). Without --config the machine is a 3-axis XYZ mill
whose per-axis limits equal the path limits; with --config the file's axes and limits apply
and --vmax/--amax/--jmax/--ts, when given, replace its path limits and sample period.
A bad program: exit status 2, the errors on stderr, nothing written.

--plot draws with pyqtgraph on an offscreen Qt scene (``cli.vaj_png``); the planner itself
never imports Qt.
"""

from __future__ import annotations

import argparse
import json
import math
import shutil
import sys
import tempfile
import time
import zipfile
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from ethercat.drive_setup import drive_table_problem
from planner.core.command import run_command
from planner.core.errors import PlannerError, ProgramError
from planner.core.files import OutputClash, check_outputs, write_output, write_output_via_path
from planner.core.machine import INTERPOLATIONS, PLANNER_MODES, MachineSpec, load_machine
from planner.core.rules import drive_tables
from planner.core.schema import table_keys
from planner.motion.meter import path_vaj
from planner.motion.plan import LimitReport
from resources import SUBROUTINES

__all__ = ["build_machine", "command", "main"]

PAPER_V, PAPER_A, PAPER_J, PAPER_TS = 30.0, 1000.0, 10_000.0, 0.001
LIMIT_RANGE = {key.name: (float(key.lo), float(key.hi)) for key in table_keys("limits")
               if key.lo is not None and key.hi is not None}
TS_RANGE = next((float(k.lo), float(k.hi)) for k in table_keys("planner") if k.name == "ts_s"
                and k.lo is not None and k.hi is not None)
# A program that runs longer than this is almost always a mistake (a feed of 0.0001, a circle
# of radius 1e6); interpolating it blindly would take hours and gigabytes for nothing.
DEFAULT_MAX_CYCLE_H = 24.0
# A program whose moves take this long on average, over an hour in all, is out of scale with
# its length (one arc of 15.7 h at F1): its cycle time is told at once and its samples (56
# million for that arc, a minute of work) are made only with --interpolate-long.
LONG_MOVE_S = 600.0
LONG_CYCLE_S = 3600.0


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="cnc-plan", description="Plan a G-code program: jerk-limited "
                                "profiles, joint speeds and set-points every Ts.")
    p.add_argument("program", help="G-code file")
    p.add_argument("--vmax", type=float, default=None, help="path speed limit, mm/s (default 30)")
    p.add_argument("--amax", type=float, default=None, help="path acceleration limit, mm/s^2 (default 1000)")
    p.add_argument("--jmax", type=float, default=None, help="path jerk limit, mm/s^3 (default 10000)")
    p.add_argument("--ts", type=float, default=None, help="sample period, s (default 0.001)")
    p.add_argument("--mode", choices=PLANNER_MODES, default=None, help="joint speeds (default lookahead)")
    p.add_argument("--interp", choices=INTERPOLATIONS, default=None, help="interpolation (default exact)")
    p.add_argument("--block-delete", action="store_true",
                   help="skip lines starting with '/' (the block delete switch on; off by default, as in "
                        "LinuxCNC)")
    p.add_argument("--config", help="machine configuration TOML")
    p.add_argument("--tools", help="tool table in LinuxCNC's .tbl format (T1 P1 Z12.5 D6 ;comment); "
                                   "without it every tool number is accepted with zero offsets")
    p.add_argument("--tool", type=int, default=0, help="the tool in the spindle when the program starts")
    p.add_argument("--samples", help="write t, q, axes, s, line to this NPZ file")
    p.add_argument("--csv", help="write the samples to this CSV file")
    p.add_argument("--plot", help="write a velocity/acceleration/jerk PNG (paper Fig. 14)")
    p.add_argument("--canon", help="write the moves as LinuxCNC canonical calls (JSONL)")
    p.add_argument("--json", action="store_true", help="print a JSON report on stdout")
    p.add_argument("--interpolate-long", action="store_true",
                   help="interpolate and measure a program whose moves take over 10 minutes each on average "
                        "(by default its cycle time is told without samples)")
    p.add_argument("--mkdir", action="store_true", help="create the folders of the output files when missing")
    p.add_argument("--max-cycle-h", type=float, default=DEFAULT_MAX_CYCLE_H,
                   help=f"refuse to interpolate a program whose cycle time exceeds this many hours "
                        f"(default {DEFAULT_MAX_CYCLE_H:g}); its cycle time is reported instead")
    return p


def build_machine(config: str | None, vmax: float | None, amax: float | None, jmax: float | None,
                  ts: float | None) -> MachineSpec:
    """The machine of the command line (see the module docstring)."""
    # the configuration's own bounds ([limits] and [planner] ts_s): beyond them planning has no
    # meaning left (a cycle of 1e47 s) and would not end
    for name, value, (lo, hi) in (("--vmax", vmax, LIMIT_RANGE["v_max_mm_s"]),
                                  ("--amax", amax, LIMIT_RANGE["a_max_mm_s2"]),
                                  ("--jmax", jmax, LIMIT_RANGE["j_max_mm_s3"]), ("--ts", ts, TS_RANGE)):
        if value is not None and not (np.isfinite(value) and value > 0):
            raise PlannerError(f"{name} must be a positive number, got {value}")
        if value is not None and not lo <= value <= hi:
            raise PlannerError(f"{name} {value:g} is out of range ({lo:g} to {hi:g}, as in the machine "
                               "configuration)")
    if config:
        machine = load_machine(config, drive_tables(drive_table_problem))
        changes = {k: v for k, v in (("v_max_mm_s", vmax), ("a_max_mm_s2", amax),
                                     ("j_max_mm_s3", jmax)) if v is not None}
        if changes:
            machine = machine.with_limits(**changes)
        if ts is not None:
            machine = machine.with_planner(ts_s=ts)
        return replace(machine, shipped_subroutine_dir=str(SUBROUTINES))
    v = PAPER_V if vmax is None else vmax
    a = PAPER_A if amax is None else amax
    j = PAPER_J if jmax is None else jmax
    base = MachineSpec.default()
    axes = tuple(replace(ax, v_max=v, a_max=a, j_max=j) for ax in base.axes)
    machine = replace(base, axes=axes).with_limits(v_max_mm_s=v, a_max_mm_s2=a, j_max_mm_s3=j,
                                                   rapid_mm_s=v)
    # the shipped subroutines (probing, tool measurement) are found as the panel finds them
    return replace(machine.with_planner(ts_s=PAPER_TS if ts is None else ts),
                   shipped_subroutine_dir=str(SUBROUTINES))


class _Sinks:
    """The sample files (--samples, --csv, --plot), filled chunk by chunk as the samples are
    made, in a scratch folder (the NPZ's arrays as memory-mapped .npy files); ``deliver`` puts
    each where it was asked for. Memory: a chunk, and for --plot the path length of every
    sample (8 bytes each)."""

    def __init__(self, args, axes: list[str], n_samples: int, scratch: Path) -> None:
        self.args = args
        self.axes = axes
        self.n = n_samples
        self.k = 0
        self.csv = None
        if args.csv:
            self.csv = open(scratch / "samples.csv", "wb")  # noqa: SIM115  (closed in deliver)
            self.csv.write((",".join(["t", *axes, "s", "line"]) + "\n").encode("utf-8"))
        self.npz: dict[str, np.ndarray] = {}
        if args.samples:
            open_memmap = np.lib.format.open_memmap
            d = len(axes)
            self.npz = {"t": open_memmap(scratch / "t.npy", "w+", float, (n_samples,)),
                        "q": open_memmap(scratch / "q.npy", "w+", float, (n_samples, d)),
                        "s": open_memmap(scratch / "s.npy", "w+", float, (n_samples,)),
                        "line": open_memmap(scratch / "line.npy", "w+", np.int32, (n_samples,))}
        self.plot_s = np.empty(n_samples) if args.plot else None
        self.scratch = scratch

    @property
    def wanted(self) -> bool:
        return bool(self.csv or self.npz or self.plot_s is not None)

    def add(self, c) -> None:
        m = len(c)
        if self.k + m > self.n:
            raise PlannerError(f"more samples than planned ({self.k + m} > {self.n}): an error of this "
                               "control, please report the program")
        sl = slice(self.k, self.k + m)
        if self.csv is not None:
            block = np.column_stack([c.t, c.q, c.s, c.line])
            np.savetxt(self.csv, block, fmt=["%.6f"] + ["%.9f"] * len(self.axes) + ["%.9f", "%d"],
                       delimiter=",")
        if self.npz:
            for name in ("t", "q", "s", "line"):
                self.npz[name][sl] = getattr(c, name)
        if self.plot_s is not None:
            self.plot_s[sl] = c.s
        self.k += m

    def deliver(self, machine: MachineSpec, ts: float, title: str) -> None:
        if self.k != self.n:
            raise PlannerError(f"{self.k} samples made, {self.n} planned: an error of this control, "
                               "please report the program")
        if self.csv is not None:
            self.csv.close()
            with open(self.scratch / "samples.csv", "rb") as src:
                write_output(self.args.csv, lambda fh: shutil.copyfileobj(src, fh))
        if self.npz:
            for arr in self.npz.values():
                arr.flush()  # type: ignore[attr-defined]
            self.npz = {}
            # the zip is made in the scratch folder (zipfile seeks back to write its headers,
            # which a pipe or /dev/null cannot), then goes where it was asked for
            with open(self.scratch / "samples.npz", "wb") as zfh:
                self._write_npz(zfh)
            with open(self.scratch / "samples.npz", "rb") as src:
                write_output(self.args.samples, lambda fh: shutil.copyfileobj(src, fh))
        if self.plot_s is not None:
            from cli import vaj_png  # Qt starts only when a plot is asked for

            v, a, j = path_vaj(self.plot_s, ts)
            t = np.arange(self.n) * ts
            lim = machine.limits

            def w(tmp: str) -> None:
                vaj_png.export_vaj_png(tmp, t, v, a, j, title=title,
                                        limits=(lim.v_max_mm_s, lim.a_max_mm_s2, lim.j_max_mm_s3))
            write_output_via_path(self.args.plot, w)

    def _write_npz(self, fh) -> None:
        """np.savez's layout (a zip of .npy files, stored), from the files on disk."""
        with zipfile.ZipFile(fh, "w", zipfile.ZIP_STORED, allowZip64=True) as zf:
            for name in ("t", "q"):
                zf.write(self.scratch / f"{name}.npy", arcname=f"{name}.npy")
            with zf.open("axes.npy", "w") as entry:
                np.lib.format.write_array(entry, np.array(self.axes))
            for name in ("s", "line"):
                zf.write(self.scratch / f"{name}.npy", arcname=f"{name}.npy")


@dataclass(eq=False)
class _Summary:
    """A plan as cnc-plan reports it, without the plan: cycle time, and with --json the limit
    report and each move's figures in compact columns."""

    mode: str
    interpolation: str
    ts_s: float
    cycle_time_s: float
    n_samples: int
    plan_s: float
    interp_s: float = 0.0
    report: LimitReport | None = None
    moves: list[tuple[np.ndarray, ...]] = field(default_factory=list)  # per segment: line, kind, ...
    not_sampled: str = ""      # why no sample was made ("": they were, or none was asked for)


def _summarise(program, machine: MachineSpec, args, scratch: Path) -> _Summary:
    """Plan segment by segment for the cycle time; with --json or sample files, plan again and
    interpolate (and measure) segment by segment, the files filled as the samples come (the
    cycle time comes first: a program of days is refused before any sample is made)."""
    from planner.motion.interpolate import first_sample_at
    from planner.motion.plan import plan_segments, report_segments, resolve_settings, stream_program

    mode, interpolation = resolve_settings(machine, args.mode, args.interp)
    ts = machine.planner.ts_s
    started = time.perf_counter()
    cycle = 0.0
    for seg in plan_segments(program, machine, mode, interpolation):
        cycle = seg.t_end
    n_samples = first_sample_at(cycle, ts) + 1 if len(program.moves) else 1
    out = _Summary(mode, interpolation, ts, cycle, n_samples, time.perf_counter() - started)
    if not cycle <= args.max_cycle_h * 3600.0:
        return out
    per_move = cycle / max(len(program.moves), 1)
    asked = args.interpolate_long or args.samples or args.csv or args.plot    # samples wanted by name
    if cycle > LONG_CYCLE_S and per_move > LONG_MOVE_S and not asked:
        out.not_sampled = (f"{len(program.moves)} move(s) take {cycle / 3600.0:.3g} h, "
                           f"{per_move / 60.0:.3g} min a move on average (a feed too low?): not interpolated "
                           f"({out.n_samples:,} samples); --interpolate-long makes and measures them")
        return out
    sinks = _Sinks(args, list(program.axes), n_samples, scratch)
    if not args.json:
        if sinks.wanted:
            started = time.perf_counter()
            for chunk in stream_program(program, machine, mode, interpolation):
                sinks.add(chunk)
            out.interp_s = time.perf_counter() - started
            sinks.deliver(machine, ts, f"{Path(args.program).name}: {mode}, {interpolation}")
        return out

    def keep(seg) -> None:
        tab, prof = seg.table, seg.profiles
        out.moves.append((tab.line, tab.kind, tab.length, prof.vs, prof.ve, prof.vp, seg.t0,
                          seg.t0 + prof.duration))

    started = time.perf_counter()
    out.report = report_segments(program, machine, interpolation,
                                 plan_segments(program, machine, mode, interpolation), on_segment=keep,
                                 on_chunk=sinks.add if sinks.wanted else None)
    out.interp_s = time.perf_counter() - started
    if sinks.wanted:
        sinks.deliver(machine, ts, f"{Path(args.program).name}: {mode}, {interpolation}")
    return out


def _move_list_json(moves: list[tuple[np.ndarray, ...]]):
    """The JSON text of the move list, piece by piece (a few thousand moves each)."""
    from planner.core.program import MoveKind

    kinds = {int(k): k.name.lower() for k in MoveKind}
    first = True
    for cols in moves:
        line, kind, length, vs, ve, vp, t0, t1 = (c.tolist() for c in cols)
        rows = [{"line": r[0], "kind": kinds[r[1]], "length": r[2], "vs": r[3], "ve": r[4], "vpeak": r[5],
                 "t0": r[6], "t1": r[7]} for r in zip(line, kind, length, vs, ve, vp, t0, t1)]
        if rows:
            text = json.dumps(rows)[1:-1]
            yield text if first else ", " + text
            first = False


def _print_summary(args, program, parse_s: float, summary: _Summary) -> int:
    from planner.geometry.blend import blend_report

    # G38.x: what follows a probe depends on where it touches; planned here as running to the
    # programmed end point, #5070 = 0 (the run reads the rest again with the machine's result)
    probes = [{"line": p.line, "code": p.name, "assumed": not p.known} for p in program.probes]
    synchronised = [{"line": s.line, "code": s.code} for s in program.synchronised]
    analog = [{"line": a.line, "code": a.code, "index": a.index, "value": a.value}
              for a in program.analog_outputs]
    if not args.json:
        print(f"{program.name}: {len(program.moves)} moves, cycle time {summary.cycle_time_s:.3f} s, "
              f"{summary.n_samples} samples, plan {summary.plan_s * 1e3:.1f} ms")
        if probes:
            lines = ", ".join(str(p["line"]) for p in probes)
            print(f"{program.name}: probing (G38.x) at line(s) {lines}: planned as running to the "
                  "programmed end point (#5070 = 0, as LinuxCNC's preview); a run reads what follows "
                  "again with the machine's result")
        if synchronised:
            lines = ", ".join(f"{s['code']} at {s['line']}" for s in synchronised)
            print(f"{program.name}: spindle-synchronised motion ({lines}): planned at the pitch times "
                  "the programmed speed; the machine refuses to run it (its spindle has no encoder)")
        if analog:
            lines = ", ".join(f"{a['code']} at {a['line']}" for a in analog)
            print(f"{program.name}: analog outputs ({lines}): read; the machine refuses to run them (its "
                  "drives' outputs are digital)")
        return 0
    report = summary.report
    assert report is not None
    blends = blend_report(program)
    out = {
        "program": str(args.program),
        "lines": int(program.line_count),
        "moves": len(program.moves),
        "mode": summary.mode,
        "interpolation": summary.interpolation,
        "ts_s": summary.ts_s,
        "cycle_time_s": summary.cycle_time_s,
        "samples": report.samples,
        "parse_s": parse_s,
        "plan_s": summary.plan_s,
        "interp_s": summary.interp_s,
        "tangential": report.tangential,
        "tangential_samples": report.tangential_samples,
        "axes": report.axes,
        "contour_error_mm": report.contour_error_mm,
        "end_error_mm": report.end_error_mm,
        "violations": report.violations,
        "joint_jerk": report.joint_jerk,
        # joints crossed with a velocity step beyond the jerk limit ([planner]
        # corner_velocity_step_mm_s): how many, the largest step, their lines
        "corner_steps": report.corner_steps,
        # how far the path leaves the programmed one: only corner blends do (G64 P)
        "blends": blends.blends,
        "path_deviation_mm": blends.max_corner_deviation_mm,
        "path_deviation_line": blends.line,
        "ok": report.ok,
        "probes": probes,
        "synchronised": synchronised,
        "analog_outputs": analog,
    }
    # one string through the C encoder per piece: json.dump writes piece by piece in Python
    # (1.7 s for the 35,000 moves of the sphere finishing program against 0.1 s); the move
    # list goes out a segment at a time, never as one string
    head = json.dumps(out)
    sys.stdout.write(head[:-1] + ', "move_list": [')
    for piece in _move_list_json(summary.moves):
        sys.stdout.write(piece)
    sys.stdout.write("]}\n")
    return 0


def main(argv: list[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    from planner.gcode.canon import write_canon
    from planner.pipeline import Abilities, SoftLimitError, load

    # --canon alone needs no planning: comparing with LinuxCNC's canonical calls runs it on every file.
    want_plan = bool(args.json or args.samples or args.csv or args.plot or not args.canon)
    summary: _Summary | None = None
    if not (math.isfinite(args.max_cycle_h) and args.max_cycle_h > 0):
        print(f"cnc-plan: error: --max-cycle-h must be a positive number of hours, got {args.max_cycle_h}",
              file=sys.stderr)
        return 2
    outputs = {"--samples": args.samples, "--csv": args.csv, "--plot": args.plot, "--canon": args.canon}
    if args.json:
        outputs["--json"] = "-"
    inputs = {"the program": args.program, "--config": args.config, "--tools": args.tools}
    try:
        check_outputs(outputs, inputs, make_dirs=args.mkdir)
    except OutputClash as exc:
        print(f"cnc-plan: error: {exc}", file=sys.stderr)
        return 2
    with tempfile.TemporaryDirectory(prefix="cnc-plan-") as scratch:
        try:
            machine = build_machine(args.config, args.vmax, args.amax, args.jmax, args.ts)
            try:      # a subroutine file is an input too (the machine names their folders)
                check_outputs(outputs, inputs, input_dirs=machine.subroutine_paths())
            except OutputClash as exc:
                print(f"cnc-plan: error: {exc}", file=sys.stderr)
                return 2
            started = time.perf_counter()
            tools = None
            if args.tools:
                from planner.core.tools import read_tbl

                tools = read_tbl(args.tools)
            # the one load pipeline, as the controller loads: read; blend in look-ahead mode (G64 P:
            # sharp line corners become clothoid blends within the tolerance; the paper's mode keeps
            # the path as programmed, so its figures can still be reproduced); the machine's travel
            # on the path that runs, with --config; then planned (and interpolated and measured)
            # segment by segment: memory bounded by a segment, whatever the length of the program.
            # A planning tool refuses nothing a machine might run (Abilities()).
            timings: dict[str, float] = {}

            def plan(program):  # noqa: ANN001, ANN202 - planner.core.program.Program -> _Summary | None
                timings["parse_s"] = time.perf_counter() - started
                return _summarise(program, machine, args, Path(scratch)) if want_plan else None

            loaded = load(Path(args.program), args.program, machine, plan, tools=tools,
                          tool_in_spindle=args.tool, block_delete=args.block_delete, abilities=Abilities(),
                          blend=want_plan and (args.mode or machine.planner.mode) == "lookahead",
                          check_travel=bool(args.config), require_motion=want_plan)
            program, programmed, summary = loaded.program, loaded.programmed, loaded.plan
            parse_s = timings["parse_s"]
        except SoftLimitError as exc:
            for v in exc.violations:
                print(f"{args.program}:{v.line}: error: {str(v).split(': ', 1)[1]}", file=sys.stderr)
            return 2
        except ProgramError as exc:
            print(str(exc), file=sys.stderr)
            return 2
        except PlannerError as exc:
            print(f"{args.program}: error: {exc}", file=sys.stderr)
            return 2
        except OSError as exc:
            print(f"cnc-plan: cannot write: {exc}", file=sys.stderr)
            return 1

    over = summary is not None and not summary.cycle_time_s <= args.max_cycle_h * 3600.0
    if over and summary is not None and not (args.samples or args.csv or args.plot):
        # a long program (a mould's finish) is no error: its cycle time is the answer
        summary.not_sampled = (f"the cycle time is {summary.cycle_time_s / 3600.0:.1f} h, more than "
                               f"--max-cycle-h {args.max_cycle_h:g}: not interpolated")
    elif over and summary is not None:
        print(f"{args.program}: error: the cycle time is {summary.cycle_time_s / 3600.0:.1f} h, more than "
              f"--max-cycle-h {args.max_cycle_h:g}: not interpolated, so the samples asked for are not made "
              "(a feed too low or a move too long? --max-cycle-h raises the bound)", file=sys.stderr)
        if args.json:
            json.dump({"program": str(args.program), "cycle_time_s": summary.cycle_time_s, "ok": False,
                       "refused": f"cycle time over {args.max_cycle_h:g} h"}, sys.stdout)
            sys.stdout.write("\n")
        return 2
    if summary is not None and summary.not_sampled:
        print(f"{args.program}: {summary.not_sampled}", file=sys.stderr)
        if args.json:
            json.dump({"program": str(args.program), "moves": len(program.moves),
                       "cycle_time_s": summary.cycle_time_s, "ok": True, "sampled": False,
                       "note": summary.not_sampled}, sys.stdout)
            sys.stdout.write("\n")
        else:
            print(f"{program.name}: {len(program.moves)} moves, cycle time {summary.cycle_time_s:.3f} s")
        if not args.canon:
            return 0
    if args.canon:
        try:
            write_canon(programmed, args.canon)
        except OSError as exc:
            print(f"cnc-plan: cannot write: {exc}", file=sys.stderr)
            return 1
    if summary is None or summary.not_sampled:
        return 0
    return _print_summary(args, program, parse_s, summary)

def command() -> int:
    """``cnc-plan`` as installed: ``main`` with its last word said in one line."""
    return run_command("cnc-plan", main)


if __name__ == "__main__":
    sys.exit(command())
