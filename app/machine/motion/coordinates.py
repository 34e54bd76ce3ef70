"""Part zero: the work offsets (G54-G59), the G-code parameters that programs leave (G92, the
XY rotation of G10 L2 R, G28/G30 positions), the tool length offset in force, and from them the
frame in force (``planner.core.frames.Frame``): the one model by which machine positions are
read as program positions (the Work DRO: the tool tip in the active system) and offsets are set
by touch-off (LinuxCNC's G10 L20).

The tool length offset in force at the panel follows the tool in the spindle (G43 of that tool:
a tool change or a new length in the table moves it) until a program or MDI block leaves
another one (G49, G43.1, G43.2, G43 H of another tool), which stays as LinuxCNC keeps it; the
next program starts from it. While a program runs, the frame is the program's own at the move
the drives execute.

Work offsets and parameters are persisted at every change, as LinuxCNC writes its var file.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

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
from planner.core.program import Program, TableRef
from planner.gcode.codes import G

__all__ = ["Coordinates"]

#: the G92/G52 offset is on (#5210) and its values (#5211 X ... #5219 W)
_G92_ON, _G92 = 5210, 5211


@dataclass(frozen=True, slots=True)
class ToolOffset:
    """The tool length offset in force: its code (G43, G43.1, G43.2, G49), its value per axis
    (machine units), and whether it follows the tool in the spindle (G43 of that tool)."""

    code: G
    values: tuple[float, ...]
    follows_spindle: bool

    @property
    def text(self) -> str:
        return str(self.code)


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
        n = len(settings.config.axes)
        self._spindle_tool: tuple[int, tuple[float, ...]] = (0, (0.0,) * n)
        self.tool_offset = ToolOffset(G.G43, (0.0,) * n, True)
        # while a program runs: its frame at the move the drives execute (the DRO reads it)
        self._program_frame: Frame | None = None
        events.config_changed.connect(self._config_changed)
        pauses.on(PauseKind.OFFSETS, self._at_offsets)
        events.announce.connect(lambda: self._out.offsetsChanged.emit(dict(self._offsets),
                                                                      self.active_offset))

    @property
    def gate(self) -> StateMachine:
        return self._states

    @property
    def offsets(self) -> dict[str, tuple[float, ...]]:
        """The G54-G59.3 table (machine coordinates of each system's zero)."""
        return self._offsets

    def restore(self, offsets: dict[str, tuple[float, ...]] | None, parameters: dict[int, float],
                active: str | None) -> None:
        """What the state folder kept."""
        if offsets is not None:
            self._offsets.update({k: v for k, v in offsets.items() if k in WORK_OFFSET_NAMES})
        self.parameters = dict(parameters)
        # a system the kept table lacks (G59.1-G59.3 of a folder from before they were shown)
        # is what the kept parameters say: a program's G10 L2 P7 is never undone by a zero
        axes = self._settings.config.axes
        for k, name in enumerate(WORK_OFFSET_NAMES):
            if offsets is not None and name in offsets:
                continue
            keys = [system_parameter_base(k + 1) + PARAMETER_AXES.index(a) for a in axes]
            if any(key in self.parameters for key in keys):
                base = self._offsets.get(name, (0.0,) * len(axes))
                self._offsets[name] = tuple(float(self.parameters.get(key, base[i]))
                                            for i, key in enumerate(keys))
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
        """The offsets in force: while a program runs, the program's own at the move the drives
        execute; else the panel's (the active system with its rotation, G92 and the tool length
        offset in force)."""
        running = self._program_frame
        if running is not None:
            return running
        return self.panel_frame()

    def panel_frame(self) -> Frame:
        """The offsets in force at the panel (touch-off, MDI, jog, the next program's start)."""
        axes = self._settings.config.axes
        zero = (0.0,) * len(axes)
        tlo = self.tool_offset
        return Frame(tuple(axes), tuple(self._offsets.get(self.active_offset, zero)),
                     tuple(float(v) for v in self.g92_offset()), tlo.values, self.rotation(), self._system(),
                     self._spindle_tool[0] if tlo.follows_spindle else 0)

    def work_pos(self) -> np.ndarray:
        """The actual position read in the frame in force: the tool tip in program coordinates
        (what a program reads as its position, LinuxCNC's relative DRO)."""
        return self.frame().to_program(self._positions.machine_pos())

    # ------------------------------------------------------------------ the tool length offset
    def set_spindle_tool(self, number: int, offsets: tuple[float, ...]) -> None:
        """The tool in the spindle and its offsets from the table (a change, a new length):
        the offset in force follows it when it is G43 of the tool in the spindle."""
        offsets = tuple(float(v) for v in offsets)
        if self._spindle_tool == (number, offsets):
            return
        self._spindle_tool = (number, offsets)
        if self.tool_offset.follows_spindle:
            self.tool_offset = ToolOffset(G.G43, offsets, True)
            self._events.coordinates_changed.emit()

    def start_offset(self) -> tuple[int, tuple[float, ...]]:
        """The tool length offset a program starts from (``parse_program(tool_offset=)``)."""
        return int(self.tool_offset.code), self.tool_offset.values

    def follow_program(self, frame: Frame | None) -> None:
        """While a program runs: its frame at the executing move (None: the panel's again)."""
        if frame != self._program_frame:
            self._program_frame = frame
            self._events.coordinates_changed.emit()

    def program_left(self, program: Program, move: int) -> None:
        """A program or MDI block ended with move ``move`` the last to run (``len(moves)``: it
        ran to its end): the tool length offset it left stays in force (LinuxCNC keeps it);
        G43 of the tool in the spindle follows that tool again."""
        frame = program.frame_at(move)
        codes = program.modal_at_move(move).split()
        code = next((G[c.replace(".", "_")] for c in codes if c in ("G43", "G43.1", "G43.2", "G49")), None)
        self._program_frame = None
        if code is not None:
            values = tuple(float(v) for v in frame.tool)
            follows = code is G.G43 and values == self._spindle_tool[1]
            self.tool_offset = ToolOffset(G.G49 if code is G.G49 else code, values, follows)
        self._events.coordinates_changed.emit()

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
    def _zero_outside_travel(self, name: str, g5x: tuple[float, ...], changed: set[int]) -> str:
        """Why system ``name`` with origin ``g5x`` cannot be stored: its programmed zero (the tool
        tip at 0 with the tool length offset in force) outside the travel of a changed axis;
        "" when it can."""
        cfg = self._settings.config
        frame = replace(self.panel_frame(), g5x=g5x, g92=(0.0,) * len(g5x), rotation_deg=0.0)
        zero = frame.to_machine(np.zeros(len(g5x)))
        for k in sorted(changed):
            ax = cfg.machine.axes[k]
            if not ax.min_pos - 1e-9 <= float(zero[k]) <= ax.max_pos + 1e-9:
                tool = " with the tool length offset in force" if frame.tool[k] else ""
                return (f"{name} {ax.name} zero would be at machine {ax.name}{float(zero[k]):.4f}{tool}, "
                        f"outside the travel {ax.min_pos:g} .. {ax.max_pos:g} {ax.unit}")
        return ""

    @guarded(Action.SET_WORK_OFFSET)
    def set_work_offset(self, name: str, values: dict[str, float] | tuple[float, ...]) -> CommandResult:
        """Set a G54-G59.3 offset (machine coordinates of part zero; a dict by axis name or one value
        per axis); persisted. Refused when a value is not a number or puts the system's zero
        outside the travel.
        """
        action = Action.SET_WORK_OFFSET
        name = name.upper()
        if name not in WORK_OFFSET_NAMES:
            return self._states.refuse(action, f"unknown work offset {name!r} (G54-G59.3)")
        old = tuple(self._offsets.get(name, (0.0,) * len(self._settings.config.axes)))
        cur = list(old)
        try:
            if isinstance(values, dict):
                for k, v in values.items():
                    cur[self._states.axis(k)] = float(v)
            else:
                if len(values) != len(cur):
                    return self._states.refuse(action, f"{name} needs {len(cur)} values")
                cur = [float(v) for v in values]
        except MachineError as exc:
            return self._states.refuse(action, str(exc))
        except (TypeError, ValueError):
            return self._states.refuse(action, f"{name}: not a number")
        if not all(math.isfinite(v) for v in cur):
            return self._states.refuse(action, f"{name}: not a number (offsets are finite numbers)")
        new = tuple(v + 0.0 for v in cur)          # -0 is 0
        why = self._zero_outside_travel(name, new, {k for k in range(len(new)) if new[k] != old[k]})
        if why:
            return self._states.refuse(action, why)
        self._offsets[name] = new
        self._changed()
        return self._states.ok(action)

    def set_work_rotation(self, name: str, degrees: float) -> CommandResult:
        """The XY rotation of a coordinate system (G10 L2 R: degrees about Z, parameter base + 9);
        persisted with the parameters, as a program's G10 L2 R sets it."""
        action = Action.SET_WORK_OFFSET
        why = self._states.refusal(action)
        if why:
            return self._states.refuse(action, why)
        name = name.upper()
        if name not in WORK_OFFSET_NAMES:
            return self._states.refuse(action, f"unknown work offset {name!r} (G54-G59.3)")
        try:
            value = float(degrees) + 0.0
        except (TypeError, ValueError):
            return self._states.refuse(action, f"{name} rotation: not a number")
        if not math.isfinite(value) or abs(value) > 360.0:
            return self._states.refuse(action, f"{name} rotation: a number of degrees within -360 .. 360")
        # the rotation's parameter alone: the table's origins are the panel's, whatever older
        # values the parameters hold for them
        self.parameters[system_parameter_base(WORK_OFFSET_NAMES.index(name) + 1) + 9] = value
        self._parameters_changed()
        return self._states.ok(action)

    def rotation_of(self, name: str) -> float:
        """The XY rotation (degrees) of coordinate system ``name``."""
        system = WORK_OFFSET_NAMES.index(name) + 1 if name in WORK_OFFSET_NAMES else 1
        return float(self.parameters.get(system_parameter_base(system) + 9, 0.0))

    @guarded(Action.SELECT_WORK_OFFSET)
    def select_work_offset(self, name: str) -> CommandResult:
        """Make one of G54-G59.3 the active work offset (MDI and work coordinates); persisted."""
        name = name.upper()
        if name not in WORK_OFFSET_NAMES:
            return self._states.refuse(Action.SELECT_WORK_OFFSET, f"unknown work offset {name!r} (G54-G59.3)")
        self.active_offset = name
        self._changed()
        return self._states.ok(Action.SELECT_WORK_OFFSET)

    @guarded(Action.TOUCH_OFF)
    def touch_off(self, axis: str | int, work_value: float = 0.0, offset: str | None = None) -> CommandResult:
        """LinuxCNC's G10 L20: set the system (the active one unless named) so that the tool tip
        here reads ``work_value`` on ``axis``, the tool length offset in force and G92 included;
        in a rotated system X and Y move together. Refused when the value is not a number or
        the system's zero would lie outside the travel.
        """
        action = Action.TOUCH_OFF
        try:
            i = self._states.axis(axis)
        except MachineError as exc:
            return self._states.refuse(action, str(exc))
        name = (offset or self.active_offset).upper()
        if name not in WORK_OFFSET_NAMES:
            return self._states.refuse(action, f"unknown work offset {name!r} (G54-G59.3)")
        try:
            value = float(work_value) + 0.0          # -0 is 0
        except (TypeError, ValueError):
            return self._states.refuse(action, f"touch off {self._settings.config.axes[i]}: not a number")
        if not math.isfinite(value):
            return self._states.refuse(action, f"touch off {self._settings.config.axes[i]}: not a number")
        system = WORK_OFFSET_NAMES.index(name) + 1
        zero = (0.0,) * len(self._settings.config.axes)
        frame = replace(self.panel_frame(), g5x=tuple(self._offsets.get(name, zero)), system=system,
                        rotation_deg=float(self.parameters.get(system_parameter_base(system) + 9, 0.0)))
        new = tuple(v + 0.0 for v in frame.origin_for(self._positions.machine_pos(), i, value))
        why = self._zero_outside_travel(name, new, {k for k in range(len(new)) if new[k] != frame.g5x[k]})
        if why:
            return self._states.refuse(action, why)
        self._offsets[name] = new
        self._changed()
        return self._states.ok(action)

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
        self._parameters_changed()

    def _parameters_changed(self) -> None:
        """The parameters kept at once, as LinuxCNC writes its var file, then the table."""
        try:
            self._store.save_parameters(self.parameters)
        except OSError as exc:
            self._alarms.raise_alarm("persistence", f"cannot save the G-code parameters: {exc}",
                                     Severity.WARNING, "state_file")
        self._changed()

    def _at_offsets(self, job: Job, point: PausePoint, _snap: WorkerSnapshot) -> bool:
        """G10, G92, G52, G28.1 ... reached by the motion: the machine keeps them; it goes on."""
        sets = job.plan.program.parameter_sets
        index = point.payload_as(TableRef).index
        if 0 <= index < len(sets):
            self.apply_parameters(sets[index])
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
