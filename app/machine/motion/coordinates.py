"""Part zero: the work offsets (G54-G59), the G-code parameters that programs leave (G92, the
XY rotation of G10 L2 R, G28/G30 positions), and from them the frame in force
(``planner.core.frames.Frame``): the one model by which machine positions are read as program
positions (the Work DRO) and offsets are set by touch-off.

Persisted at every change, as LinuxCNC writes its var file.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from app.machine.config import MachineConfig
from app.machine.errors import MachineError
from app.machine.infra.events import MachineEvents, PanelChannels
from app.machine.infra.persist import StateStore
from app.machine.model import CommandResult, Severity
from app.machine.motion.jobs import Job
from app.machine.motion.pauses import PauseHandlers
from app.machine.motion.timescale import PauseKind, PausePoint
from app.machine.ports import AlarmSink, PositionsView, Settings
from app.machine.state.gate import Action, guarded
from app.machine.state.states import StateMachine
from ethercat.worker import WorkerSnapshot
from planner.core.frames import PARAMETER_AXES, Frame, system_parameter_base
from planner.core.machine import WORK_OFFSET_NAMES, MachineSpec

__all__ = ["Coordinates"]

#: the G92/G52 offset is on (#5210) and its values (#5211 X ... #5219 W)
_G92_ON, _G92 = 5210, 5211


class Coordinates:
    """Work offsets, the active one, the persistent parameters and the frame in force
    (``controller.coordinates``)."""

    def __init__(self, settings: Settings, states: StateMachine, positions: PositionsView, store: StateStore,
                 alarms: AlarmSink, out: PanelChannels, events: MachineEvents, pauses: PauseHandlers) -> None:
        self._settings = settings
        self._states = states
        self._positions = positions
        self._store = store
        self._alarms = alarms
        self._out = out
        self._events = events
        self._offsets: dict[str, tuple[float, ...]] = {
            k: tuple(v) for k, v in settings.config.machine.work_offsets.items()}
        self.active_offset = "G54"
        # the persistent G-code parameters (G92, G28/G30 positions, G59.1-G59.3): programs start
        # from them and leave theirs (G10, G92, G28.1 ...) here; G54-G59 live in ``offsets``
        self.parameters: dict[int, float] = {}
        events.config_changed.connect(self._config_changed)
        pauses.on(PauseKind.OFFSETS, self._at_offsets)
        events.announce.connect(lambda: self._out.offsetsChanged.emit(dict(self._offsets),
                                                                      self.active_offset))

    @property
    def gate(self) -> StateMachine:
        return self._states

    @property
    def offsets(self) -> dict[str, tuple[float, ...]]:
        """The G54-G59 table (machine coordinates of each system's zero)."""
        return self._offsets

    def restore(self, offsets: dict[str, tuple[float, ...]] | None, parameters: dict[int, float],
                active: str | None) -> None:
        """What the state folder kept."""
        if offsets is not None:
            self._offsets.update({k: v for k, v in offsets.items() if k in WORK_OFFSET_NAMES})
        self.parameters = dict(parameters)
        if active in WORK_OFFSET_NAMES:
            self.active_offset = str(active)

    # ------------------------------------------------------------------ the model
    def _system(self) -> int:
        name = self.active_offset
        return WORK_OFFSET_NAMES.index(name) + 1 if name in WORK_OFFSET_NAMES else 1

    def rotation(self) -> float:
        """The XY rotation (degrees, G10 L2 R) of the work offset in use, from the parameters."""
        return float(self.parameters.get(system_parameter_base(self._system()) + 9, 0.0))

    def g92_offset(self) -> np.ndarray:
        """The G92/G52 offset per axis (#5211-, machine units) when #5210 says it is on."""
        axes = self._settings.config.axes
        p = self.parameters
        if not p.get(_G92_ON, 0.0):
            return np.zeros(len(axes))
        return np.array([p.get(_G92 + PARAMETER_AXES.index(a), 0.0) for a in axes])

    def frame(self) -> Frame:
        """The offsets in force at the panel: the active system with its rotation and G92."""
        axes = self._settings.config.axes
        zero = (0.0,) * len(axes)
        return Frame(tuple(axes), tuple(self._offsets.get(self.active_offset, zero)),
                     tuple(float(v) for v in self.g92_offset()), zero, self.rotation(), self._system())

    def work_pos(self) -> np.ndarray:
        """The actual position read in the frame in force (what a program reads as its position)."""
        return self.frame().to_program(self._positions.machine_pos())

    @property
    def work_position(self) -> tuple[float, ...]:
        """Actual position in the active work offset's coordinates."""
        return tuple(float(x) for x in self.work_pos())

    @property
    def work_offsets(self) -> dict[str, tuple[float, ...]]:
        """The G54-G59 table (a copy)."""
        return dict(self._offsets)

    @property
    def g92_in_force(self) -> tuple[float, ...] | None:
        """The G92/G52 offset per axis when it is on (a program left it), else None."""
        if not self.parameters.get(_G92_ON, 0.0):
            return None
        return tuple(float(v) for v in self.g92_offset())

    @property
    def xy_rotation_deg(self) -> float:
        """The XY rotation (G10 L2 R) of the active work offset, degrees."""
        return self.rotation()

    def machine(self) -> MachineSpec:
        """The machine as the planner reads it: the configuration with the work offsets in force."""
        return replace(self._settings.config.machine, work_offsets=dict(self._offsets))

    # ------------------------------------------------------------------ commands
    @guarded(Action.SET_WORK_OFFSET)
    def set_work_offset(self, name: str, values: dict[str, float] | tuple[float, ...]) -> CommandResult:
        """Set a G54-G59 offset (machine coordinates of part zero; a dict by axis name or one value
        per axis); persisted.
        """
        action = Action.SET_WORK_OFFSET
        name = name.upper()
        if name not in WORK_OFFSET_NAMES:
            return self._states.refuse(action, f"unknown work offset {name!r} (G54-G59)")
        cur = list(self._offsets.get(name, (0.0,) * len(self._settings.config.axes)))
        if isinstance(values, dict):
            for k, v in values.items():
                try:
                    cur[self._states.axis(k)] = float(v)
                except MachineError as exc:
                    return self._states.refuse(action, str(exc))
        else:
            if len(values) != len(cur):
                return self._states.refuse(action, f"{name} needs {len(cur)} values")
            cur = [float(v) for v in values]
        if not all(math.isfinite(v) for v in cur):
            return self._states.refuse(action, "offsets must be finite numbers")
        self._offsets[name] = tuple(cur)
        self._changed()
        return self._states.ok(action)

    @guarded(Action.SELECT_WORK_OFFSET)
    def select_work_offset(self, name: str) -> CommandResult:
        """Make G54-G59 the active work offset (MDI and work coordinates); persisted."""
        name = name.upper()
        if name not in WORK_OFFSET_NAMES:
            return self._states.refuse(Action.SELECT_WORK_OFFSET, f"unknown work offset {name!r} (G54-G59)")
        self.active_offset = name
        self._changed()
        return self._states.ok(Action.SELECT_WORK_OFFSET)

    @guarded(Action.TOUCH_OFF)
    def touch_off(self, axis: str | int, work_value: float = 0.0, offset: str | None = None) -> CommandResult:
        """Set part zero here: choose the offset (active unless named) so that the current
        position reads ``work_value`` in work coordinates on ``axis``.
        """
        try:
            i = self._states.axis(axis)
        except MachineError as exc:
            return self._states.refuse(Action.TOUCH_OFF, str(exc))
        name = (offset or self.active_offset).upper()
        if name not in WORK_OFFSET_NAMES:
            return self._states.refuse(Action.TOUCH_OFF, f"unknown work offset {name!r} (G54-G59)")
        cur = list(self._offsets.get(name, (0.0,) * len(self._settings.config.axes)))
        cur[i] = float(self._positions.machine_pos()[i]) - float(work_value)
        self._offsets[name] = tuple(cur)
        self._changed()
        return self._states.ok(Action.TOUCH_OFF)

    @guarded(Action.CLEAR_G92)
    def clear_g92(self) -> CommandResult:
        """G92.1 from the panel: the G92/G52 offset off and its parameters zero (what an earlier
        program left), persisted."""
        values = dict(self.parameters)
        for k in range(_G92_ON, _G92_ON + 10):
            values[k] = 0.0
        self.apply_parameters(values)
        return self._states.ok(Action.CLEAR_G92)

    def apply_parameters(self, values: dict[int, float]) -> None:
        """A program's G10/G92/G52/G28.1/G30.1 reached by the motion (or an MDI block): the
        parameters are kept, G54-G59 become the work offsets. Persisted at once, as LinuxCNC
        writes its var file."""
        self.parameters = dict(values)
        axes = self._settings.config.axes
        for k, name in enumerate(WORK_OFFSET_NAMES):
            base = system_parameter_base(k + 1)
            cur = list(self._offsets.get(name, (0.0,) * len(axes)))
            for i, axis in enumerate(axes):
                key = base + PARAMETER_AXES.index(axis)
                if key in values:
                    cur[i] = float(values[key])
            self._offsets[name] = tuple(cur)
        try:
            self._store.save_parameters(self.parameters)
        except OSError as exc:
            self._alarms.raise_alarm("persistence", f"cannot save the G-code parameters: {exc}",
                                     Severity.WARNING, "state_file")
        self._changed()

    def _at_offsets(self, job: Job, point: PausePoint, _snap: WorkerSnapshot) -> bool:
        """G10, G92, G52, G28.1 ... reached by the motion: the machine keeps them; it goes on."""
        sets = job.plan.program.parameter_sets
        if 0 <= int(point.value) < len(sets):
            self.apply_parameters(sets[int(point.value)])
        return True

    def _changed(self) -> None:
        try:
            self._store.save_offsets(self._offsets)
        except OSError as exc:
            self._alarms.raise_alarm("persistence", f"cannot save work offsets: {exc}", Severity.WARNING,
                                     "state_file")
        self._out.offsetsChanged.emit(dict(self._offsets), self.active_offset)
        self._events.coordinates_changed.emit()

    def _config_changed(self, cfg: MachineConfig, axes_changed: bool) -> None:
        if axes_changed:
            self._offsets = {k: tuple(v) for k, v in cfg.machine.work_offsets.items()}
            self._store.save_offsets(self._offsets)
