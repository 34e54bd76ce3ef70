"""The one refusal mechanism: every operator command is named (``Action``), and a command that
the machine's state forbids is refused by ``guarded`` before its body runs, with the reason the
state machine gives (``StateMachine.refusal``) and ``commandRefused`` told."""

from __future__ import annotations

import enum
import functools
from collections.abc import Callable
from typing import Concatenate, ParamSpec, Protocol, TypeVar

from app.machine.infra.events import PanelChannels
from app.machine.model import CommandResult

__all__ = ["Action", "Answers", "Gate", "Guarded", "guarded"]


class Action(enum.StrEnum):
    """The operator's commands, by the name the panel and the refusals use."""

    CYCLE_START = "cycle_start"
    RUN_FROM_LINE = "run_from_line"
    FEED_HOLD = "feed_hold"
    RESUME = "resume"
    STOP = "stop"
    RESET = "reset"
    ESTOP_RELEASE = "estop_release"
    JOG = "jog"
    MDI = "mdi"
    HOME = "home"
    SET_MACHINE_ZERO_HERE = "set_machine_zero_here"
    LOAD_PROGRAM = "load_program"
    UPDATE_CONFIG = "update_config"
    CONNECT = "connect"
    TOUCH_OFF = "touch_off"
    SET_WORK_OFFSET = "set_work_offset"
    SELECT_WORK_OFFSET = "select_work_offset"
    CLEAR_G92 = "clear_g92"
    SPINDLE_ON = "spindle_on"
    SPINDLE_SPEED = "spindle_speed"
    SET_SPINDLE_OVERRIDE = "set_spindle_override"
    SET_FEED_OVERRIDE = "set_feed_override"
    SET_RAPID_OVERRIDE = "set_rapid_override"
    SET_SINGLE_BLOCK = "set_single_block"
    SET_OPTIONAL_STOP = "set_optional_stop"
    SET_BLOCK_DELETE = "set_block_delete"
    SET_TOOL = "set_tool"
    REMOVE_TOOL = "remove_tool"
    SET_TOOL_IN_SPINDLE = "set_tool_in_spindle"
    TOUCH_OFF_TOOL = "touch_off_tool"
    MEASURE_TOOL = "measure_tool"
    PROBE = "probe"
    IMPORT_TOOL_TABLE = "import_tool_table"
    ACKNOWLEDGE_ALARM = "acknowledge_alarm"


class Answers:
    """A command's answer: accepted, or refused with the reason (``commandRefused`` told)."""

    def __init__(self, out: PanelChannels) -> None:
        self._out = out

    def refuse(self, action: str, reason: str) -> CommandResult:
        self._out.commandRefused.emit(str(action), reason)
        return CommandResult(False, str(action), reason)

    def ok(self, action: str) -> CommandResult:
        return CommandResult(True, str(action), "")


class Gate(Protocol):
    """What a part asks of the state machine to accept or refuse a command."""

    def refusal(self, action: str) -> str: ...

    def claim(self, action: str) -> str: ...

    def refuse(self, action: str, reason: str) -> CommandResult: ...

    def ok(self, action: str) -> CommandResult: ...


class Guarded(Protocol):
    """A part whose commands pass its ``gate`` first."""

    @property
    def gate(self) -> Gate: ...


P = ParamSpec("P")
G = TypeVar("G", bound=Guarded)


def guarded(action: Action) -> Callable[[Callable[Concatenate[G, P], CommandResult]],
                                        Callable[Concatenate[G, P], CommandResult]]:
    """The command is refused with the gate's reason when the machine's state forbids
    ``action`` (``StateMachine.refusal``) or the axes cannot be taken for it
    (``StateMachine.claim``); otherwise its body decides."""

    def wrap(fn: Callable[Concatenate[G, P], CommandResult]) -> Callable[Concatenate[G, P], CommandResult]:
        @functools.wraps(fn)
        def command(self: G, /, *args: P.args, **kwargs: P.kwargs) -> CommandResult:
            why = self.gate.refusal(action) or self.gate.claim(action)
            if why:
                return self.gate.refuse(action, why)
            return fn(self, *args, **kwargs)

        return command

    return wrap
