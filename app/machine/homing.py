"""Machine zero (homing: the drive's CiA 402 mode 6 or 'set here') and part zero (G54-G59 work
offsets, touch-off). Part of ``MachineController`` (mixed in).
"""

from __future__ import annotations

import math
from typing import Any

from app.machine.errors import MachineError
from app.machine.model import Activity, CommandResult, MachineState, Severity
from planner.machine import WORK_OFFSET_NAMES

__all__ = ["HomingMixin"]


class HomingMixin:
    """Homing, machine zero, work offsets, touch-off.

    Mixed into ``MachineController``, which holds the state.
    """

    def home_axis(self, axis: str | int) -> CommandResult:
        """Home one axis by the configured method: "drive" (CiA 402 homing mode 6 with
        ``homing.drive_method``, via the worker) or "set_here" (current position = machine zero).
        """
        try:
            i = self._axis(axis)
        except MachineError as exc:
            return self._refuse("home", str(exc))
        return self._home([i])

    def home_all(self) -> CommandResult:
        """Home every axis (Z first) by the configured method."""
        order = list(range(len(self._cfg.axes)))
        if "Z" in self._cfg.axes:  # Z first: clear the part before the others move
            z = self._cfg.axes.index("Z")
            order.remove(z)
            order.insert(0, z)
        return self._home(order)

    def _home(self, axes: list[int]) -> CommandResult:
        why = self.refusal("home")
        if why:
            return self._refuse("home", why)
        if self._cfg.homing.method == "set_here":
            return self.set_machine_zero_here(None if len(axes) == len(self._cfg.axes) else axes[0])
        self._homing_queue = list(axes)
        self._set_state(MachineState.HOMING, "homing " + " ".join(self._cfg.axes[i] for i in axes))
        self._set_activity(Activity.HOMING)
        self._next_homing()
        return self._ok("home")

    def _next_homing(self) -> None:
        if not self._homing_queue:
            self._homing_axis = -1
            self._persist_state()
            if self._state is MachineState.HOMING:
                self._set_state(MachineState.IDLE, "homed")
            return
        i = self._homing_queue.pop(0)
        self._homing_axis = i
        self._homed[i] = False
        self.homedChanged.emit(tuple(self._homed))
        try:
            with self._lock:
                self._worker.home(i, self._cfg.homing.drive_method)
        except Exception as exc:  # noqa: BLE001
            self._homing_queue.clear()
            self._homing_axis = -1
            self._raise_alarm(
                f"drive {self._cfg.axes[i]}", f"homing refused: {exc}", Severity.STOP, "homing_error"
            )
            self._set_state(MachineState.ALARM, f"homing refused: {exc}")

    def _poll_homing(self, snap: Any) -> None:
        from ethercat.worker import HomingState, WorkerState

        i = self._homing_axis
        if i < 0 or self._state is not MachineState.HOMING:
            return
        if snap.homing[i] is HomingState.DONE and snap.state is WorkerState.ENABLED:
            self._home_offset[i] = 0.0  # the drive's own zero is machine zero
            self._homed[i] = True
            self.homedChanged.emit(tuple(self._homed))
            self._next_homing()

    def set_machine_zero_here(self, axis: str | int | None = None) -> CommandResult:
        """Declare the current position machine zero for one axis (all when None); homed; persisted."""
        if self._state not in (MachineState.IDLE,):
            return self._refuse("set_machine_zero_here", f"machine is {self._state.label.lower()}")
        try:
            idx = list(range(len(self._cfg.axes))) if axis is None else [self._axis(axis)]
        except MachineError as exc:
            return self._refuse("set_machine_zero_here", str(exc))
        for i in idx:
            self._home_offset[i] = self._raw_pos[i]
            self._homed[i] = True
        self._persist_state()
        self.homedChanged.emit(tuple(self._homed))
        self._last_emit_pos = ()
        self.positionChanged.emit(
            tuple(float(x) for x in self._machine_pos()), tuple(float(x) for x in self._work_pos())
        )
        return self._ok("set_machine_zero_here")

    def set_work_offset(self, name: str, values: dict[str, float] | tuple[float, ...]) -> CommandResult:
        """Set a G54-G59 offset (machine coordinates of part zero; a dict by axis name or one value
        per axis); persisted.
        """
        why = self.refusal("set_work_offset")
        if why:
            return self._refuse("set_work_offset", why)
        name = name.upper()
        if name not in WORK_OFFSET_NAMES:
            return self._refuse("set_work_offset", f"unknown work offset {name!r} (G54-G59)")
        cur = list(self._offsets.get(name, (0.0,) * len(self._cfg.axes)))
        if isinstance(values, dict):
            for k, v in values.items():
                try:
                    cur[self._axis(k)] = float(v)
                except MachineError as exc:
                    return self._refuse("set_work_offset", str(exc))
        else:
            if len(values) != len(cur):
                return self._refuse("set_work_offset", f"{name} needs {len(cur)} values")
            cur = [float(v) for v in values]
        if not all(math.isfinite(v) for v in cur):
            return self._refuse("set_work_offset", "offsets must be finite numbers")
        self._offsets[name] = tuple(cur)
        self._offsets_changed()
        return self._ok("set_work_offset")

    def _offsets_changed(self) -> None:
        try:
            self._store.save_offsets(self._offsets)
        except OSError as exc:
            self._raise_alarm(
                "persistence", f"cannot save work offsets: {exc}", Severity.WARNING, "state_file"
            )
        self._persist_state()
        self.offsetsChanged.emit(dict(self._offsets), self._active_offset)
        self._last_emit_pos = ()
        self.positionChanged.emit(
            tuple(float(x) for x in self._machine_pos()), tuple(float(x) for x in self._work_pos())
        )

    def select_work_offset(self, name: str) -> CommandResult:
        """Make G54-G59 the active work offset (MDI and work coordinates); persisted."""
        why = self.refusal("select_work_offset")
        if why:
            return self._refuse("select_work_offset", why)
        name = name.upper()
        if name not in WORK_OFFSET_NAMES:
            return self._refuse("select_work_offset", f"unknown work offset {name!r} (G54-G59)")
        self._active_offset = name
        self._offsets_changed()
        return self._ok("select_work_offset")

    def touch_off(self, axis: str | int, work_value: float = 0.0, offset: str | None = None) -> CommandResult:
        """Set part zero here: choose the offset (active unless named) so that the current
        position reads ``work_value`` in work coordinates on ``axis``.
        """
        why = self.refusal("touch_off")
        if why:
            return self._refuse("touch_off", why)
        try:
            i = self._axis(axis)
        except MachineError as exc:
            return self._refuse("touch_off", str(exc))
        name = (offset or self._active_offset).upper()
        if name not in WORK_OFFSET_NAMES:
            return self._refuse("touch_off", f"unknown work offset {name!r} (G54-G59)")
        cur = list(self._offsets.get(name, (0.0,) * len(self._cfg.axes)))
        cur[i] = float(self._machine_pos()[i]) - float(work_value)
        self._offsets[name] = tuple(cur)
        self._offsets_changed()
        return self._ok("touch_off")
