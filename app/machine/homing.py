"""Machine zero (homing: the drive's CiA 402 mode 6 or 'set here') and part zero (G54-G59 work
offsets, touch-off). Part of ``MachineController`` (``controller.pos``), which also owns the
positions and the homed flags.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

from app.machine.errors import MachineError
from app.machine.model import Activity, CommandResult, MachineState, Severity
from planner.machine import WORK_OFFSET_NAMES

if TYPE_CHECKING:
    from app.machine.controller import MachineController

__all__ = ["Positions"]


class Positions:
    """Homing, machine zero, work offsets, touch-off.

    A part of ``MachineController`` (``controller.pos``): it owns the state set up in
    ``__init__`` and reaches the other parts through the facade ``m``.
    """

    def __init__(self, m: MachineController) -> None:
        self.m = m
        n = len(m.config.axes)
        self.raw_pos = np.zeros(n)
        self.ref_raw = np.zeros(n)
        self.home_offset = np.zeros(n)
        self.homed = [False] * n
        self.active_offset = "G54"
        self.offsets: dict[str, tuple[float, ...]] = {
            k: tuple(v) for k, v in m.config.machine.work_offsets.items()
        }
        self.homing_queue: list[int] = []
        self.homing_axis = -1
        # the persistent G-code parameters (G92, G28/G30 positions, G59.1-G59.3): programs start
        # from them and leave theirs (G10, G92, G28.1 ...) here; G54-G59 live in ``offsets``
        self.parameters: dict[int, float] = {}

    def home_axis(self, axis: str | int) -> CommandResult:
        """Home one axis by the configured method: "drive" (CiA 402 homing mode 6 with
        ``homing.drive_method``, via the worker) or "set_here" (current position = machine zero).
        """
        try:
            i = self.m.states.axis(axis)
        except MachineError as exc:
            return self.m.states.refuse("home", str(exc))
        return self._home([i])

    def home_all(self) -> CommandResult:
        """Home every axis (Z first) by the configured method."""
        order = list(range(len(self.m.config.axes)))
        if "Z" in self.m.config.axes:  # Z first: clear the part before the others move
            z = self.m.config.axes.index("Z")
            order.remove(z)
            order.insert(0, z)
        return self._home(order)

    def _home(self, axes: list[int]) -> CommandResult:
        why = self.m.states.refusal("home")
        if why:
            return self.m.states.refuse("home", why)
        if self.m.config.homing.method == "set_here":
            return self.set_machine_zero_here(None if len(axes) == len(self.m.config.axes) else axes[0])
        self.homing_queue = list(axes)
        self.m.states.set_state(
            MachineState.HOMING, "homing " + " ".join(self.m.config.axes[i] for i in axes)
        )
        self.m.states.set_activity(Activity.HOMING)
        self._next_homing()
        return self.m.states.ok("home")

    def _next_homing(self) -> None:
        if not self.homing_queue:
            self.homing_axis = -1
            self.m.conn.persist_state()
            if self.m.states.state is MachineState.HOMING:
                self.m.states.set_state(MachineState.IDLE, "homed")
            return
        i = self.homing_queue.pop(0)
        self.homing_axis = i
        self.homed[i] = False
        self.m.homedChanged.emit(tuple(self.homed))
        try:
            with self.m._lock:
                self.m.worker.home(i, self.m.config.homing.drive_method)
        except Exception as exc:  # noqa: BLE001
            self.homing_queue.clear()
            self.homing_axis = -1
            self.m.alarm_log.raise_alarm(
                f"drive {self.m.config.axes[i]}", f"homing refused: {exc}", Severity.STOP, "homing_error"
            )
            self.m.states.set_state(MachineState.ALARM, f"homing refused: {exc}")

    def poll_homing(self, snap: Any) -> None:
        from ethercat.worker import HomingState, WorkerState

        i = self.homing_axis
        if i < 0 or self.m.states.state is not MachineState.HOMING:
            return
        if snap.homing[i] is HomingState.DONE and snap.state is WorkerState.ENABLED:
            self.home_offset[i] = 0.0  # the drive's own zero is machine zero
            self.homed[i] = True
            self.m.homedChanged.emit(tuple(self.homed))
            self._next_homing()

    def set_machine_zero_here(self, axis: str | int | None = None) -> CommandResult:
        """Declare the current position machine zero for one axis (all when None); homed; persisted."""
        if self.m.states.state not in (MachineState.IDLE,):
            return self.m.states.refuse(
                "set_machine_zero_here", f"machine is {self.m.states.state.label.lower()}"
            )
        try:
            idx = list(range(len(self.m.config.axes))) if axis is None else [self.m.states.axis(axis)]
        except MachineError as exc:
            return self.m.states.refuse("set_machine_zero_here", str(exc))
        for i in idx:
            self.home_offset[i] = self.raw_pos[i]
            self.homed[i] = True
        self.m.conn.persist_state()
        self.m.homedChanged.emit(tuple(self.homed))
        self.m.poller.last_emit_pos = ()
        self.m.positionChanged.emit(
            tuple(float(x) for x in self.m.states.machine_pos()),
            tuple(float(x) for x in self.m.states.work_pos()),
        )
        return self.m.states.ok("set_machine_zero_here")

    def set_work_offset(self, name: str, values: dict[str, float] | tuple[float, ...]) -> CommandResult:
        """Set a G54-G59 offset (machine coordinates of part zero; a dict by axis name or one value
        per axis); persisted.
        """
        why = self.m.states.refusal("set_work_offset")
        if why:
            return self.m.states.refuse("set_work_offset", why)
        name = name.upper()
        if name not in WORK_OFFSET_NAMES:
            return self.m.states.refuse("set_work_offset", f"unknown work offset {name!r} (G54-G59)")
        cur = list(self.offsets.get(name, (0.0,) * len(self.m.config.axes)))
        if isinstance(values, dict):
            for k, v in values.items():
                try:
                    cur[self.m.states.axis(k)] = float(v)
                except MachineError as exc:
                    return self.m.states.refuse("set_work_offset", str(exc))
        else:
            if len(values) != len(cur):
                return self.m.states.refuse("set_work_offset", f"{name} needs {len(cur)} values")
            cur = [float(v) for v in values]
        if not all(math.isfinite(v) for v in cur):
            return self.m.states.refuse("set_work_offset", "offsets must be finite numbers")
        self.offsets[name] = tuple(cur)
        self._offsets_changed()
        return self.m.states.ok("set_work_offset")

    def rotation(self) -> float:
        """The XY rotation (degrees, G10 L2 R) of the work offset in use, from the parameters."""
        from planner.interpreter import system_base

        names = WORK_OFFSET_NAMES
        code = 540 + 10 * names.index(self.active_offset) if self.active_offset in names else 540
        return float(self.parameters.get(system_base(code) + 9, 0.0))

    def g92_offset(self) -> np.ndarray:
        """The G92/G52 offset per axis (#5211-, machine units) when #5210 says it is on."""
        n = len(self.raw_pos)
        p = self.parameters
        if not p.get(5210, 0.0):
            return np.zeros(n)
        return np.array([p.get(5211 + "XYZABCUVW".index(a), 0.0) for a in self.m.config.axes])

    def clear_g92(self) -> CommandResult:
        """G92.1 from the panel: the G92/G52 offset off and its parameters zero (what an earlier
        program left), persisted."""
        why = self.m.states.refusal("set_work_offset")
        if why:
            return self.m.states.refuse("clear_g92", why)
        values = dict(self.parameters)
        for k in range(5210, 5220):
            values[k] = 0.0
        self.apply_parameters(values)
        return self.m.states.ok("clear_g92")

    def apply_parameters(self, values: dict[int, float]) -> None:
        """A program's G10/G92/G52/G28.1/G30.1 reached by the motion (or an MDI block): the
        parameters are kept, G54-G59 become the work offsets. Persisted at once, as LinuxCNC
        writes its var file."""
        from planner.interpreter import system_base

        self.parameters = dict(values)
        names = self.m.config.axes
        for k, name in enumerate(WORK_OFFSET_NAMES):
            base = system_base(540 + 10 * k)
            cur = list(self.offsets.get(name, (0.0,) * len(names)))
            for i, axis in enumerate(names):
                key = base + "XYZABCUVW".index(axis)
                if key in values:
                    cur[i] = float(values[key])
            self.offsets[name] = tuple(cur)
        try:
            self.m.conn.store.save_parameters(self.parameters)
        except OSError as exc:
            self.m.alarm_log.raise_alarm(
                "persistence", f"cannot save the G-code parameters: {exc}", Severity.WARNING, "state_file")
        self._offsets_changed()

    def _offsets_changed(self) -> None:
        try:
            self.m.conn.store.save_offsets(self.offsets)
        except OSError as exc:
            self.m.alarm_log.raise_alarm(
                "persistence", f"cannot save work offsets: {exc}", Severity.WARNING, "state_file"
            )
        self.m.conn.persist_state()
        self.m.offsetsChanged.emit(dict(self.offsets), self.active_offset)
        self.m.poller.last_emit_pos = ()
        self.m.positionChanged.emit(
            tuple(float(x) for x in self.m.states.machine_pos()),
            tuple(float(x) for x in self.m.states.work_pos()),
        )

    def select_work_offset(self, name: str) -> CommandResult:
        """Make G54-G59 the active work offset (MDI and work coordinates); persisted."""
        why = self.m.states.refusal("select_work_offset")
        if why:
            return self.m.states.refuse("select_work_offset", why)
        name = name.upper()
        if name not in WORK_OFFSET_NAMES:
            return self.m.states.refuse("select_work_offset", f"unknown work offset {name!r} (G54-G59)")
        self.active_offset = name
        self._offsets_changed()
        return self.m.states.ok("select_work_offset")

    def touch_off(self, axis: str | int, work_value: float = 0.0, offset: str | None = None) -> CommandResult:
        """Set part zero here: choose the offset (active unless named) so that the current
        position reads ``work_value`` in work coordinates on ``axis``.
        """
        why = self.m.states.refusal("touch_off")
        if why:
            return self.m.states.refuse("touch_off", why)
        try:
            i = self.m.states.axis(axis)
        except MachineError as exc:
            return self.m.states.refuse("touch_off", str(exc))
        name = (offset or self.active_offset).upper()
        if name not in WORK_OFFSET_NAMES:
            return self.m.states.refuse("touch_off", f"unknown work offset {name!r} (G54-G59)")
        cur = list(self.offsets.get(name, (0.0,) * len(self.m.config.axes)))
        cur[i] = float(self.m.states.machine_pos()[i]) - float(work_value)
        self.offsets[name] = tuple(cur)
        self._offsets_changed()
        return self.m.states.ok("touch_off")
