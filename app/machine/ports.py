"""The narrow interfaces the controller's parts receive from one another.

No part holds the controller: each gets, at construction, only what it uses of the others,
typed by one of these protocols (a part may offer several: the positions are read by many and
changed by few). The facade (``app.machine.controller``) builds the parts and hands them over.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Protocol

if TYPE_CHECKING:
    import numpy as np

    from app.machine.config import MachineConfig
    from app.machine.model import (
        Alarm,
        Budget,
        CommandResult,
        ProgramInfo,
        ResumePoint,
        Severity,
        SpindleState,
    )
    from planner.core.frames import Frame
    from planner.core.machine import MachineSpec
    from planner.core.program import Coolant, Program
    from planner.core.tools import Tool, ToolTable

__all__ = [
    "AlarmSink",
    "AlarmStore",
    "CoordinatesView",
    "LoaderView",
    "MotionState",
    "OutputSwitch",
    "PositionsView",
    "RunModes",
    "Settings",
    "SpindleDrive",
    "SpindleView",
    "ToolView",
]


class Settings(Protocol):
    """The applied machine configuration (it changes with ``update_config``: read it anew)."""

    @property
    def config(self) -> MachineConfig: ...

    @property
    def budget(self) -> Budget: ...


class AlarmSink(Protocol):
    """Where a part records what went wrong, and what the state machine acknowledges."""

    def raise_alarm(self, source: str, cause: str, severity: Severity, code: str = "") -> Alarm: ...

    def alarm_stop(self, cause: str, source: str, code: str, resumable: bool = True) -> None: ...

    def fault(self, cause: str, source: str, code: str) -> None: ...

    def acknowledge_all(self) -> None: ...

    def acknowledge_code(self, code: str) -> None: ...

    def stops_motion(self) -> bool: ...


class AlarmStore(Protocol):
    def load_alarms(self) -> list[Alarm]: ...

    def save_alarms(self, alarms: list[Alarm]) -> None: ...


class PositionsView(Protocol):
    """Where the axes are (machine coordinates) and whether they are homed."""

    @property
    def homed(self) -> tuple[bool, ...]: ...

    @property
    def home_offset(self) -> np.ndarray: ...

    def machine_pos(self) -> np.ndarray: ...

    def reference_pos(self) -> np.ndarray: ...


class CoordinatesView(Protocol):
    """The one model of coordinates: the offsets in force and the machine the planner reads."""

    @property
    def active_offset(self) -> str: ...

    @property
    def offsets(self) -> dict[str, tuple[float, ...]]: ...

    @property
    def parameters(self) -> dict[int, float]: ...

    def rotation_of(self, name: str) -> float: ...

    def frame(self) -> Frame: ...

    def panel_frame(self) -> Frame: ...

    def machine(self) -> MachineSpec: ...

    def apply_parameters(self, values: dict[int, float]) -> None: ...

    def set_spindle_tool(self, number: int, offsets: tuple[float, ...]) -> None: ...

    def start_offset(self) -> tuple[int, tuple[float, ...]]: ...

    def follow_program(self, frame: Frame | None) -> None: ...

    def program_left(self, program: Program, move: int) -> None: ...


class LoaderView(Protocol):
    """The program loaded, and what is being checked or planned in the background."""

    @property
    def program_info(self) -> ProgramInfo | None: ...

    @property
    def checking_name(self) -> str: ...

    @property
    def planning_name(self) -> str: ...


class MotionState(Protocol):
    """Whether something moves, and where a stopped program would resume."""

    @property
    def busy(self) -> bool: ...

    @property
    def resume_point(self) -> ResumePoint | None: ...

    def standing(self) -> bool: ...


class RunModes(Protocol):
    """The operator's switches for a run (``app.machine.program.switches`` owns them)."""

    @property
    def feed_pct(self) -> float: ...

    @property
    def rapid_pct(self) -> float: ...

    @property
    def single_block(self) -> bool: ...

    @property
    def optional_stop(self) -> bool: ...

    @property
    def block_delete(self) -> bool: ...


class SpindleView(Protocol):
    @property
    def spindle(self) -> SpindleState: ...


class SpindleDrive(SpindleView, Protocol):
    """The spindle as the motion switches it (a program's M3/M4/M5/S, the end of a run)."""

    def apply_spindle(self, sp: SpindleState) -> None: ...

    def stop_spindle(self) -> None: ...

    def set_program_lock(self, locked: bool) -> None: ...

    def spin_up_s(self, new: SpindleState) -> float: ...

    def restart_after_hold(self) -> float: ...

    def at_speed(self, now_s: float, until_s: float) -> bool: ...


class SignalValues(Protocol):
    """What a machine signal reads now (None: not wired, or the bus is down)."""

    def value(self, key: str) -> bool | None: ...


class Interlocks(Protocol):
    """What the machine's signals refuse now (the door open, the E-stop chain open): "" when
    nothing."""

    def refusal(self, action: str) -> str: ...


class MotionClaim(Protocol):
    """What must let go of the axes before a motion starts (the handwheel): "" when they are
    free, else why the motion must wait."""

    def claim(self, action: str) -> str: ...


class JogInterlocks(Protocol):
    """What the machine's signals allow a jog: the speed with the door open (None: closed), the
    limit switch an axis stands on (+1 / -1, 0: none), whether both its limit switches are
    wired."""

    def jog_speed_cap(self) -> float | None: ...

    def limit_side(self, axis: int) -> int: ...

    def has_limit_switches(self, axis: int) -> bool: ...


class OutputSwitch(Protocol):
    """The program's digital outputs (M62-M65) and coolant (M7-M9): "" when switched, else why
    not."""

    def set_output(self, number: int, on: bool) -> str: ...

    def set_coolant(self, switch: Coolant) -> str: ...


class ToolsView(Protocol):
    """The tool table and the tool in the spindle, read only."""

    @property
    def table(self) -> ToolTable: ...

    @property
    def in_spindle(self) -> int: ...


class ToolView(Protocol):
    """The tool table and the tool in the spindle."""

    @property
    def table(self) -> ToolTable: ...

    @property
    def in_spindle(self) -> int: ...

    def set_by_program(self, tool: Tool) -> None: ...

    def loaded_by_program(self, number: int) -> None: ...

    def set_tool_in_spindle(self, number: int) -> CommandResult: ...
