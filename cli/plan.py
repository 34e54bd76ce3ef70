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
import sys
import time
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from planner.errors import PlannerError, ProgramError
from planner.files import write_output, write_output_via_path
from planner.machine import INTERPOLATIONS, PLANNER_MODES, MachineSpec, load_machine
from planner.meter import path_vaj
from planner.plan import LimitReport

__all__ = ["build_machine", "main"]

PAPER_V, PAPER_A, PAPER_J, PAPER_TS = 30.0, 1000.0, 10_000.0, 0.001
# A program that runs longer than this is almost always a mistake (a feed of 0.0001, a circle
# of radius 1e6); interpolating it blindly would take hours and gigabytes for nothing.
DEFAULT_MAX_CYCLE_H = 24.0


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
    p.add_argument("--config", help="machine configuration TOML")
    p.add_argument("--tools", help="tool table in LinuxCNC's .tbl format (T1 P1 Z12.5 D6 ;comment); "
                                   "without it every tool number is accepted with zero offsets")
    p.add_argument("--tool", type=int, default=0, help="the tool in the spindle when the program starts")
    p.add_argument("--samples", help="write t, q, axes, s, line to this NPZ file")
    p.add_argument("--csv", help="write the samples to this CSV file")
    p.add_argument("--plot", help="write a velocity/acceleration/jerk PNG (paper Fig. 14)")
    p.add_argument("--canon", help="write the moves as LinuxCNC canonical calls (JSONL)")
    p.add_argument("--json", action="store_true", help="print a JSON report on stdout")
    p.add_argument("--max-cycle-h", type=float, default=DEFAULT_MAX_CYCLE_H,
                   help=f"refuse to interpolate a program whose cycle time exceeds this many hours "
                        f"(default {DEFAULT_MAX_CYCLE_H:g}); its cycle time is reported instead")
    return p


def build_machine(config: str | None, vmax: float | None, amax: float | None, jmax: float | None,
                  ts: float | None) -> MachineSpec:
    """The machine of the command line (see the module docstring)."""
    for name, value in (("--vmax", vmax), ("--amax", amax), ("--jmax", jmax), ("--ts", ts)):
        if value is not None and not (np.isfinite(value) and value > 0):
            raise PlannerError(f"{name} must be a positive number, got {value}")
    if config:
        machine = load_machine(config)
        changes = {k: v for k, v in (("v_max_mm_s", vmax), ("a_max_mm_s2", amax),
                                     ("j_max_mm_s3", jmax)) if v is not None}
        if changes:
            machine = machine.with_limits(**changes)
        if ts is not None:
            machine = machine.with_planner(ts_s=ts)
        return machine
    v = PAPER_V if vmax is None else vmax
    a = PAPER_A if amax is None else amax
    j = PAPER_J if jmax is None else jmax
    base = MachineSpec.default()
    axes = tuple(replace(ax, v_max=v, a_max=a, j_max=j) for ax in base.axes)
    machine = replace(base, axes=axes).with_limits(v_max_mm_s=v, a_max_mm_s2=a, j_max_mm_s3=j,
                                                   rapid_mm_s=v)
    return machine.with_planner(ts_s=PAPER_TS if ts is None else ts)


def _write_npz(path: str, chunk, axes) -> None:
    write_output(path, lambda fh: np.savez(fh, t=chunk.t, q=chunk.q, axes=np.array(axes), s=chunk.s,
                                           line=chunk.line))


def _write_csv(path: str, plan, axes) -> None:
    def w(fh):
        fh.write((",".join(["t", *axes, "s", "line"]) + "\n").encode("utf-8"))
        d = len(axes)
        for c in plan.iter_chunks():
            block = np.column_stack([c.t, c.q, c.s, c.line])
            np.savetxt(fh, block, fmt=["%.6f"] + ["%.9f"] * d + ["%.9f", "%d"], delimiter=",")
    write_output(path, w)


def _plot(path: str, plan, chunk, title: str) -> None:
    from cli import vaj_png  # Qt starts only when a plot is asked for
    v, a, j = path_vaj(chunk.s, plan.ts_s)
    lim = plan.machine.limits

    def w(tmp):
        vaj_png.export_vaj_png(tmp, chunk.t, v, a, j, title=title,
                                limits=(lim.v_max_mm_s, lim.a_max_mm_s2, lim.j_max_mm_s3))
    write_output_via_path(path, w)


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


def _summarise(program, machine: MachineSpec, args) -> _Summary:
    """Plan segment by segment for the cycle time; with --json, plan again and interpolate and
    measure segment by segment (the cycle time comes first: a program of days is refused
    before any sample is made)."""
    from planner.interpolate import first_sample_at
    from planner.plan import plan_segments, report_segments, resolve_settings

    mode, interpolation = resolve_settings(machine, args.mode, args.interp)
    ts = machine.planner.ts_s
    started = time.perf_counter()
    cycle = 0.0
    for seg in plan_segments(program, machine, mode, interpolation):
        cycle = seg.t_end
    n_samples = first_sample_at(cycle, ts) + 1 if len(program.moves) else 1
    out = _Summary(mode, interpolation, ts, cycle, n_samples, time.perf_counter() - started)
    if not args.json or not cycle <= args.max_cycle_h * 3600.0:
        return out

    def keep(seg) -> None:
        tab, prof = seg.table, seg.profiles
        out.moves.append((tab.line, tab.kind, tab.length, prof.vs, prof.ve, prof.vp, seg.t0,
                          seg.t0 + prof.duration))

    started = time.perf_counter()
    out.report = report_segments(program, machine, interpolation,
                                 plan_segments(program, machine, mode, interpolation), on_segment=keep)
    out.interp_s = time.perf_counter() - started
    return out


def _move_list_json(moves: list[tuple[np.ndarray, ...]]):
    """The JSON text of the move list, piece by piece (a few thousand moves each)."""
    from planner.program import MoveKind

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
    from planner.blend import blend_report

    if not args.json:
        print(f"{program.name}: {len(program.moves)} moves, cycle time {summary.cycle_time_s:.3f} s, "
              f"{summary.n_samples} samples, plan {summary.plan_s * 1e3:.1f} ms")
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
        # how far the path leaves the programmed one: only corner blends do (G64 P)
        "blends": blends.blends,
        "path_deviation_mm": blends.max_corner_deviation_mm,
        "path_deviation_line": blends.line,
        "ok": report.ok,
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
    from planner.blend import blend_program
    from planner.canon import write_canon
    from planner.interpreter import parse_file
    from planner.plan import plan_program
    from planner.softlimits import check_program

    # --canon alone needs no planning: comparing with LinuxCNC's canonical calls runs it on every file.
    want_plan = bool(args.json or args.samples or args.csv or args.plot or not args.canon)
    # the cycle time and the limit report need no whole plan in memory: it is planned and
    # measured segment by segment (memory bounded by a segment); samples written out still
    # take the whole plan
    streamed = not (args.samples or args.csv or args.plot)
    plan = None
    summary: _Summary | None = None
    if not (math.isfinite(args.max_cycle_h) and args.max_cycle_h > 0):
        print(f"cnc-plan: error: --max-cycle-h must be a positive number of hours, got {args.max_cycle_h}",
              file=sys.stderr)
        return 2
    try:
        machine = build_machine(args.config, args.vmax, args.amax, args.jmax, args.ts)
        started = time.perf_counter()
        tools = None
        if args.tools:
            from planner.tools import read_tbl

            tools = read_tbl(args.tools)
        program = parse_file(args.program, machine, tools=tools, tool_in_spindle=args.tool)
        parse_s = time.perf_counter() - started
        if args.config:
            # the machine's travel, checked on the whole path as the controller does
            over = check_program(program, machine)
            if over:
                for v in over:
                    print(f"{args.program}:{v.line}: error: {str(v).split(': ', 1)[1]}", file=sys.stderr)
                return 2
        programmed = program  # --canon writes the programmed path, as LinuxCNC's canon does
        if want_plan and (args.mode or machine.planner.mode) == "lookahead":
            # G64 P: sharp line corners become clothoid blends within the tolerance (the paper's
            # mode keeps the path as programmed, so its figures can still be reproduced)
            program = blend_program(program, machine)
        if want_plan and streamed:
            summary = _summarise(program, machine, args)
        elif want_plan:
            plan = plan_program(program, machine, mode=args.mode, interpolation=args.interp)
    except ProgramError as exc:
        print(str(exc), file=sys.stderr)
        return 2
    except PlannerError as exc:
        print(f"{args.program}: error: {exc}", file=sys.stderr)
        return 2

    cycle_time_s = plan.cycle_time_s if plan is not None else summary.cycle_time_s if summary else None
    if cycle_time_s is not None and not cycle_time_s <= args.max_cycle_h * 3600.0:
        print(f"{args.program}: error: the cycle time is {cycle_time_s / 3600.0:.1f} h, more than "
              f"--max-cycle-h {args.max_cycle_h:g}: not interpolated (a feed too low or a move too long?)",
              file=sys.stderr)
        if args.json:
            json.dump({"program": str(args.program), "cycle_time_s": cycle_time_s, "ok": False,
                       "refused": f"cycle time over {args.max_cycle_h:g} h"}, sys.stdout)
            sys.stdout.write("\n")
        return 2
    if summary is not None:
        if args.canon:
            try:
                write_canon(programmed, args.canon)
            except OSError as exc:
                print(f"cnc-plan: cannot write: {exc}", file=sys.stderr)
                return 1
        return _print_summary(args, program, parse_s, summary)

    axes = list(program.axes)
    need_samples = bool(args.samples or args.plot)
    interp_s = 0.0
    n_samples = plan.n_samples if plan is not None else 0
    collected = None
    if plan is not None and (need_samples or args.json):
        from planner.interpolate import SampleChunk

        started = time.perf_counter()
        chunks = []
        n_samples = 0
        for c in plan.iter_chunks():
            n_samples += len(c)
            if need_samples:
                chunks.append(c)
        interp_s = time.perf_counter() - started
        collected = SampleChunk.concat(chunks, len(axes)) if need_samples else None
    try:
        if args.canon:
            write_canon(programmed, args.canon)
        if args.samples:
            _write_npz(args.samples, collected, axes)
        if args.csv:
            _write_csv(args.csv, plan, axes)
        if args.plot and plan is not None:
            _plot(args.plot, plan, collected, f"{Path(args.program).name}: {plan.mode}, {plan.interpolation}")
    except OSError as exc:
        print(f"cnc-plan: cannot write: {exc}", file=sys.stderr)
        return 1
    if plan is None:
        return 0

    seg, prof = plan.segment, plan.segment.profiles
    whole = _Summary(plan.mode, plan.interpolation, plan.ts_s, plan.cycle_time_s, n_samples, plan.plan_s,
                     interp_s, plan.limit_report() if args.json else None,
                     [(seg.table.line, seg.table.kind, seg.table.length, prof.vs, prof.ve, prof.vp, seg.t0,
                       seg.t0 + prof.duration)])
    return _print_summary(args, program, parse_s, whole)

if __name__ == "__main__":
    sys.exit(main())
