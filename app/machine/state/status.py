"""The one status snapshot: the machine's state, program, line, progress, overrides, spindle,
tool, positions in both frames with the offsets in force, and alarms, in one immutable object.

``current()`` makes one now. Whenever the panel is told anything, the board marks itself and
publishes a new snapshot once the controller's thread is free (every change of one event
loop turn in one snapshot; at most one a poll while the axes move), keeping it as ``latest``:
a reader in another thread (an OPC UA server) takes ``latest``, an immutable object, and never
waits for the controller.
"""

from __future__ import annotations

import time
from typing import Protocol

from PySide6.QtCore import QObject, QTimer

from app.machine.infra.events import Channel, PanelChannels
from app.machine.model import BusStatus, ControllerSnapshot, RunSummary, SpindleState, TrackingReport
from app.machine.ports import (
    CoordinatesView,
    LoaderView,
    PositionsView,
    RunModes,
    Settings,
    SpindleView,
    ToolView,
)
from app.machine.state.alarms import AlarmLog
from app.machine.state.states import StateMachine

__all__ = ["StatusBoard"]


class _Motion(Protocol):
    @property
    def line(self) -> int: ...

    @property
    def progress(self) -> tuple[float, float]: ...

    @property
    def tracking(self) -> TrackingReport: ...

    @property
    def last_summary(self) -> RunSummary | None: ...


class _Loading(LoaderView, Protocol):
    @property
    def loading(self) -> bool: ...


class _Bus(Protocol):
    @property
    def bus_status(self) -> BusStatus: ...

    @property
    def speed(self) -> float: ...


class _Resume(Protocol):
    @property
    def resume_line(self) -> int: ...


class StatusBoard:
    """Makes and publishes the status snapshot (``controller.status``)."""

    def __init__(self, settings: Settings, states: StateMachine, positions: PositionsView,
                 coordinates: CoordinatesView, motion: _Motion, modes: RunModes, resume: _Resume,
                 loader: _Loading, spindle: SpindleView, tools: ToolView, alarms: AlarmLog, bus: _Bus,
                 out: PanelChannels, qt_parent: QObject) -> None:
        self._settings = settings
        self._states = states
        self._positions = positions
        self._coordinates = coordinates
        self._motion = motion
        self._modes = modes
        self._resume = resume
        self._loader = loader
        self._spindle = spindle
        self._tools = tools
        self._alarms = alarms
        self._bus = bus
        self._sequence = 0
        # publishes once the controller's thread is free; a child of the controller's object,
        # so it never fires after the controller is gone
        self._timer = QTimer(qt_parent)
        self._timer.setSingleShot(True)
        self._timer.setInterval(0)
        self._timer.timeout.connect(self.publish)
        #: the newest snapshot published (None before the first)
        self.latest: ControllerSnapshot | None = None
        #: each snapshot as it is published
        self.published: Channel[ControllerSnapshot] = Channel()
        for name in PanelChannels.names():
            getattr(out, name).connect(self._mark)

    def _mark(self, *_told: object) -> None:
        if not self._timer.isActive():
            self._timer.start()

    def publish(self) -> ControllerSnapshot:
        """A new snapshot, kept as ``latest`` and told to ``published``."""
        self._timer.stop()
        self._sequence += 1
        snap = self.current()
        self.latest = snap
        self.published.emit(snap)
        return snap

    def current(self) -> ControllerSnapshot:
        """The status now."""
        states, modes, motion = self._states, self._modes, self._motion
        frame = self._coordinates.frame()
        machine = self._positions.machine_pos()
        info = self._loader.program_info
        spindle: SpindleState = self._spindle.spindle
        return ControllerSnapshot(
            state=states.state,
            activity=states.activity,
            axes=self._settings.config.axes,
            machine_pos=tuple(float(x) for x in machine),
            work_pos=tuple(float(x) for x in frame.to_program(machine)),
            homed=self._positions.homed,
            active_offset=self._coordinates.active_offset,
            line=motion.line,
            progress=motion.progress[0],
            remaining_s=motion.progress[1],
            path_speed_mm_s=self._bus.speed,
            feed_override_pct=modes.feed_pct,
            rapid_override_pct=modes.rapid_pct,
            single_block=modes.single_block,
            optional_stop=modes.optional_stop,
            block_delete=modes.block_delete,
            spindle=spindle,
            alarms=self._alarms.all,
            bus=self._bus.bus_status,
            state_reason=states.state_reason,
            hold_kind=states.hold_kind,
            prompt=states.prompt,
            reference_pos=tuple(float(x) for x in self._positions.reference_pos()),
            frame=frame,
            tool_in_spindle=self._tools.in_spindle,
            program_name=info.name if info is not None else "",
            program_path=info.path if info is not None else "",
            program_lines=info.line_count if info is not None else 0,
            estimated_cycle_s=info.cycle_time_s if info is not None else 0.0,
            loading=self._loader.loading,
            resume_line=self._resume.resume_line,
            last_run=motion.last_summary,
            time_s=time.time(),
            sequence=self._sequence,
        )
