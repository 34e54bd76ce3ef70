"""``CyclicWorker``: the controller's handle of the cyclic worker.

    cfg = WorkerConfig(drives=(DriveSpec(0, "X", 10_000.0), DriveSpec(1, "Y", 10_000.0)))
    w = CyclicWorker(cfg)
    w.start()                      # bus open, cyclic loop running, drives DISABLED
    w.enable()                     # CiA 402 walk to OPERATION ENABLED, target := actual
    n = w.push(q_mm)               # (N, n_axes) set-points in axis units; returns how many fit
    s = w.snapshot()               # WorkerSnapshot, read at <= 30 Hz by the panel
    w.quick_stop("operator")       # quick stop all axes + alarm naming the cause
    w.fault_reset(); w.enable()
    w.stop()                       # drives disabled, bus closed, process joined

Modes (``WorkerConfig.mode``): "process" runs the loop in its own spawned process, pinned to
a core no other worker holds, SCHED_FIFO when permitted, memory locked, GC off, exchanging
everything through one shared block (``shared.py``; x86-64 only, see there); "thread" runs
the same loop as a thread of the caller (for comparison and for CPUs without total store
order); "manual" has no clock: ``step(n)`` runs n cycles at once (tests, fast headless runs).

Set-point serials: the k-th set-point the loop takes since start has serial k;
``samples_consumed()`` (live, not the snapshot) is the serial taken next. ``replace(from_serial,
q)`` swaps the queued tail from a serial on, atomically between two cycles.

All methods are called from one controller thread (or guarded by the caller); none blocks
for more than ``command_timeout_s``.
"""

from __future__ import annotations

import atexit
import collections
import contextlib
import multiprocessing as mp
import os
import threading
import time
from collections.abc import Sequence
from multiprocessing import shared_memory
from typing import Any

import numpy as np

from ..cia402 import Cia402State
from ..errors import ConfigurationError, WorkerError, WorkerTimeoutError
from .cycle import CycleLoop
from .gantry import widen, with_followers
from .messages import INJECT_NAMES, Command, Result, alarm_message, event_message
from .process import process_main, start_without_main
from .shared import ALARM_SLOTS, HIST_BIN_S, SharedBlock, Status, require_ordered_stores, trace_columns
from .types import (
    Alarm,
    AlarmCode,
    EventCode,
    HomingState,
    HomingStep,
    ProbeLatch,
    ProbeState,
    ReplaceResult,
    TimingStats,
    TraceChunk,
    TrackingStats,
    WatchAction,
    WorkerConfig,
    WorkerEvent,
    WorkerSnapshot,
    WorkerState,
)

__all__ = ["CyclicWorker"]

_EVENTS_KEPT = 32


#: the injections whose index is a terminal's (in ``WorkerConfig.terminals``), not an axis
_TERMINAL_INJECTIONS = frozenset({"terminal_input", "encoder_add", "lose_terminal", "restore_terminal"})


class CyclicWorker:
    """The controller-facing handle of the cyclic worker. See the module docstring."""

    def __init__(self, config: WorkerConfig) -> None:
        self.config = config
        self._layout = (config.n_axes, config.buffer_capacity, config.trace_capacity, config.n_terminals,
                        len(config.watches))
        self._shm: shared_memory.SharedMemory | None = None
        self._block: SharedBlock | None = None
        self._loop: CycleLoop | None = None
        self._thread: threading.Thread | None = None
        self._process: Any = None
        self._lock = threading.RLock()   # one command in flight; push/replace own the ring head
        self._alarms: list[Alarm] = []
        self._events: collections.deque[WorkerEvent] = collections.deque(maxlen=_EVENTS_KEPT)
        self._alarms_read = 0
        self._cmd_sent = 0                      # sequence number of the last command sent
        self._reasons: dict[int, str] = {}      # command seq -> quick stop / E-stop reason
        self._trace_read = 0
        self._started = False
        self.realtime_applied = ""
        #: what the bus start-up adapted to (a drive's own PDO mapping, objects it lacks, ...)
        self.bus_notes: tuple[str, ...] = ()

    # ------------------------------------------------------------------ life cycle
    @property
    def running(self) -> bool:
        return self._started

    def start(self) -> None:
        """Open the bus and start the cycle; returns when the drives are DISABLED and
        process data runs. Raises ``WorkerError`` (with the bus error text) on failure."""
        if self._started:
            return
        cfg = self.config
        if cfg.mode == "process":
            require_ordered_stores()
        self._alarms.clear()
        self._events.clear()
        self._alarms_read = 0
        self._cmd_sent = 0
        self._trace_read = 0
        self._reasons.clear()
        size = SharedBlock.size(*self._layout)
        if cfg.mode == "process":
            self._shm = shared_memory.SharedMemory(create=True, size=size)
            self._block = SharedBlock(self._shm.buf, *self._layout)
        else:
            self._block = SharedBlock(bytearray(size), *self._layout)
        self._block.clear_control()
        try:
            if cfg.mode == "process":
                assert self._shm is not None
                ctx = mp.get_context("spawn")
                self._process = ctx.Process(target=process_main,
                                            args=(cfg, self._shm.name, self._layout, os.getpid()),
                                            name="ethercat-worker", daemon=True)
                start_without_main(self._process)
                self._wait_status(cfg.start_timeout_s)
                self.realtime_applied, *notes = self._block.read_msg().split("\n")
                self.bus_notes = tuple(notes)
            else:
                self._loop = CycleLoop(cfg, self._block)
                self._loop.open_bus()
                self.bus_notes = tuple(self._loop.bus.notes) if self._loop.bus is not None else ()
                self._loop.publish()
                if cfg.mode == "thread":
                    self._thread = threading.Thread(target=self._thread_main, name="ethercat-worker",
                                                    daemon=True)
                    self._thread.start()
        except BaseException:
            self._cleanup()
            raise
        self._started = True
        atexit.register(self.stop)             # drives disabled and bus closed at interpreter exit

    def _thread_main(self) -> None:
        assert self._loop is not None
        try:
            self._loop.run_realtime()
        finally:
            self._loop.close_bus()

    def _wait_status(self, timeout_s: float) -> None:
        block = self._block
        assert block is not None
        t_end = time.monotonic() + timeout_s
        while time.monotonic() < t_end:
            status = int(block.ctl.status)
            if status == Status.RUNNING:
                return
            if status == Status.FAILED:
                raise WorkerError(f"worker failed to start: {block.read_msg()}")
            if self._process is not None and not self._process.is_alive():
                if int(block.ctl.status) == Status.FAILED:   # it wrote why just before it ended
                    raise WorkerError(f"worker failed to start: {block.read_msg()}")
                raise WorkerError(f"worker process exited with code {self._process.exitcode}")
            time.sleep(0.005)
        raise WorkerTimeoutError(f"worker did not start within {timeout_s} s")

    def stop(self) -> None:
        """Disable the drives, close the bus, end the loop. Stopping twice is harmless."""
        if not self._started:
            return
        atexit.unregister(self.stop)
        try:
            with contextlib.suppress(WorkerError):
                self._command(Command.STOP)
            if self._thread is not None:
                self._thread.join(timeout=5.0)
            if self._process is not None:
                self._process.join(timeout=5.0)
                if self._process.is_alive():
                    self._process.terminate()
                    self._process.join(timeout=2.0)
            if self.config.mode == "manual" and self._loop is not None:
                self._loop.close_bus()
        finally:
            self._started = False
            self._cleanup()

    def _cleanup(self) -> None:
        self._thread = None
        self._process = None
        if self._shm is not None:
            shm = self._shm
            self._block = None
            self._shm = None
            with contextlib.suppress(Exception):
                shm.close()
            with contextlib.suppress(Exception):
                shm.unlink()

    def __enter__(self) -> CyclicWorker:
        self.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self.stop()

    def __del__(self) -> None:  # pragma: no cover - best effort
        with contextlib.suppress(Exception):
            self.stop()

    # ------------------------------------------------------------------ commands
    def _live(self) -> SharedBlock:
        if not self._started or self._block is None:
            raise WorkerError("worker is not running: call start() first")
        return self._block

    def _command(self, code: Command, a: int = 0, b: int = 0, reason: str = "") -> bool:
        return self._command_result(code, a, b, reason) is Result.OK

    def _command_result(self, code: Command, a: int = 0, b: int = 0, reason: str = "",
                        reals: Sequence[float] = ()) -> Result:
        block = self._block
        if block is None:
            raise WorkerError("worker is not running")
        ctl = block.ctl
        with self._lock:
            ctl.cmd_code[...] = int(code)
            ctl.cmd_a[...] = a
            ctl.cmd_b[...] = b
            ctl.cmd_f[:len(reals)] = reals
            seq = int(ctl.cmd_seq) + 1
            if reason:
                self._reasons[seq] = reason
            self._cmd_sent = seq
            ctl.cmd_seq[...] = seq               # last: the loop reads the arguments after it
            if self.config.mode == "manual":
                assert self._loop is not None
                self._loop.poll_command()
                self._loop.publish()
            else:
                t_end = time.monotonic() + self.config.command_timeout_s
                while int(ctl.cmd_ack) != seq:
                    if time.monotonic() > t_end:
                        raise WorkerTimeoutError(f"worker did not acknowledge command {code.name} "
                                                 f"within {self.config.command_timeout_s} s")
                    if int(ctl.status) in (Status.STOPPED, Status.FAILED) and self._process is not None:
                        raise WorkerError("worker process has stopped")
                    if self._thread is not None and not self._thread.is_alive():
                        raise WorkerError("worker thread has stopped")
                    time.sleep(0.0005)
            return Result(int(ctl.cmd_result))

    def enable(self) -> None:
        """Walk every drive to OPERATION ENABLED (target := actual first). Returns at once;
        watch ``snapshot().state`` for ENABLED. Refused (WorkerError) in FAULT: fault_reset()."""
        self._live()
        if not self._command(Command.ENABLE):
            raise WorkerError(self._enable_refusal())

    def _enable_refusal(self) -> str:
        """Why the loop refused to enable: the E-stop chain open, an axis on a limit switch, or
        its state."""
        snap = self.snapshot()
        for w, active in zip(self.config.watches, snap.watches_active):
            if active and w.action is WatchAction.ESTOP_CHAIN:
                return f"the E-stop chain is open ({w.name or 'its input'}): close it first"
        for w, active in zip(self.config.watches, snap.watches_active):
            if active and w.action is WatchAction.LIMIT and not snap.limits_overridden:
                side = "positive" if w.side > 0 else "negative"
                return (f"axis {self.config.axis_names[w.axis]} is on its {side} limit switch: override "
                        "limits to jog it off the switch")
        return f"enable refused in state {snap.state.name}"

    def disable(self) -> None:
        """Shut the drives down to READY TO SWITCH ON; the buffer is flushed."""
        self._live()
        self._command(Command.DISABLE)

    def fault_reset(self) -> None:
        """Fault reset edge to faulted drives, clear the worker's alarms -> DISABLED."""
        self._live()
        self.snapshot()              # collect alarms raised so far, then clear them
        self._command(Command.FAULT_RESET)
        self._alarms.clear()

    def quick_stop(self, reason: str = "quick stop requested") -> None:
        """Quick stop of all axes, buffer flushed, alarm QUICK_STOP with `reason`."""
        self._live()
        self._command(Command.QUICK_STOP, reason=reason or "requested")

    def estop(self, reason: str = "E-stop") -> None:
        """E-stop input: quick stop of all axes and alarm ESTOP."""
        self._live()
        self._command(Command.ESTOP, reason=reason or "E-stop")

    def home(self, axis: int | str, method: int = 35) -> None:
        """Start the drive's own homing (CiA 402 mode 6) on one axis, method `method` (0x6098,
        written by SDO outside the cycle first). Only when ENABLED and at rest; watch
        ``snapshot().homing[axis]``; a refused method ends in HomingState.ERROR with an alarm."""
        self._live()
        i = self._axis_index(axis)
        if not self._command(Command.HOME, i, int(method)):
            raise WorkerError(f"homing axis {self.config.axis_names[i]} refused in state {self.state().name} "
                              "(needs ENABLED, buffer empty, no other acyclic transfer under way)")

    def home_to_switches(self, axes: Sequence[int | str]) -> None:
        """Home ``axes`` together to their switches (``WorkerConfig.switch_homing``), in
        position mode with set-points made by the loop. Only when ENABLED and at rest; watch
        ``snapshot().homing_steps`` and ``home_latched``; a failure is an alarm HOMING_SWITCH."""
        self._live()
        mask = 0
        for axis in axes:
            mask |= 1 << self._axis_index(axis)
        mask = with_followers(mask, self.config.gantry)          # a gantry homes both its sides
        if not self._command(Command.HOME_SWITCH, mask):
            names = " ".join(self.config.axis_names[i] for i in range(self.config.n_axes) if mask >> i & 1)
            snap = self.snapshot()
            if snap.alarms and snap.alarms[-1].code is AlarmCode.HOMING_SWITCH:
                raise WorkerError(snap.alarms[-1].message)     # an axis cannot home as configured
            raise WorkerError(f"homing {names} to switches refused in state {snap.state.name} "
                              "(needs ENABLED, at rest, and switch homing configured for each)")

    def set_terminal_output(self, terminal: int, word: int) -> None:
        """Terminal ``terminal``'s outputs (index in ``WorkerConfig.terminals``), from the next
        cycle on (an analog terminal's four 16-bit channels: a 64-bit word, sent as signed)."""
        self._live()
        word = int(word) - (1 << 64) if int(word) >= 1 << 63 else int(word)
        if not self._command(Command.TOUT, int(terminal), word):
            raise WorkerError(f"terminal {terminal} does not exist ({self.config.n_terminals} configured)")

    def override_limits(self, on: bool) -> None:
        """While on, an axis on a limit switch may be enabled and move away from it (never
        toward it); off by itself once no limit switch reads active."""
        self._live()
        self._command(Command.OVERRIDE_LIMITS, int(bool(on)))

    def handwheel(self, axis: int | str, mode: int, scale: float, limits: Sequence[float]) -> bool:
        """Axis ``axis`` follows the handwheel's counts from where it stands: ``scale`` axis units
        per count, ``mode`` 0 position or 1 velocity (``handwheel.HandwheelMode``), ``limits`` its
        (v, a, j, lowest, highest position) in axis units. False when refused: no handwheel
        configured, not ENABLED, set-points queued, the axis outside those positions, or
        another axis still moving (which then brakes to rest: ask again once it stands)."""
        self._live()
        reals = [float(scale), *(float(x) for x in limits)]
        if len(reals) != 6:
            raise WorkerError(f"handwheel limits are (v, a, j, lowest, highest), got {tuple(limits)}")
        return self._command_result(Command.HANDWHEEL, self._axis_index(axis), int(mode),
                                    reals=reals) is Result.OK

    def handwheel_off(self) -> bool:
        """The handwheel lets its axis go: True when the axis stood (the wheel is off now),
        False while it brakes to rest (off once it stands)."""
        self._live()
        return self._command(Command.HANDWHEEL, -1)

    def spindle(self, rpm: float, ramp_rpm_s: float) -> bool:
        """The spindle's own drive to ``rpm`` (signed: negative turns counter-clockwise; 0 stops
        and then disables it), the speed ramped at ``ramp_rpm_s`` (mode 9; in mode 3 the drive
        ramps). False when refused: no spindle drive, or it is quick-stopping or faulted."""
        self._live()
        return self._command_result(Command.SPINDLE, reals=[float(rpm), float(ramp_rpm_s)]) is Result.OK

    def compensate(self, axis: int | str, on: bool, home_offset: float = 0.0) -> bool:
        """Leadscrew compensation of ``axis`` on (the axis is homed: its machine position is the
        set-point less ``home_offset``) or off; the step it makes is taken up within the axis'
        limits (``compensation``). False: the axis has no compensation configured."""
        self._live()
        return self._command_result(Command.COMPENSATE, self._axis_index(axis), int(bool(on)),
                                    reals=[float(home_offset)]) is Result.OK

    def set_digital_output(self, axis: int | str, value: int) -> None:
        """The drive's digital outputs 0x60FE:1 (spindle on/direction bits), sent in the
        process data from the next cycle on."""
        self._live()
        if not self._command(Command.DOUT, self._axis_index(axis), int(value)):
            raise WorkerError(f"digital outputs of axis {axis} are not in the drive's process data "
                              "(0x60FE:1 not mapped)")

    def arm_probe(self, axis: int | str, bit: int, level: bool, terminal: int = -1) -> bool:
        """Watch bit ``bit`` of the digital inputs (0x60FD) of ``axis``'s drive (of terminal
        ``terminal``'s inputs when >= 0) from the next
        cycle on: the first cycle it reads ``level`` latches the actual positions and the
        set-points consumed (``snapshot().probe``). False, and nothing armed, when it reads
        ``level`` already (G38.2 with the probe touching) or the inputs are not in the drive's
        process data."""
        self._live()
        if not 0 <= int(bit) < 32:
            raise ConfigurationError(f"probe input bit {bit} outside 0..31 of 0x60FD")
        word = self.config.n_axes + int(terminal) if terminal >= 0 else self._axis_index(axis)
        return self._command(Command.PROBE, word, 1 | int(bit) << 1 | int(bool(level)) << 6)

    def disarm_probe(self) -> None:
        """Stop watching the probe input; the latch reads OFF."""
        self._live()
        self._command(Command.PROBE, 0, 0)

    def inject(self, name: str, axis: int | str = 0, value: int = 0) -> None:
        """Fault injection through the worker (any mode; the simulated bus only): names as
        ``sim_bus.INJECTIONS``; `value` = error code or frame count."""
        self._live()
        if name not in INJECT_NAMES:
            raise ConfigurationError(f"unknown injection {name!r}; known: {INJECT_NAMES}")
        code = INJECT_NAMES.index(name) | (int(value) << 8)
        # a terminal's injections name the terminal's index, the others an axis
        index = int(axis) if name in _TERMINAL_INJECTIONS else self._axis_index(axis)
        if not self._command(Command.INJECT, index, code):
            raise WorkerError(f"injection {name!r} needs bus_kind='sim'")

    def flush(self) -> None:
        """Drop the set-points not yet sent."""
        self._live()
        self._command(Command.FLUSH)

    def reset_tracking(self) -> None:
        """Zero the RMSE/MSE accumulators (start of a run)."""
        self._live()
        self._command(Command.RESET_TRACKING)

    def _axis_index(self, axis: int | str) -> int:
        if isinstance(axis, str):
            try:
                return self.config.axis_names.index(axis)
            except ValueError:
                raise ConfigurationError(f"unknown axis {axis!r}; axes: {self.config.axis_names}") from None
        if not 0 <= axis < self.config.n_axes:
            raise ConfigurationError(f"axis index {axis} out of range")
        return int(axis)

    # ------------------------------------------------------------------ set-points
    def free_space(self) -> int:
        """Set-points ``push`` can accept now."""
        return self.config.buffer_capacity - self.buffer_level()

    def buffer_level(self) -> int:
        ctl = self._live().ctl
        return int(ctl.head) - int(ctl.tail)

    def _setpoints(self, q: np.ndarray, what: str) -> np.ndarray:
        q = np.asarray(q, dtype=np.float64)
        q = q.reshape(1, -1) if q.ndim == 1 else q
        m = self.config.n_motion_axes              # a gantry's follower has no column
        if q.ndim != 2 or q.shape[1] != m:
            raise ConfigurationError(f"{what} expects (N, {m}) set-points, got {q.shape}")
        if not np.isfinite(q).all():
            raise ConfigurationError(f"{what}: set-points must be finite")
        return widen(q, self.config.gantry)

    def push(self, q: np.ndarray) -> int:
        """Append set-points (N, n_axes) in axis units (mm | deg), one per cycle. Returns how
        many were accepted (the ring is bounded: push the rest later). They are consumed
        only while ENABLED; ``enable()``, ``disable()``, ``fault_reset()`` and every reaction
        (quick stop) flush the buffer, so push after ``enable()``, starting at the actual
        position."""
        block = self._live()
        q = self._setpoints(q, "push")
        ctl = block.ctl
        cap = self.config.buffer_capacity
        with self._lock:                # head is ours, except while a replace() is in flight
            head = int(ctl.head)
            n = min(len(q), cap - (head - int(ctl.tail)))
            if n <= 0:
                return 0
            ring = block.ring
            start = head % cap
            first = min(n, cap - start)
            ring[start:start + first] = q[:first]
            if n > first:
                ring[: n - first] = q[first:n]
            ctl.head[...] = head + n    # after the rows it covers (see shared.py on ordering)
        return n

    def replace(self, from_serial: int, q: np.ndarray) -> tuple[ReplaceResult, int]:
        """Atomically drop every queued set-point with serial >= `from_serial` and queue `q`
        (N, n_axes) in their place. Returns (what happened, how many of `q` were queued): the
        ring is bounded, so push the rest later. The loop applies it between two cycles: the
        drives see the old set-points up to `from_serial - 1`, then `q[0]`, never a gap or a
        mix. Blocks until the loop acknowledges (about one cycle; at once in "manual").

        Protocol (single producer = this handle, single consumer = the loop): `q` goes to the
        staging area, then the command (code, from_serial, n), its sequence number last. The
        loop checks `from_serial` against its consumed count, copies the staging area into the
        ring and sets the ring head itself, then acknowledges. While the command is in flight
        this handle holds its lock (``push`` waits), so the head has one writer at any time."""
        block = self._live()
        q = self._setpoints(q, "replace")
        from_serial = int(from_serial)
        cap = self.config.buffer_capacity
        with self._lock:
            # room from from_serial on, judged now; the loop only makes more by consuming
            kept = max(0, from_serial - int(block.live.consumed))
            n = max(0, min(len(q), cap - kept))
            block.stage[:n] = q[:n]
            result = self._command_result(Command.REPLACE, from_serial, n)
        if result is Result.OK:
            return ReplaceResult.DONE, n
        if result is Result.TOO_LATE:
            return ReplaceResult.TOO_LATE, 0
        if result is Result.BEYOND_END:
            return ReplaceResult.BEYOND_END, 0
        raise WorkerError(f"replace refused ({result.name})")

    def samples_consumed(self) -> int:
        """Live serial the loop takes next (= set-points taken since start), read from the
        shared block at once (not the 30 Hz snapshot). One aligned int64 load."""
        return int(self._live().live.consumed)

    def probe_latched(self) -> tuple[float, ...] | None:
        """The actual positions (axis units) latched when the armed probe input changed, read
        from the shared block at once; None while it has not."""
        live = self._live().live
        if int(live.probe_state) != ProbeLatch.TRIPPED:
            return None
        return tuple(float(x) for x in live.probe_pos)

    # ------------------------------------------------------------------ manual mode
    def step(self, n_cycles: int = 1) -> None:
        """Manual mode only: run `n_cycles` cycles now (simulated time)."""
        if self.config.mode != "manual":
            raise WorkerError("step() is only available in mode='manual'")
        self._live()
        assert self._loop is not None
        self._loop.run_manual(int(n_cycles))

    # ------------------------------------------------------------------ reading
    def state(self) -> WorkerState:
        if not self._started or self._block is None:
            return WorkerState.STOPPED
        return WorkerState(int(self._block.snap_record["state"]))

    @property
    def command_seq(self) -> int:
        """Sequence number of the last command sent (compare ``WorkerSnapshot.command_seq``)."""
        return self._cmd_sent

    def wait_for(self, states: WorkerState | Sequence[WorkerState], timeout_s: float = 2.0) -> WorkerState:
        """Wait (polling snapshots) until the worker is in one of `states`, judged only on
        snapshots taken after at least one cycle ran and after the loop applied the last
        command sent through this handle: an older snapshot is stale and ignored."""
        wanted = (states,) if isinstance(states, WorkerState) else tuple(states)
        t_end = time.monotonic() + timeout_s
        need = self._cmd_sent
        while True:
            if self.config.mode == "manual":
                self.step(10)
            snap = self._read_snapshot()
            st = WorkerState(int(snap["state"]))
            fresh = int(snap["cmd_applied"]) >= need and int(snap["cycle"]) > 0
            if fresh and st in wanted:
                return st
            if time.monotonic() > t_end:
                stale = "" if fresh else f" (no snapshot yet after command {need})"
                names = [s.name for s in wanted]
                raise WorkerTimeoutError(f"worker in state {st.name}{stale}, wanted {names}")
            if self.config.mode != "manual":
                time.sleep(0.002)

    def _read_snapshot(self) -> np.ndarray:
        for _ in range(100):
            snap = self._live().read_snapshot()
            if snap is not None:
                snap.flags.writeable = False
                return snap
            time.sleep(0)
        raise WorkerTimeoutError("snapshot: writer never stable")

    def _collect_alarms(self) -> None:
        block = self._block
        assert block is not None
        total = int(block.ctl.alarms)
        start = max(self._alarms_read, total - ALARM_SLOTS)
        names = self.config.axis_names
        ts = self.config.ts_s
        for k in range(start, total):
            row = block.alarm[k % ALARM_SLOTS].copy()
            code_i, axis_i, cycle = int(row["code"]), int(row["axis"]), int(row["cycle"])
            a, b, f = int(row["a"]), int(row["b"]), float(row["f"])
            axis = names[axis_i] if 0 <= axis_i < len(names) else ""
            if code_i >= 100:
                ecode = EventCode(code_i)
                text = event_message(self.config, ecode, a, b, axis)
                self._events.append(WorkerEvent(ecode, text, axis, cycle, cycle * ts, time.time()))
                continue
            code = AlarmCode(code_i)
            commanded = code in (AlarmCode.ESTOP, AlarmCode.QUICK_STOP)
            reason = self._reasons.pop(int(row["command"]), "") if commanded else ""
            detail = block.read_msg() if code is AlarmCode.BUS_ERROR else ""
            msg = alarm_message(self.config, code, axis, axis_i, a, b, f, reason, detail)
            self._alarms.append(Alarm(code, msg, axis, cycle, cycle * ts, time.time()))
        self._alarms_read = total

    def alarms(self) -> tuple[Alarm, ...]:
        """Active alarms (cleared by ``fault_reset``)."""
        if self._block is not None:
            self._collect_alarms()
        return tuple(self._alarms)

    def events(self) -> tuple[WorkerEvent, ...]:
        """Recent events (the last 32; not cleared by ``fault_reset``), oldest first."""
        if self._block is not None:
            self._collect_alarms()
        return tuple(self._events)

    def snapshot(self) -> WorkerSnapshot:
        """A consistent copy of the worker's state (seqlock read; about 20 us)."""
        cfg = self.config
        s = self._read_snapshot()
        self._collect_alarms()
        ctl = self._live().ctl
        timed = int(s["timed"])
        hist = s["hist"]
        timing = TimingStats(
            cycles=int(s["cycle"]),
            period_mean_s=float(s["period_sum"]) / timed if timed else 0.0,
            period_min_s=float(s["period_min"]) if timed else 0.0,
            period_max_s=float(s["period_max"]) if timed else 0.0,
            jitter_p50_s=_percentile(hist, 0.50), jitter_p99_s=_percentile(hist, 0.99),
            jitter_p999_s=_percentile(hist, 0.999), jitter_max_s=float(s["jitter_max"]),
            late_cycles=int(s["late"]), missed_cycles=int(s["missed"]),
            exec_mean_s=float(s["exec_sum"]) / timed if timed else 0.0, exec_max_s=float(s["exec_max"]),
            span_s=float(s["last_start"] - s["first_start"]) if timed else 0.0,
            histogram_bin_s=HIST_BIN_S, jitter_histogram=tuple(int(x) for x in hist),
        )
        n_track = int(s["track_n"])
        n_win = int(s["window_n"])
        mse = s["sum_e2"] / n_track if n_track else np.zeros(cfg.n_axes)
        wmse = s["win_e2"] / n_win if n_win else mse
        tracking = TrackingStats(
            samples=n_track, rmse=tuple(float(x) for x in np.sqrt(mse)), mse=tuple(float(x) for x in mse),
            max_abs=tuple(float(x) for x in s["max_e"]), window_samples=n_win if n_win else n_track,
            window_rmse=tuple(float(x) for x in np.sqrt(wmse)), window_mse=tuple(float(x) for x in wmse),
        )
        level = int(ctl.head) - int(ctl.tail)
        lost = int(s["lost"])
        m = cfg.n_terminals
        return WorkerSnapshot(
            state=WorkerState(int(s["state"])), cycle=int(s["cycle"]), time_s=float(s["time_s"]),
            axis_names=cfg.axis_names,
            drive_states=tuple(Cia402State(int(x)) for x in s["drive_state"]),
            statuswords=tuple(int(x) for x in s["statusword"]),
            error_codes=tuple(int(x) for x in s["error_code"]),
            actual_position=s["act"], reference_position=s["ref"], following_error=s["fe"],
            buffer_level=level, buffer_capacity=cfg.buffer_capacity, samples_consumed=int(s["consumed"]),
            underruns=int(s["underruns"]), wkc=int(s["wkc"]), expected_wkc=int(s["wkc_expected"]),
            wkc_errors=int(s["wkc_errors"]),
            homing=tuple(HomingState(int(x)) for x in s["homing"]), homed=tuple(bool(x) for x in s["homed"]),
            alarms=tuple(self._alarms), timing=timing, tracking=tracking,
            digital_outputs=tuple(int(x) for x in s["dout"]),
            command_seq=int(s["cmd_applied"]),
            lost_slaves=tuple(p for p in range(63) if lost >> p & 1),
            events=tuple(self._events),
            digital_inputs=tuple(int(x) for x in s["din"]),
            probe=ProbeState(ProbeLatch(int(s["probe_state"])), int(s["probe_consumed"]),
                             tuple(float(x) for x in s["probe_pos"])),
            terminal_inputs=tuple(int(x) for x in s["tin"][:m]),
            terminal_outputs=tuple(int(x) for x in s["tout"][:m]),
            terminal_counts=tuple(int(x) for x in s["tcount"][:m]),
            watches_active=tuple(bool(x) for x in s["watch"][:len(cfg.watches)]),
            limits_overridden=bool(s["override"]),
            homing_steps=tuple(HomingStep(int(x)) for x in s["home_step"]),
            home_latched=tuple(float(x) for x in s["home_latch"]),
            handwheel_state=int(s["wheel_state"]), handwheel_axis=int(s["wheel_axis"]),
            compensation=tuple(float(x) for x in s["comp"]),
            compensation_on=tuple(bool(x) for x in s["comp_on"]),
            spindle_state=int(s["spindle_state"]),
            spindle_drive_state=Cia402State(int(s["spindle_drive"])) if cfg.spindle else None,
            spindle_rpm_command=float(s["spindle_cmd"]), spindle_rpm_actual=float(s["spindle_rpm"]),
            spindle_error_code=int(s["spindle_error"]), gantry_skew=tuple(float(x) for x in s["skew"]),
        )

    def drain_trace(self) -> TraceChunk:
        """Per-cycle (reference, actual) recorded while ENABLED since the last drain."""
        block = self._live()
        n = self.config.n_axes
        cap = self.config.trace_capacity
        head = int(block.ctl.trace_head)
        start = max(self._trace_read, head - cap)
        dropped = start - self._trace_read
        idx = np.arange(start, head) % cap if cap else np.zeros(0, dtype=np.int64)
        rows = block.trace[idx].copy() if cap else np.zeros((0, trace_columns(n)))
        self._trace_read = head
        return TraceChunk(rows[:, 0].astype(np.int64), rows[:, 1:1 + n], rows[:, 1 + n:1 + 2 * n], dropped,
                          rows[:, -1].astype(np.int64))


def _percentile(hist: np.ndarray, q: float) -> float:
    total = int(hist.sum())
    if total == 0:
        return 0.0
    idx = int(np.searchsorted(np.cumsum(hist), q * total, side="left"))
    return (idx + 1) * HIST_BIN_S        # upper edge of the bin (conservative)
