"""The cyclic worker: one EtherCAT cycle every Ts on absolute deadlines, fed set-points by the
controller through a bounded ring, with supervision, tracking and timing records.

One file per concern: ``types`` (states, codes, records, configuration), ``shared`` (the one
shared block and its ordering rules), ``cycle`` (the loop), ``clocked`` (the loop on its clock),
``homing`` (drive-side homing), ``switch_homing`` (homing to switches in position mode),
``watches`` (E-stop chain, limits), ``handwheel`` (an encoder's counts moving one axis),
``gantry`` (one axis on two drives), ``compensation`` (leadscrew), ``spindle`` (its own drive),
``ring`` (replacing queued set-points),
``acyclic`` (SDO and recovery beside the cycle), ``realtime`` (core, priority, sleeping),
``process`` (the worker's own process), ``messages`` (commands and alarm texts) and
``client`` (``CyclicWorker``, the controller's handle).
"""

from ..bus import DriveSpec
from .client import CyclicWorker
from .compensation import CompSpec
from .gantry import GantrySpec
from .handwheel import HandwheelMode, WheelState, stop_distance
from .messages import error_code_text
from .realtime import PROCESS_SPIN_S
from .spindle import SpindleState
from .types import (
    Alarm,
    AlarmCode,
    EventCode,
    HandwheelSpec,
    HomingState,
    HomingStep,
    InputWatch,
    ProbeLatch,
    ProbeState,
    ReplaceResult,
    SwitchHoming,
    TimingStats,
    TraceChunk,
    TrackingStats,
    WatchAction,
    WorkerConfig,
    WorkerEvent,
    WorkerSnapshot,
    WorkerState,
)

__all__ = [
    "PROCESS_SPIN_S", "Alarm", "AlarmCode", "CompSpec", "CyclicWorker", "DriveSpec", "EventCode",
    "GantrySpec", "HandwheelMode",
    "HandwheelSpec", "HomingState",
    "HomingStep", "InputWatch", "ProbeLatch", "ProbeState", "ReplaceResult", "SwitchHoming", "TimingStats",
    "TraceChunk", "TrackingStats", "WatchAction",
    "WorkerConfig", "WorkerEvent",
    "SpindleState", "WheelState", "WorkerSnapshot", "WorkerState", "error_code_text", "stop_distance",
]
