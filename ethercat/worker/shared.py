"""The one block of memory the cyclic loop and the controller share.

Its layout is one structured NumPy dtype (``block_dtype``): a control record (command
mailbox, ring indices, sequence numbers), the live record the loop writes every cycle, the
snapshot record (a seqlock copy of the live one, read by the controller at <= 30 Hz), the
set-point ring, the staging area of ``replace``, the alarm ring and the trace ring. In mode
"process" the block lives in ``multiprocessing.shared_memory``; in "thread" and "manual" in a
``bytearray``. ``SharedBlock`` makes every view once, so the cycle indexes ready-made arrays
and allocates none.

Ordering. One producer and one consumer per channel, each publishing with a single aligned
8-byte store *after* the data it covers: the controller writes ring rows, then ``head``; the
command's arguments, then ``cmd_seq``; the loop writes the snapshot between two increments
of ``snap_seq``. That is correct when every store becomes visible to the other CPU in program
order, which x86-64 guarantees (total store order) and NumPy's stores preserve (no compiler
reordering across separate Python statements). On weakly ordered CPUs (ARM, POWER, RISC-V)
a reader could see ``head`` before the rows it covers, and Python offers no store barrier,
so the process mode refuses to start there (``require_ordered_stores``); the thread and
manual modes stay correct on every CPU because the GIL hand-over between threads is a full
barrier.
"""

from __future__ import annotations

import platform

import numpy as np

from ..errors import WorkerError

__all__ = ["ALARM_SLOTS", "CMD_FLOATS", "HIST_BINS", "HIST_BIN_S", "MSG_BYTES", "SharedBlock", "Status",
           "block_dtype", "ordered_stores", "require_ordered_stores"]

HIST_BIN_S = 5e-6
HIST_BINS = 401              # 0 .. 2 ms in 5 us bins, last = overflow
ALARM_SLOTS = 64
MSG_BYTES = 1024
CMD_FLOATS = 8               # a command's real-valued arguments (the handwheel's scale and limits)

#: CPUs whose stores become visible to other cores in program order
TSO_MACHINES = frozenset({"x86_64", "amd64", "i386", "i486", "i586", "i686", "x86"})


class Status:
    """Life of the worker process, in ``control.status``."""

    STARTING, RUNNING, STOPPED, FAILED = range(4)


_CONTROL = np.dtype([
    ("status", "i8"), ("pid", "i8"),
    # command mailbox: the controller writes code, a, b, then seq; the loop answers result, ack
    ("cmd_seq", "i8"), ("cmd_ack", "i8"), ("cmd_code", "i8"), ("cmd_a", "i8"), ("cmd_b", "i8"),
    ("cmd_result", "i8"), ("cmd_f", "f8", (CMD_FLOATS,)),
    # set-point ring: head written by the controller (and by the loop during a replace, while
    # the controller waits for the acknowledgement), tail by the loop
    ("head", "i8"), ("tail", "i8"),
    ("snap_seq", "i8"),     # odd while the loop copies the snapshot
    ("alarms", "i8"),       # alarm records written so far
    ("trace_head", "i8"),   # trace rows written so far
])

_ALARM = np.dtype([("code", "i8"), ("axis", "i8"), ("cycle", "i8"), ("a", "i8"), ("b", "i8"),
                   ("command", "i8"), ("f", "f8")])


def live_dtype(n: int, m: int = 0, w: int = 0) -> np.dtype:
    """What the loop updates every cycle (and what a snapshot copies): n axes, m terminals,
    w watched inputs (arrays of the last two hold at least one element)."""
    m1, w1 = max(m, 1), max(w, 1)
    return np.dtype([
        ("cycle", "i8"), ("state", "i8"), ("consumed", "i8"), ("underruns", "i8"), ("wkc", "i8"),
        ("wkc_expected", "i8"), ("wkc_errors", "i8"), ("late", "i8"), ("missed", "i8"),
        ("track_n", "i8"), ("window_n", "i8"), ("timed", "i8"), ("cmd_applied", "i8"), ("lost", "i8"),
        ("time_s", "f8"), ("period_sum", "f8"), ("period_min", "f8"), ("period_max", "f8"),
        ("jitter_max", "f8"), ("exec_sum", "f8"), ("exec_max", "f8"), ("first_start", "f8"),
        ("last_start", "f8"),
        # the probe: state (0 off, 1 armed, 2 tripped), the set-points consumed when it tripped,
        # and the actual positions of that cycle
        ("probe_state", "i8"), ("probe_consumed", "i8"), ("probe_pos", "f8", (n,)),
        ("drive_state", "i8", (n,)), ("statusword", "i8", (n,)), ("error_code", "i8", (n,)),
        ("homing", "i8", (n,)), ("homed", "i8", (n,)), ("dout", "i8", (n,)), ("din", "i8", (n,)),
        ("act", "f8", (n,)), ("ref", "f8", (n,)), ("fe", "f8", (n,)),
        ("sum_e2", "f8", (n,)), ("win_e2", "f8", (n,)), ("max_e", "f8", (n,)),
        ("hist", "i8", (HIST_BINS,)),
        # terminals: inputs, outputs, encoder counts; watched inputs active; limits overridden;
        # homing to switches: step and latched position per axis
        ("tin", "i8", (m1,)), ("tout", "i8", (m1,)), ("tcount", "i8", (m1,)), ("watch", "i8", (w1,)),
        ("override", "i8"), ("home_step", "i8", (n,)), ("home_latch", "f8", (n,)),
        # the handwheel: its state (``handwheel.WheelState``) and the axis it moves (-1: none)
        ("wheel_state", "i8"), ("wheel_axis", "i8"),
        # leadscrew compensation: the correction sent last per axis, and whether it is on
        ("comp", "f8", (n,)), ("comp_on", "i8", (n,)),
        # the spindle's drive: ``spindle.SpindleState``, its CiA 402 state, the speed commanded
        # and read (rpm), its error code
        ("spindle_state", "i8"), ("spindle_drive", "i8"), ("spindle_cmd", "f8"), ("spindle_rpm", "f8"),
        ("spindle_error", "i8"),
        # gantries: each follower's skew from its leader (0 at the other axes)
        ("skew", "f8", (n,)),
    ], align=True)



def trace_columns(n: int) -> int:
    """Columns of a trace row for n axes: cycle, reference (n), actual (n), the serial of the
    reference's set-point."""
    return 2 + 2 * n


def block_dtype(n: int, capacity: int, trace_capacity: int, m: int = 0, w: int = 0) -> np.dtype:
    """The whole shared block for n axes, a ring of `capacity` set-points and a trace ring
    (m terminals, w watched inputs)."""
    live = live_dtype(n, m, w)
    return np.dtype([
        ("control", _CONTROL), ("msg", "u1", (MSG_BYTES,)), ("live", live), ("snap", live),
        ("ring", "f8", (capacity, n)), ("stage", "f8", (capacity, n)),
        ("alarm", _ALARM, (ALARM_SLOTS,)), ("trace", "f8", (max(trace_capacity, 1), trace_columns(n))),
    ], align=True)


class _Fields:
    """Attribute access to the fields of one record: scalars as 0-d views (read with
    ``int(x)`` / ``float(x)``, write with ``x[...] = v``), arrays as views. Subclasses declare
    the fields; the declaration must match the dtype (checked when the views are made)."""

    def __init__(self, record: np.ndarray) -> None:
        names = tuple(record.dtype.names or ())
        declared = tuple(getattr(type(self), "__annotations__", {}))
        if names != declared:
            raise TypeError(f"{type(self).__name__} declares {declared}, the record has {names}")
        for name in names:
            setattr(self, name, record[name])


class ControlFields(_Fields):
    status: np.ndarray
    pid: np.ndarray
    cmd_seq: np.ndarray
    cmd_ack: np.ndarray
    cmd_code: np.ndarray
    cmd_a: np.ndarray
    cmd_b: np.ndarray
    cmd_result: np.ndarray
    cmd_f: np.ndarray
    head: np.ndarray
    tail: np.ndarray
    snap_seq: np.ndarray
    alarms: np.ndarray
    trace_head: np.ndarray


class LiveFields(_Fields):
    cycle: np.ndarray
    state: np.ndarray
    consumed: np.ndarray
    underruns: np.ndarray
    wkc: np.ndarray
    wkc_expected: np.ndarray
    wkc_errors: np.ndarray
    late: np.ndarray
    missed: np.ndarray
    track_n: np.ndarray
    window_n: np.ndarray
    timed: np.ndarray
    cmd_applied: np.ndarray
    lost: np.ndarray
    time_s: np.ndarray
    period_sum: np.ndarray
    period_min: np.ndarray
    period_max: np.ndarray
    jitter_max: np.ndarray
    exec_sum: np.ndarray
    exec_max: np.ndarray
    first_start: np.ndarray
    last_start: np.ndarray
    probe_state: np.ndarray
    probe_consumed: np.ndarray
    probe_pos: np.ndarray
    drive_state: np.ndarray
    statusword: np.ndarray
    error_code: np.ndarray
    homing: np.ndarray
    homed: np.ndarray
    dout: np.ndarray
    din: np.ndarray
    act: np.ndarray
    ref: np.ndarray
    fe: np.ndarray
    sum_e2: np.ndarray
    win_e2: np.ndarray
    max_e: np.ndarray
    hist: np.ndarray
    tin: np.ndarray
    tout: np.ndarray
    tcount: np.ndarray
    watch: np.ndarray
    override: np.ndarray
    home_step: np.ndarray
    home_latch: np.ndarray
    wheel_state: np.ndarray
    wheel_axis: np.ndarray
    comp: np.ndarray
    comp_on: np.ndarray
    spindle_state: np.ndarray
    spindle_drive: np.ndarray
    spindle_cmd: np.ndarray
    spindle_rpm: np.ndarray
    spindle_error: np.ndarray
    skew: np.ndarray


class SharedBlock:
    """Typed views of one shared block, made once."""

    def __init__(self, buf: bytearray | memoryview | None, n: int, capacity: int,
                 trace_capacity: int, m: int = 0, w: int = 0) -> None:
        if buf is None:
            raise WorkerError("shared memory block is closed")
        self.dtype = block_dtype(n, capacity, trace_capacity, m, w)
        self.root = np.ndarray((), dtype=self.dtype, buffer=buf)
        self.ctl = ControlFields(self.root["control"])
        self.live_record = self.root["live"]
        self.snap_record = self.root["snap"]
        self.live = LiveFields(self.live_record)
        self.msg = self.root["msg"]
        self.ring = self.root["ring"]
        self.stage = self.root["stage"]
        self.alarm = self.root["alarm"]
        self.trace = self.root["trace"]

    @staticmethod
    def size(n: int, capacity: int, trace_capacity: int, m: int = 0, w: int = 0) -> int:
        return block_dtype(n, capacity, trace_capacity, m, w).itemsize

    def clear_control(self) -> None:
        self.root["control"] = 0

    # ---------------------------------------------------------------- snapshot (seqlock)
    def publish(self) -> None:
        """Copy the live record into the snapshot between two increments of snap_seq."""
        seq = self.ctl.snap_seq
        seq[...] = int(seq) + 1
        np.copyto(self.snap_record, self.live_record)
        seq[...] = int(seq) + 1

    def read_snapshot(self, attempts: int = 1000) -> np.ndarray | None:
        """A consistent copy of the snapshot record, or None when the writer never held still."""
        seq = self.ctl.snap_seq
        for _ in range(attempts):
            s1 = int(seq)
            if s1 & 1:
                continue
            copy = self.snap_record.copy()
            if int(seq) == s1:
                return copy
        return None

    # ---------------------------------------------------------------- text channel
    def write_msg(self, text: str) -> None:
        data = text.encode("utf-8", "replace")[: MSG_BYTES - 1]
        self.msg[:] = 0
        self.msg[: len(data)] = np.frombuffer(data, dtype=np.uint8)

    def read_msg(self) -> str:
        return bytes(self.msg).split(b"\0", 1)[0].decode("utf-8", "replace")


def ordered_stores(machine: str | None = None) -> bool:
    """True on CPUs with total store order (x86, x86-64)."""
    return (machine if machine is not None else platform.machine()).lower() in TSO_MACHINES


def require_ordered_stores(machine: str | None = None) -> None:
    """Refuse the shared-memory process mode where stores may be seen out of order."""
    if not ordered_stores(machine):
        name = machine if machine is not None else platform.machine()
        raise WorkerError(
            f"worker mode 'process' needs a CPU with total store order (x86-64); this is {name!r}, "
            "where the set-point ring could be read before its data arrives. Use mode 'thread' here.")
