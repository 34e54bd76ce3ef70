"""Operator scenarios for ``cnc-run --script OPS.jsonl``: what an operator does during a run,
one action per line, and a recording of everything the machine did meanwhile.

A script line is a JSON object with one trigger and one action::

    {"at_line": 6, "op": "stop"}                  when the program reaches line 6
    {"after_s": 2.5, "op": "run_from_line", "line": 10}   2.5 s (machine time) after the previous action
    {"after_s": 0, "op": "feed_override", "percent": 150}

Actions run in the order written, each when its trigger comes after the one before it. Ops:
``feed_hold``, ``resume``, ``stop``, ``reset``, ``estop``, ``estop_release``, ``cycle_start``,
``run_from_line`` (``line``), ``feed_override`` / ``rapid_override`` / ``spindle_override``
(``percent``) and
``tool_changed`` (the operator has put in the tool: cycle start at a tool-change stop),
``override_limits``, ``input`` (simulated drives: a machine signal reads ``value``, true or
false, or null to release it: ``{"after_s": 1, "op": "input", "signal": "door_closed", "value":
false}``), and the handwheel: ``handwheel`` (``axis``: give it an axis, "" none),
``handwheel_step`` (``scale``: 0 x1, 1 x10, 2 x100) and ``mpg`` (simulated drives: the wheel
turned by ``counts``, either way: ``{"after_s": 0.5, "op": "mpg", "counts": 100}``), and
``spindle_load`` (simulated drives: a load bogs the spindle's own drive down to ``rpm``, null
takes it off: ``{"after_s": 2, "op": "spindle_load", "rpm": 3000}``). Blank
lines and lines starting with ``#`` are skipped. Every mistake is an error naming the file,
the line and the key.

``Recorder`` keeps every set-point the drives were sent (program, approach, jog and MDI alike)
with the program line and the commanded spindle speed, every change of the spindle and every
prompt the operator was shown. All times (trace, spindle changes, actions) are the machine's:
the worker's clock in s, the same in all three.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Protocol

import numpy as np

from app.machine.api import MachineApi
from app.machine.errors import MachineError
from app.machine.model import CommandResult, HoldKind, MachineState, SpindleState
from planner.core.errors import PlannerError
from planner.core.reading import SCRIPT, read_text

__all__ = ["OPS", "Recorder", "ScenarioOp", "ScenarioRunner", "read_script"]

#: op -> the extra key it needs ("" for none)
OPS: dict[str, str] = {
    "feed_hold": "", "resume": "", "stop": "", "reset": "", "estop": "", "estop_release": "",
    "cycle_start": "", "restart": "", "run_from_line": "line", "feed_override": "percent",
    "rapid_override": "percent", "spindle_override": "percent", "tool_changed": "", "override_limits": "",
    "input": "signal", "handwheel": "axis", "handwheel_step": "scale", "mpg": "counts",
    "spindle_load": "rpm",
}
_TRIGGERS = ("at_line", "after_s")


@dataclass(frozen=True, slots=True)
class ScenarioOp:
    op: str
    source: str                  # "file:line" of the script line, for messages
    at_line: int | None = None
    after_s: float | None = None
    line: int = 0                # run_from_line
    percent: float = 100.0       # overrides
    signal: str = ""             # input: the signal and the value it reads (None: released)
    value: bool | None = None
    axis: str = ""               # handwheel: the axis given to it ("" none)
    scale: int = 0               # handwheel_step: 0 x1, 1 x10, 2 x100
    counts: int = 0              # mpg: the counts the wheel is turned by (- the other way)
    rpm: float | None = None     # spindle_load: the speed a load bogs the spindle down to (None: off)

    def describe(self) -> str:
        trigger = f"at line {self.at_line}" if self.at_line is not None else f"after {self.after_s:g} s"
        extra = {"line": f" {self.line}", "percent": f" {self.percent:g} %",
                 "signal": f" {self.signal}={'released' if self.value is None else str(self.value).lower()}",
                 "axis": f" {self.axis or 'off'}", "scale": f" {('x1', 'x10', 'x100')[self.scale]}",
                 "counts": f" {self.counts:+d}",
                 "rpm": f" {'off' if self.rpm is None else f'{self.rpm:g} rpm'}",
                 "": ""}[OPS[self.op]]
        return f"{self.op}{extra} {trigger}"


#: the most counts one ``mpg`` turns the wheel by (10,000 turns of a 100-detent wheel)
MAX_WHEEL_COUNTS = 4_000_000
#: the largest number a script's key takes (a line, seconds, a percentage): JSON's integers
#: have no bound, and one beyond a float's range would not even compare
MAX_SCRIPT_NUMBER = 1e12


def _number(value: Any, where: str, key: str, integer: bool) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise MachineError(f"{where}: {key} must be a {'whole ' if integer else ''}number, got {value!r}")
    if not abs(value) <= MAX_SCRIPT_NUMBER:          # nan too; a huge integer compares exactly
        shown = str(value) if len(str(value)) <= 24 else f"{str(value)[:12]}... ({len(str(value))} digits)"
        raise MachineError(f"{where}: {key} must be a {'whole ' if integer else ''}number of at most "
                           f"1e12, got {shown}")
    if integer and value != int(value):
        raise MachineError(f"{where}: {key} must be a whole number, got {value!r}")
    if value < 0:
        raise MachineError(f"{where}: {key} must not be negative, got {value!r}")
    return float(value)


def parse_op(text: str, where: str) -> ScenarioOp:
    try:
        data = json.loads(text)
    except ValueError as exc:
        raise MachineError(f"{where}: not a JSON object ({exc})") from None
    if not isinstance(data, dict):
        raise MachineError(f"{where}: not a JSON object")
    op = data.get("op")
    if not isinstance(op, str) or op not in OPS:
        raise MachineError(f"{where}: op must be one of {', '.join(OPS)}, got {op!r}")
    extra = OPS[op]
    allowed = {extra, "value"} if extra == "signal" else {extra} if extra else set()
    unknown = sorted(set(data) - {"op", *_TRIGGERS} - allowed)
    if unknown:
        raise MachineError(f"{where}: unknown key {unknown[0]!r} for op {op!r}")
    triggers = [k for k in _TRIGGERS if k in data]
    if len(triggers) != 1:
        raise MachineError(f"{where}: give exactly one of at_line or after_s")
    kw: dict[str, Any] = {}
    if triggers[0] == "at_line":
        kw["at_line"] = int(_number(data["at_line"], where, "at_line", True))
    else:
        kw["after_s"] = _number(data["after_s"], where, "after_s", False)
    if extra == "line":
        if "line" not in data:
            raise MachineError(f"{where}: run_from_line needs \"line\"")
        kw["line"] = int(_number(data["line"], where, "line", True))
        if kw["line"] < 1:
            raise MachineError(f"{where}: line must be 1 or more")
    elif extra == "signal":
        if not isinstance(data.get("signal"), str) or "value" not in data:
            raise MachineError(f"{where}: input needs \"signal\" (its name) and \"value\" (true, false or "
                               "null)")
        if data["value"] is not None and not isinstance(data["value"], bool):
            raise MachineError(f"{where}: value must be true, false or null, got {data['value']!r}")
        kw["signal"], kw["value"] = data["signal"], data["value"]
    elif extra == "axis":
        if not isinstance(data.get("axis"), str):
            raise MachineError(f"{where}: handwheel needs \"axis\" (its name, \"\" for none)")
        kw["axis"] = data["axis"]
    elif extra == "scale":
        if data.get("scale") not in (0, 1, 2) or isinstance(data.get("scale"), bool):
            raise MachineError(f"{where}: scale must be 0 (x1), 1 (x10) or 2 (x100), got "
                               f"{data.get('scale')!r}")
        kw["scale"] = int(data["scale"])
    elif extra == "counts":
        counts = data.get("counts")
        if isinstance(counts, bool) or not isinstance(counts, int) or abs(counts) > MAX_WHEEL_COUNTS:
            raise MachineError(f"{where}: counts must be a whole number within +-{MAX_WHEEL_COUNTS}, got "
                               f"{counts!r}")
        kw["counts"] = counts
    elif extra == "rpm":
        if "rpm" not in data:
            raise MachineError(f"{where}: spindle_load needs \"rpm\" (the speed it bogs down to, null: off)")
        kw["rpm"] = None if data["rpm"] is None else _number(data["rpm"], where, "rpm", False)
    elif extra == "percent":
        if "percent" not in data:
            raise MachineError(f"{where}: {op} needs \"percent\"")
        kw["percent"] = _number(data["percent"], where, "percent", False)
    return ScenarioOp(op=op, source=where, **kw)


def read_script(path: str | Path) -> tuple[ScenarioOp, ...]:
    """The operator actions of a script file (MachineError naming file and line if wrong)."""
    p = Path(path)
    try:
        text = read_text(p, SCRIPT)
    except PlannerError as exc:
        raise MachineError(str(exc)) from None
    ops = []
    for number, line in enumerate(text.split("\n"), 1):
        stripped = line.strip()
        if stripped and not stripped.startswith("#"):
            ops.append(parse_op(stripped, f"{p}:{number}"))
    return tuple(ops)


class ScriptedMachine(MachineApi, Protocol):
    """The controller as a script drives it: its public face, the machine's clock and the
    trace of every set-point sent."""

    def machine_time_s(self) -> float: ...

    def add_trace_sink(self, sink: Callable[[np.ndarray, np.ndarray, np.ndarray, np.ndarray], None]
                       ) -> None: ...


class Recorder:
    """Every set-point sent while the drives were enabled, in machine coordinates, with the
    program line and commanded spindle speed (signed: + CW) of its time, and the prompts."""

    def __init__(self, ctl: ScriptedMachine) -> None:
        self.ctl = ctl
        self.ts_s = float(ctl.config.machine.planner.ts_s)
        self._chunks: list[tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, float]] = []
        self.prompts: list[dict[str, object]] = []
        # every change of the commanded spindle, at its machine time (the set-point trace has
        # no samples while the drives are disabled, after an E-stop for one)
        self.spindle: list[dict[str, float]] = []
        self._last_prompt: object = None
        ctl.add_trace_sink(self._chunk)
        ctl.stateChanged.connect(self._on_state)
        ctl.spindleChanged.connect(self._on_spindle)

    def _on_spindle(self, sp: SpindleState) -> None:
        t = float(self.ctl.machine_time_s())
        self.spindle.append({"t_s": round(t, 6), "rpm": float(sp.direction * sp.rpm)})

    def _chunk(self, cycles: np.ndarray, reference: np.ndarray, actual: np.ndarray,
               lines: np.ndarray) -> None:
        """A drained chunk of the trace (machine coordinates), each row with its set-point's line
        (a row of no program's set-point, at rest before it: the line shown)."""
        sp = self.ctl.spindle
        tagged = np.where(lines > 0, lines, int(self.ctl.current_line))
        self._chunks.append((cycles.copy(), reference.copy(), actual.copy(), tagged,
                             float(sp.direction * sp.rpm)))

    def _on_state(self, state: MachineState, _reason: str) -> None:
        prompt = self.ctl.prompt
        if state is MachineState.HOLD and prompt is not None and prompt is not self._last_prompt:
            if prompt.kind is not HoldKind.SINGLE_BLOCK:
                self.prompts.append(prompt.as_dict())
        self._last_prompt = prompt

    def arrays(self) -> dict[str, np.ndarray]:
        n = len(self.ctl.axes)
        if not self._chunks:
            empty = np.zeros((0, n))
            return {"t": np.zeros(0), "reference": empty, "actual": empty, "axes": np.array(self.ctl.axes),
                    "line": np.zeros(0, dtype=np.int64), "spindle_rpm": np.zeros(0)}
        cyc = np.concatenate([c[0] for c in self._chunks])
        return {
            "t": cyc * self.ts_s,
            "reference": np.concatenate([c[1] for c in self._chunks]),
            "actual": np.concatenate([c[2] for c in self._chunks]),
            "axes": np.array(self.ctl.axes),
            "line": np.concatenate([c[3] for c in self._chunks]).astype(np.int64),
            "spindle_rpm": np.concatenate([np.full(len(c[0]), c[4]) for c in self._chunks]),
        }

    def save(self, path: str) -> None:
        from planner.core.files import write_output

        d = self.arrays()
        write_output(path, lambda fh: np.savez_compressed(fh, t=d["t"], reference=d["reference"],
                                                          actual=d["actual"],
                                                          axes=d["axes"], line=d["line"],
                                                          spindle_rpm=d["spindle_rpm"]))


class ScenarioRunner:
    """Fires the script's actions in order as their triggers come; ``step()`` after every
    advance of the machine. ``done`` when every action has been tried."""

    def __init__(self, ctl: ScriptedMachine, ops: tuple[ScenarioOp, ...], now: Callable[[], float]) -> None:
        self.ctl = ctl
        self.ops = list(ops)
        self.now = now
        self.start_t = self.last_t = now()
        self.results: list[dict[str, object]] = []

    @property
    def done(self) -> bool:
        return not self.ops

    def step(self) -> None:
        while self.ops and self._due(self.ops[0]):
            op = self.ops.pop(0)
            res = self._fire(op)
            self.last_t = self.now()
            self.results.append({"op": op.describe(), "source": op.source, "t_s": round(self.last_t, 6),
                                 "ok": bool(res), "reason": getattr(res, "reason", "")})

    def _due(self, op: ScenarioOp) -> bool:
        if op.after_s is not None:
            return self.now() - self.last_t >= op.after_s - 1e-9
        status = self.ctl.snapshot()
        reached = (status.line >= (op.at_line or 0)
                   and status.state in (MachineState.RUNNING, MachineState.HOLD))
        if op.op == "tool_changed":
            # the operator puts the tool in once the machine stands at the change: the M6's own
            # line is reached while the motion still slows down to it
            return reached and status.hold_kind is HoldKind.TOOL_CHANGE
        return reached

    def _fire(self, op: ScenarioOp) -> CommandResult | _Refused:
        c = self.ctl
        if op.op == "run_from_line":
            return c.run_from_line(op.line, wait=True)
        if op.op == "feed_override":
            return c.set_feed_override(op.percent)
        if op.op == "rapid_override":
            return c.set_rapid_override(op.percent)
        if op.op == "spindle_override":
            return c.set_spindle_override(op.percent)
        if op.op == "cycle_start":
            return c.cycle_start(wait=True)
        if op.op == "restart":                   # after a stop: from the beginning, chosen
            return c.cycle_start(wait=True, from_start=True)
        if op.op == "estop":
            return c.estop("operator (script)")
        if op.op == "input":
            return c.simulate_input(op.signal, op.value)
        if op.op == "handwheel":
            return c.select_handwheel(op.axis)
        if op.op == "handwheel_step":
            return c.set_handwheel_step(op.scale)
        if op.op == "mpg":
            return c.turn_handwheel(op.counts)
        if op.op == "spindle_load":
            return c.simulate_spindle_load(op.rpm)
        if op.op == "tool_changed":
            if c.hold_kind is not HoldKind.TOOL_CHANGE:
                return _Refused(f"no tool change is waiting (machine {c.state.value})")
            return c.cycle_start()
        return getattr(c, op.op)()


@dataclass(frozen=True, slots=True)
class _Refused:
    reason: str

    def __bool__(self) -> bool:
        return False
