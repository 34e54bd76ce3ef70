"""How the parts of the controller tell each other and the panel what happened, without Qt.

A ``Channel`` is a typed signal in plain Python: ``connect`` a handler, ``emit`` the values;
handlers run at once, in the emitting thread, in the order they were connected. The parts are
built by the facade in a fixed order (``app.machine.controller``), so the order of handlers is
that order: a part built earlier hears an event first.

``PanelChannels`` are the facts the panel is told; the facade relays each to its Qt signal of
the same name, one to one. ``MachineEvents`` are what the parts tell each other (as Klipper's
objects subscribe to "klippy:shutdown"): a part that must react to an E-stop, a fault, a reset
or a new configuration subscribes to it, instead of the part that saw it reaching into every
other one. Every event is emitted in the controller's (GUI) thread.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field, fields
from enum import Enum
from typing import TYPE_CHECKING, Any, Generic, TypeVarTuple, Unpack

if TYPE_CHECKING:
    from app.machine.config import MachineConfig
    from app.machine.model import (
        Activity,
        Alarm,
        BusStatus,
        HandwheelStatus,
        MachineState,
        ProbingResult,
        ProgramInfo,
        ProgramIssue,
        RunSummary,
        SpindleState,
        TrackingReport,
    )
    from planner.core.program import Program
    from planner.core.tools import ToolTable

__all__ = ["AlarmReaction", "Channel", "MachineEvents", "PanelChannels"]

Ts = TypeVarTuple("Ts")


class Channel(Generic[*Ts]):
    """A typed signal: handlers connected in order, called in that order by ``emit``."""

    __slots__ = ("_handlers",)

    def __init__(self) -> None:
        self._handlers: list[Callable[[Unpack[Ts]], object]] = []

    def connect(self, handler: Callable[[Unpack[Ts]], object]) -> None:
        self._handlers.append(handler)

    def emit(self, *args: *Ts) -> None:
        for handler in tuple(self._handlers):
            handler(*args)


def _ch() -> Any:
    return Channel()


@dataclass(frozen=True, eq=False)
class PanelChannels:
    """What the panel is told, one channel per Qt signal of the facade (same name, same values;
    ``app.machine.api.MachineApi`` documents each)."""

    stateChanged: Channel[MachineState, str] = field(default_factory=_ch)
    activityChanged: Channel[Activity] = field(default_factory=_ch)
    positionChanged: Channel[tuple[float, ...], tuple[float, ...]] = field(default_factory=_ch)
    trackingSample: Channel[float, tuple[float, ...], tuple[float, ...]] = field(default_factory=_ch)
    programLoaded: Channel[ProgramInfo] = field(default_factory=_ch)
    programReadAgain: Channel[Program] = field(default_factory=_ch)
    programErrors: Channel[tuple[ProgramIssue, ...]] = field(default_factory=_ch)
    loadingChanged: Channel[bool, str] = field(default_factory=_ch)
    programFinished: Channel[RunSummary] = field(default_factory=_ch)
    lineChanged: Channel[int] = field(default_factory=_ch)
    progressChanged: Channel[float, float] = field(default_factory=_ch)
    speedChanged: Channel[float] = field(default_factory=_ch)
    overridesChanged: Channel[float, float] = field(default_factory=_ch)
    feedOverrideNote: Channel[str] = field(default_factory=_ch)
    modesChanged: Channel[bool, bool, bool] = field(default_factory=_ch)
    alarmsChanged: Channel[tuple[Alarm, ...]] = field(default_factory=_ch)
    homedChanged: Channel[tuple[bool, ...]] = field(default_factory=_ch)
    offsetsChanged: Channel[dict[str, tuple[float, ...]], str] = field(default_factory=_ch)
    spindleChanged: Channel[SpindleState] = field(default_factory=_ch)
    toolsChanged: Channel[ToolTable, int] = field(default_factory=_ch)
    busStateChanged: Channel[BusStatus] = field(default_factory=_ch)
    trackingUpdated: Channel[TrackingReport] = field(default_factory=_ch)
    configChanged: Channel[MachineConfig] = field(default_factory=_ch)
    commandRefused: Channel[str, str] = field(default_factory=_ch)
    message: Channel[str] = field(default_factory=_ch)
    probingFinished: Channel[ProbingResult] = field(default_factory=_ch)
    handwheelChanged: Channel[HandwheelStatus] = field(default_factory=_ch)
    spindleSample: Channel[float, float, float] = field(default_factory=_ch)

    @classmethod
    def names(cls) -> tuple[str, ...]:
        return tuple(f.name for f in fields(cls))


class AlarmReaction(Enum):
    """What an alarm calls for from the state machine (``MachineEvents.alarm_reaction``)."""

    ESTOP = "estop"                    # the machine in E-stop
    FAULT = "fault"                    # the drives stopped by themselves: ALARM
    STOP = "stop"                      # a stop along the path: ALARM
    HOMING_FAILED = "homing_failed"    # homing ends: ALARM in HOMING or IDLE


@dataclass(frozen=True, eq=False)
class MachineEvents:
    """What the parts tell each other."""

    # an alarm that stops the machine was raised (what it calls for, its cause, whether a
    # program may resume where it stopped): the state machine reacts
    alarm_reaction: Channel[AlarmReaction, str, bool] = field(default_factory=_ch)

    # a real change of the machine state (old, new), before the panel is told
    transition: Channel[MachineState, MachineState] = field(default_factory=_ch)
    # the E-stop: the drives are quick-stopped; motion, homing, spindle and outputs stop (reason)
    estop: Channel[str] = field(default_factory=_ch)
    # a quick-stop class alarm: the drives stopped by themselves (cause); motion and homing end
    fault: Channel[str] = field(default_factory=_ch)
    # a STOP class alarm: motion stops along its path (cause, whether the run may resume there)
    alarm_stop: Channel[str, bool] = field(default_factory=_ch)
    # a drive's homing failed (cause): homing ends
    homing_failed: Channel[str] = field(default_factory=_ch)
    # reset accepted in this state, before the machine leaves it
    reset: Channel[MachineState] = field(default_factory=_ch)
    # a configuration was applied (it, whether its axes differ from the one before): the
    # parts whose size follows the axes adapt
    config_changed: Channel[MachineConfig, bool] = field(default_factory=_ch)
    # ... and the panel was told: what was checked against the one before is checked again
    # (before the command returns, when True: headless use)
    config_applied: Channel[bool] = field(default_factory=_ch)
    # the control is closing, its motion at rest: what runs by itself (the spindle) stops
    shutdown: Channel[()] = field(default_factory=_ch)
    # at start: the last run was cut by a power loss or a kill (its program's file, the line it
    # was at, when the position was last saved)
    run_interrupted: Channel[str, int, float] = field(default_factory=_ch)
    # the operator's override changed the speed of the turning spindle beyond the band it is at
    # speed in: the running motion holds along its path until the spindle reads its new speed
    spindle_speed_changed: Channel[()] = field(default_factory=_ch)
    # the drives' status is wanted at once (a command changed them): the poller polls
    poll_now: Channel[()] = field(default_factory=_ch)
    # the worker was started and its drives are about to be enabled
    connecting: Channel[()] = field(default_factory=_ch)
    # the bus is up: every part tells the panel all it shows
    announce: Channel[()] = field(default_factory=_ch)
    # the coordinates of the standing machine changed (machine zero set, an offset changed)
    coordinates_changed: Channel[()] = field(default_factory=_ch)
    # the operator asked for another program (a cycle start waiting for the one before is void)
    load_requested: Channel[()] = field(default_factory=_ch)
    # the loaded program was let go (a load starts), loaded (its info) or refused
    program_let_go: Channel[()] = field(default_factory=_ch)
    program_loaded: Channel[ProgramInfo] = field(default_factory=_ch)
    program_refused: Channel[()] = field(default_factory=_ch)
    # the single-block plan made in the background is ready (True) or failed (False)
    run_plan_done: Channel[bool] = field(default_factory=_ch)
