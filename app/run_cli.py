"""``cnc-run PROGRAM [--config FILE] [--sim] [--json]``: run a program headless through the
machine controller and the EtherCAT worker on simulated drives, in real time.

Prints progress (line, percent, remaining time) on stderr about once a second, then the
measured and estimated cycle time, the limit report of the set-points sent to the drives
(velocity, acceleration, jerk as ratios to the machine's limits) and the tracking RMSE/MSE
per axis (paper Eq. 18, Table 4). ``--json``: one JSON object on stdout instead.
Exit status: 0 completed, 1 run aborted (alarm), 2 bad program or configuration.

Program pauses (M00, M01 with --optional-stop, M06) are continued automatically, with a note,
unless ``--script OPS.jsonl`` gives the operator's actions (``app.machine.scenario``): then the
script does what the operator would (stop, run from line, tool changed, ...), the run ends when
every action was tried and the machine stands, and the JSON lists the actions, the prompts
shown, the alarms and the final state. ``--trace OUT.npz`` records every set-point sent (t,
reference, actual in machine coordinates, axes, program line, commanded spindle rpm signed by
direction). ``--worker manual`` runs simulated time as fast as the computer allows.
"""

from __future__ import annotations

import argparse
import json
import signal
import sys
import tempfile
import threading
import time
from dataclasses import replace
from pathlib import Path
from typing import Any

__all__ = ["command", "main"]


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="cnc-run", description=__doc__.split("\n\n")[0])
    p.add_argument("program", nargs="?", help="G-code file")
    p.add_argument("--status", action="store_true",
                   help="print the persisted machine state of --state-dir (position, homed axes, whether the "
                        "last run ended cleanly) and run nothing")
    p.add_argument("--config", help="machine configuration TOML (default: the shipped 3-axis XYZ mill)")
    p.add_argument("--sim", action="store_true", help="simulated drives whatever the configuration says")
    p.add_argument("--hardware", action="store_true",
                   help="run on the configuration's EtherCAT drives (commissioning, at the machine: "
                        "the axes move)")
    p.add_argument("--json", action="store_true", help="print one JSON object on stdout")
    p.add_argument("--feed-override", type=float, default=100.0, help="feed override in %% (0-200)")
    p.add_argument("--optional-stop", action="store_true", help="honour M01")
    p.add_argument("--block-delete", action="store_true", help="skip lines starting with '/'")
    p.add_argument("--state-dir", help="state directory (default: a temporary one)")
    p.add_argument("--worker", choices=("process", "thread", "manual"), default="process",
                   help="worker mode (default: its own real-time process)")
    p.add_argument("--tools", help="tool table (LinuxCNC .tbl) to put in the state folder before the run")
    p.add_argument("--tool", type=int, default=None, help="the tool in the spindle at the start")
    p.add_argument("--trace", help="write the NPZ trace of every set-point sent to this file")
    p.add_argument("--mkdir", action="store_true", help="create the folder of the --trace file when missing")
    p.add_argument("--script", help="operator actions, one JSON object per line: "
                                    '{"at_line": N, "op": "stop"} or {"after_s": T, "op": ...}')
    p.add_argument("--opcua-port", type=int, default=None, metavar="PORT",
                   help="serve the OPC UA model (OPC 40501) on PORT while the program runs, with the "
                        "configured [opcua] security")
    p.add_argument("--opcua-insecure", action="store_true",
                   help="the OPC UA server with security None and anonymous reading, on 127.0.0.1 only "
                        "(local dashboards and tests)")
    p.add_argument("--max-s", type=float, default=None,
                   help="machine-time limit of a scripted run in s (default: 3 x the estimate + 60)")
    return p


def _status(state_dir: str, as_json: bool) -> int:
    """The persisted state of a state folder, read without taking it (no controller started)."""
    from app.machine.infra.persist import StateStore

    raw = StateStore(state_dir)._read_json("state.json")
    if not isinstance(raw, dict):
        print(f"cnc-run: no machine state in {state_dir}", file=sys.stderr)
        return 2
    out = {
        "state_dir": str(state_dir), "axes": raw.get("axes"), "position": raw.get("raw_position"),
        "home_offset": raw.get("home_offset"), "homed": dict(zip(raw.get("axes", []), raw.get("homed", []))),
        "active_offset": raw.get("active_offset"), "unclean_shutdown": bool(raw.get("running", False)),
        "saved": raw.get("saved"),
    }
    if as_json:
        print(json.dumps(out, indent=1))
    else:
        for k, v in out.items():
            print(f"{k}: {v}")
    return 0


def main(argv: list[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    if args.status:
        if not args.state_dir:
            print("cnc-run: --status needs --state-dir", file=sys.stderr)
            return 2
        return _status(args.state_dir, args.json)
    if not args.program:
        print("cnc-run: a G-code program is needed (or --status)", file=sys.stderr)
        return 2
    # SIGTERM and Ctrl+C are caught from the start: one that comes while the run is set up ends
    # it before the program starts, one that comes while it runs stops it along the path; both
    # end as a run ends, the worker and its shared memory given back
    stop_requested: list[int] = []
    previous = _catch_stop_signals(stop_requested)
    try:
        return _run(args, stop_requested)
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)


def _catch_stop_signals(requested: list[int]) -> dict[int, Any]:
    """Record SIGTERM and SIGINT in ``requested`` (in the main thread; elsewhere signals cannot
    be caught); the handlers they had."""
    if threading.current_thread() is not threading.main_thread():
        return {}

    def on_signal(signum: int, _frame: object) -> None:
        requested.append(signum)

    previous: dict[int, Any] = {}
    for sig in (signal.SIGTERM, signal.SIGINT):
        previous[sig] = signal.signal(sig, on_signal)
    return previous


def _run(args: argparse.Namespace, stop_requested: list[int]) -> int:
    from planner.core.files import OutputClash, check_outputs

    outputs = {"--trace": args.trace, "--json": "-" if args.json else None}
    inputs = {"the program": args.program, "--config": args.config, "--tools": args.tools,
              "--script": args.script}
    try:
        check_outputs(outputs, inputs, make_dirs=args.mkdir)
    except OutputClash as exc:
        print(f"cnc-run: {exc}", file=sys.stderr)
        return 2
    import os

    os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
    from PySide6.QtCore import QCoreApplication, QEventLoop, QTimer

    from app.machine.config import MachineConfig, load_config
    from app.machine.controller import MachineController
    from app.machine.errors import ConfigError, MachineError, StateFolderBusy
    from app.machine.model import MachineState
    from app.machine.program.scenario import Recorder, ScenarioRunner, read_script
    from opcua_server.settings import OpcUaOverride

    try:
        ops = read_script(args.script) if args.script else None
    except MachineError as exc:
        print(f"cnc-run: {exc}", file=sys.stderr)
        return 2
    try:
        cfg = load_config(args.config) if args.config else MachineConfig.default()
    except ConfigError as exc:
        print(f"cnc-run: {exc}", file=sys.stderr)
        return 2
    if args.sim:
        cfg = replace(cfg, bus=replace(cfg.bus, kind="sim", adapter=""))
    if cfg.bus.kind != "sim" and not args.hardware:
        print("cnc-run: the configuration drives real hardware; run real machines from the panel, "
              "pass --sim to simulate, or --hardware at the machine to move its axes", file=sys.stderr)
        return 2
    # in-memory configuration: the state directory's machine.toml is never written by a run
    cfg = replace(cfg, path="")
    try:            # a subroutine is an input too: the trace never lands in their folders
        check_outputs(outputs, inputs, input_dirs=cfg.machine.subroutine_paths())
    except OutputClash as exc:
        print(f"cnc-run: {exc}", file=sys.stderr)
        return 2
    if not 0.0 <= args.feed_override <= 200.0:       # nan too
        print(f"cnc-run: --feed-override {args.feed_override:g}: the feed override is 0 to 200 %",
              file=sys.stderr)
        return 2
    try:
        opcua = OpcUaOverride(args.opcua_port, args.opcua_insecure) \
            if args.opcua_port is not None or args.opcua_insecure else None
    except ValueError as exc:
        print(f"cnc-run: {exc}", file=sys.stderr)
        return 2
    app = QCoreApplication.instance() or QCoreApplication([])
    tmp = None
    state_dir = args.state_dir
    if state_dir is None:
        tmp = tempfile.TemporaryDirectory(prefix="cnc-run-")
        state_dir = tmp.name
    try:
        ctl = MachineController(cfg, state_dir=state_dir, worker_mode=args.worker, opcua=opcua)
    except StateFolderBusy as exc:
        print(f"cnc-run: {exc}", file=sys.stderr)
        return 2
    if opcua is not None:
        server = ctl.remote.server
        status = server.wait_ready(30.0) if server is not None else None
        if status is not None and status.running:
            print(f"cnc-run: OPC UA server at {ctl.opcua_settings.describe()}", file=sys.stderr)
        elif status is not None:
            print(f"cnc-run: {status.error}; running without it", file=sys.stderr)
    errors: list[str] = []
    ctl.programErrors.connect(lambda issues: errors.extend(str(i) for i in issues))
    notes: list[str] = []
    ctl.commandRefused.connect(lambda action, reason: notes.append(f"{action} refused: {reason}"))
    try:
        res = ctl.connect_bus()
        if not res:
            print(f"cnc-run: {res.reason}", file=sys.stderr)
            return 2
        ctl.set_machine_zero_here()  # simulated drives: the start position is machine zero
        if args.tools:
            res = ctl.import_tool_table(args.tools)
            if not res:
                print(f"cnc-run: {res.reason}", file=sys.stderr)
                return 2
        if args.tool is not None:
            res = ctl.set_tool_in_spindle(args.tool)
            if not res:
                print(f"cnc-run: {res.reason}", file=sys.stderr)
                return 2
        ctl.set_block_delete(args.block_delete)   # before the load: it decides which lines it has
        res = ctl.load_program(Path(args.program), wait=True)
        if not res:
            for e in errors or [res.reason]:
                print(f"{args.program}: {e}", file=sys.stderr)
            return 2
        info = ctl.program_info
        assert info is not None
        ctl.set_feed_override(args.feed_override)
        ctl.set_optional_stop(args.optional_stop)
        if not args.json:
            print(f"{info.name}: {info.line_count} lines, {info.move_count} moves, "
                  f"estimated cycle time {info.cycle_time_s:.3f} s", file=sys.stderr)
        done: list[Any] = []
        ctl.programFinished.connect(done.append)
        recorder = Recorder(ctl) if (args.trace or ops is not None) else None
        runner = None
        if ops is not None:
            runner = ScenarioRunner(ctl, ops, ctl.machine_time_s)
            max_s = args.max_s if args.max_s is not None else 3.0 * info.cycle_time_s + 60.0
            max_s += runner.last_t
        if stop_requested:
            name = signal.Signals(stop_requested[0]).name
            print(f"cnc-run: stopped by signal {name} before the program started", file=sys.stderr)
            if args.json:
                print(json.dumps({"program": str(args.program), "completed": False, "reason": "signal",
                                  "notes": [f"stopped by signal {name} before the program started"]},
                                 indent=1))
            return 1
        started = time.monotonic()
        res = ctl.cycle_start(wait=True)
        if not res:
            print(f"cnc-run: {res.reason}", file=sys.stderr)
            return 2
        print("cnc-run: running; SIGTERM or Ctrl+C stops it along the path", file=sys.stderr, flush=True)
        last_print = 0.0
        loop = QEventLoop()

        def tick() -> None:
            if args.worker == "manual":
                ctl.advance(0.01 if runner is not None else 0.1)
            else:
                QTimer.singleShot(10 if runner is not None else 50, loop.quit)
                loop.exec()

        stopped_by = ""           # "time limit" or "signal" when cnc-run stopped the run itself

        def stop_run() -> None:
            # along the path, as the operator's Stop: the run ends with its summary (last line,
            # time run, limits measured so far), then the normal end
            ctl.stop()
            end = time.monotonic() + 10.0
            while ctl.state not in (MachineState.IDLE, MachineState.ALARM, MachineState.ESTOP) \
                    and time.monotonic() < end:
                tick()

        while True:
            if stop_requested:
                notes.append(f"stopped by signal {signal.Signals(stop_requested[0]).name}")
                stopped_by = "signal"
                stop_run()
                break
            tick()
            if runner is not None:
                runner.step()
                standing = ctl.state not in (MachineState.RUNNING, MachineState.HOLD, MachineState.HOMING)
                if runner.done and standing:
                    break
                if runner.now() > max_s:
                    left = "; ".join(op.describe() for op in runner.ops) or "none"
                    notes.append(f"time limit of {max_s - runner.start_t:g} s reached; "
                                 f"actions not done: {left}")
                    stopped_by = "time limit"
                    stop_run()
                    break
                continue
            if done:
                break
            if ctl.state is MachineState.HOLD and ctl.activity.value == "program":
                notes.append(f"continued after: {ctl.state_reason}")
                ctl.resume()
            if ctl.state in (MachineState.ALARM, MachineState.ESTOP) and not done:
                break
            now = time.monotonic()
            if not args.json and now - last_print >= 1.0:
                last_print = now
                frac, remaining = ctl.progress
                print(f"  line {ctl.current_line:6d}  {100 * frac:5.1f} %  remaining {remaining:7.2f} s",
                      file=sys.stderr)
        wall = time.monotonic() - started
        summary = done[-1] if done else ctl.last_run
        if summary is not None and summary.completed:
            _settle(ctl, tick)
        snap = ctl.worker.snapshot() if ctl.worker is not None else None
        result = _result(ctl, info, summary, wall, snap, notes)
        if stopped_by:
            result["reason"] = stopped_by
        if runner is not None and recorder is not None:
            result["actions"] = runner.results
            result["prompts"] = recorder.prompts
            result["spindle"] = recorder.spindle
        trace_failed = False
        if args.trace and recorder is not None:
            try:
                recorder.save(args.trace)
                result["trace"] = args.trace
            except OSError as exc:         # a full disk, a folder gone meanwhile: said, the run reported
                trace_failed = True
                why = f"cannot write the trace {args.trace}: {exc.strerror or exc}"
                result["notes"] = [*result.get("notes", []), why]
                print(f"cnc-run: {why}", file=sys.stderr)
        if opcua is not None and ctl.opcua_status is not None and ctl.opcua_status.running:
            ctl.status.publish()          # the run's end, served a moment for the clients to read
            end = time.monotonic() + OPCUA_LINGER_S
            while time.monotonic() < end:
                tick()
        if args.json:
            print(json.dumps(result, indent=1))
        else:
            _print_text(result)
        if trace_failed:
            return 1
        if runner is not None:      # a script may stop the run on purpose: it is done when it ran
            return 0 if runner.done and all(r["ok"] for r in runner.results) else 1
        return 0 if result["completed"] else 1
    finally:
        ctl.shutdown()
        del app
        if tmp is not None:
            tmp.cleanup()


#: With ``--opcua-port``, the end of the run is served this long before the server closes, so
#: a client reading at 10 Hz or faster sees the program Ended.
OPCUA_LINGER_S = 1.0

#: The run ends with its last set-point, while the drives still follow a few cycles behind (a
#: CSP drive's actual position lags its target; a slave that answers late, by more): the end
#: position is read once every axis is within SETTLE_MM of where the path ended, or after
#: SETTLE_S, as a control reports a block done once its axes are in position.
SETTLE_MM = 0.001
SETTLE_S = 1.0


def _settle(ctl: Any, tick: Any) -> None:
    until = time.monotonic() + SETTLE_S
    while time.monotonic() < until:
        gap = max((abs(a - r) for a, r in zip(ctl.machine_position, ctl.reference_position)), default=0.0)
        if gap <= SETTLE_MM:
            return
        tick()


def _result(ctl: Any, info: Any, summary: Any, wall: float, snap: Any, notes: list[str]) -> dict[str, Any]:
    """The run as JSON: from the controller's status snapshot (positions in both frames, the
    offsets in force, alarms, state) and the run's summary."""
    status = ctl.snapshot()
    axes = list(status.axes)
    frame = status.frame
    out: dict[str, Any] = {
        "program": info.name, "lines": info.line_count, "moves": info.move_count,
        "completed": bool(summary is not None and summary.completed),
        "reason": summary.reason if summary is not None else "no run",
        "cycle_time_s": summary.cycle_time_s if summary is not None else 0.0,
        "estimated_cycle_time_s": info.cycle_time_s, "wall_time_s": wall,
        "last_line": summary.last_line if summary is not None else 0,
        "end_position": list(status.machine_pos), "reference_end_position": list(status.reference_pos),
        "end_work_position": list(status.work_pos),
        "offsets": {"system": frame.system_name, "g5x": list(frame.g5x), "g92": list(frame.g92),
                    "tool": list(frame.tool), "xy_rotation_deg": frame.rotation_deg},
        "limits": summary.limits if summary is not None else {},
        "limits_ok": bool(summary is not None and all(
            v <= 1.0 + 1e-6 for k, v in summary.limits.items() if not k.endswith("_max"))),
        "tracking": {}, "alarms": [f"{a.source}: {a.cause}" for a in status.alarms], "notes": notes,
        "final_state": status.state.value,
        "homing_method": ctl.config.homing.method,
    }
    if ctl.config.homing.method == "set_here":
        from app.machine.session.connection import NO_REFERENCE

        out["notes"] = [*notes, NO_REFERENCE]
    if summary is not None:
        t = summary.tracking
        out["tracking"] = {a: {"rmse": t.rmse[i], "mse": t.mse[i], "max_abs": t.max_abs[i]}
                           for i, a in enumerate(axes) if i < len(t.rmse)}
        out["tracking_samples"] = t.samples
    if snap is not None:
        out["timing"] = snap.timing.as_dict()
    return out


def _print_text(r: dict[str, Any]) -> None:
    status = "completed" if r["completed"] else f"NOT completed ({r['reason']})"
    print(f"{r['program']}: {status}")
    print(f"cycle time      {r['cycle_time_s']:.3f} s (estimated {r['estimated_cycle_time_s']:.3f} s, "
          f"wall {r['wall_time_s']:.3f} s)")
    lim = r["limits"]
    if lim:
        print("limits (maximum / limit, set-points sent to the drives):")
        for k in ("tangential_v", "tangential_a", "tangential_j", "axis_v", "axis_a", "axis_j"):
            print(f"  {k:13s} {lim.get(k, 0.0):8.4f}")
        print(f"  within limits: {'yes' if r['limits_ok'] else 'NO'}")
    if r["tracking"]:
        print(f"tracking over {r.get('tracking_samples', 0)} samples (Eq. 18):")
        print(f"  {'axis':4s} {'RMSE':>12s} {'MSE':>12s} {'max |e|':>12s}")
        for a, t in r["tracking"].items():
            print(f"  {a:4s} {t['rmse']:12.4e} {t['mse']:12.4e} {t['max_abs']:12.4e}")
    if "timing" in r:
        tm = r["timing"]
        print(f"worker: {tm['cycles']} cycles, period mean {tm['period_mean_us']:.1f} us, "
              f"jitter p99 {tm['jitter_p99_us']:.1f} us, late cycles {tm['late_cycles']}")
    for a in r["alarms"]:
        print(f"alarm: {a}")
    for n in r["notes"]:
        print(f"note: {n}")


def command() -> int:
    """``cnc-run`` as installed: ``main`` with its last word said in one line."""
    from planner.core.command import run_command

    return run_command("cnc-run", main)


if __name__ == "__main__":
    raise SystemExit(command())
