"""The handwheel (MPG): which axis and step it has, and when it may move the axis.

The wheel's counts move the axis in the 1 ms loop itself (``ethercat.worker.handwheel``:
jerk-limited, within the axis' limits and soft limits, in position or velocity mode). This
part decides, at every poll, whether the loop should follow the wheel, and with what:

- an axis is given to it: by the panel (``select_handwheel``, ``set_handwheel_step``), or by
  the pendant's selector when the signals ``jog_enable_<axis>`` are wired (then the selector
  is the truth and the panel's buttons only show it; no axis, or two, is off);
- it is live only while the machine is IDLE with its drives enabled, on a homed axis standing
  within its soft limits, and with the door closed (open: at the setup speed
  ``[interlocks] door_open_jog_mm_s``, or not at all when that is 0);
- every other motion first takes the axis from the wheel (``claim``): refused while the axis
  still moves; a jog gives it back when the machine is IDLE again, any other motion (MDI, a
  program, homing, probing) leaves the wheel off, to be selected again. The positions are
  read again before the motion is planned, so it starts where the wheel left the axis;
- a wheel the loop stopped by itself (its counter jumped, its terminal stopped answering,
  E-stop, a fault) is off until selected again, as the loop's alarm says.

A simulated machine's wheel is turned by ``turn_handwheel`` (the scenario runner's ``mpg``):
the counts reach the simulated encoder terminal a few detents per poll, as a hand turns it.
"""

from __future__ import annotations

import math
import time

from app.machine.devices.signals import MachineSignals
from app.machine.infra.drives import DriveLink
from app.machine.infra.events import MachineEvents, PanelChannels
from app.machine.model import HANDWHEEL_SCALES, CommandResult, HandwheelStatus, MachineState
from app.machine.ports import PositionsView, Settings
from app.machine.state.gate import Action, Answers
from app.machine.wiring import WheelMode
from ethercat.worker import WheelState, WorkerSnapshot, WorkerState

__all__ = ["HandwheelControl", "SIM_COUNTS_PER_POLL"]

#: the motions that take the axis from the wheel first
_MOTION = frozenset({Action.JOG, Action.MDI, Action.HOME, Action.CYCLE_START, Action.RUN_FROM_LINE,
                     Action.RESUME, Action.PROBE, Action.MEASURE_TOOL})
#: a simulated wheel turned by hand: counts per poll (at 30 Hz and 4 counts a detent, 300
#: detents a second, three turns of a 100-detent wheel)
SIM_COUNTS_PER_POLL = 40
#: a wheel the loop refused for another reason than another axis braking (set-points queued) is
#: asked again this often while it stays wanted
RETRY_S = 1.0
#: what the loop is asked to follow: axis, mode, scale (units per count), (v, a, j, lowest, highest)
_Follow = tuple[int, int, float, tuple[float, ...]]


class HandwheelControl:
    """The handwheel's axis, step and life (``controller.handwheel_ctl``)."""

    def __init__(self, settings: Settings, drives: DriveLink, positions: PositionsView,
                 signals: MachineSignals, events: MachineEvents, out: PanelChannels) -> None:
        self._settings = settings
        self._drives = drives
        self._positions = positions
        self._signals = signals
        self._events = events
        self._out = out
        self._answers = Answers(out)
        self._axis: int | None = None          # the panel's choice
        self._scale = 0
        self._machine = MachineState.DISCONNECTED
        self._armed: _Follow | None = None      # what the loop follows
        self._refused: _Follow | None = None   # what the loop refused last, and when
        self._refused_at = 0.0
        self._refused_busy = False
        self._sim_pending = 0
        self._why = ""
        self._live = False
        self._last_selector: tuple[int | None, int] | None = None
        self.status = HandwheelStatus()
        events.transition.connect(self._transition)
        events.config_changed.connect(self._config_changed)
        self._tell()

    # ------------------------------------------------------------------ the operator's
    @property
    def _configured(self) -> bool:
        return self._settings.config.wiring.handwheel.terminal is not None

    @property
    def _selector(self) -> bool:
        wiring = self._settings.config.wiring
        return any(wiring.has(f"jog_enable_{a}") for a in self._settings.config.axes)

    def select_handwheel(self, axis: str) -> CommandResult:
        """Give the wheel axis ``axis`` ("" takes it away)."""
        action = "select_handwheel"
        why = self._panel_refusal()
        if not why and axis:
            axes = self._settings.config.axes
            if axis.upper() not in axes:
                why = f"unknown axis {axis!r}; axes: {' '.join(axes)}"
        if why:
            return self._answers.refuse(action, why)
        self._axis = self._settings.config.axes.index(axis.upper()) if axis else None
        self._update(self._drives.last_snapshot)
        return self._answers.ok(action)

    def set_handwheel_step(self, scale_index: int) -> CommandResult:
        """The wheel's step: 0 x1, 1 x10, 2 x100 (``[handwheel] steps``)."""
        action = "set_handwheel_step"
        why = self._panel_refusal()
        if not why and not 0 <= int(scale_index) < len(HANDWHEEL_SCALES):
            why = f"the step is x1, x10 or x100 (0, 1 or 2), not {scale_index}"
        if why:
            return self._answers.refuse(action, why)
        self._scale = int(scale_index)
        self._update(self._drives.last_snapshot)
        return self._answers.ok(action)

    def _panel_refusal(self) -> str:
        if not self._configured:
            return "this machine has no handwheel ([handwheel] terminal)"
        if self._selector:
            return "the pendant's selector chooses the handwheel's axis and step on this machine"
        return ""

    def _sim_refusal(self) -> str:
        if not self._configured:
            return "this machine has no handwheel ([handwheel] terminal)"
        if self._settings.config.bus.kind != "sim":
            return "only a simulated machine's handwheel can be turned"
        return ""

    def turn_handwheel(self, counts: int) -> CommandResult:
        """A simulated machine's wheel turned by ``counts`` (a detent is
        ``[handwheel] counts_per_detent``); refused on a real bus."""
        why = self._sim_refusal()
        if why:
            return self._answers.refuse("turn_handwheel", why)
        self._sim_pending += int(counts)
        return self._answers.ok("turn_handwheel")

    # ------------------------------------------------------------------ the other motions
    def claim(self, action: str) -> str:
        """Take the axis from the wheel before motion ``action``: "" when it stood (let go, the
        positions read again), else why the motion must wait."""
        snap = self._drives.last_snapshot
        wheel_on = snap is not None and snap.handwheel_state != WheelState.OFF
        if action not in _MOTION or (self._armed is None and not wheel_on):
            return ""
        i = self._armed[0] if self._armed is not None else snap.handwheel_axis if snap is not None else -1
        stood = self._drives.handwheel_off()
        self._armed = None                     # let go as asked (braking first when it moved)
        if not stood:
            return self._why_wait(i)
        if action != Action.JOG:
            self._axis = None                  # a jog gives it back; anything else leaves it off
        self._events.poll_now.emit()           # where the wheel left the axis, before it is planned
        self._tell()
        return ""

    def _why_wait(self, i: int) -> str:
        axes = self._settings.config.axes
        name = axes[i] if 0 <= i < len(axes) else "?"
        return f"the handwheel is still moving axis {name}: let it stand, then try again"

    # ------------------------------------------------------------------ the poll
    def poll(self, snap: WorkerSnapshot) -> None:
        wiring = self._settings.config.wiring
        if self._sim_pending and wiring.handwheel.terminal is not None and snap.state is WorkerState.ENABLED:
            k = max(-SIM_COUNTS_PER_POLL, min(SIM_COUNTS_PER_POLL, self._sim_pending))
            self._drives.inject("encoder_add", wiring.terminal_index(wiring.handwheel.terminal), k)
            self._sim_pending -= k
        self._update(snap, fresh=True)

    def _update(self, snap: WorkerSnapshot | None, fresh: bool = False) -> None:
        """``fresh``: ``snap`` was read at this poll, after every command sent before it."""
        if not self._configured:
            return
        if self._selector and snap is not None:
            self._read_selector(snap)
        if fresh and self._armed is not None and snap is not None and snap.handwheel_state == WheelState.OFF:
            # stopped by the loop itself (a jump, its terminal lost, E-stop, a fault): off
            self._armed = None
            self._axis = None
        why = self._why_not(snap)
        wanted = self._follow() if not why and self._axis is not None else None
        if wanted != self._armed:
            if wanted is None:
                self._drives.handwheel_off()     # at rest at once, or braking first: off either way
                self._armed = None
            elif wanted != self._refused or self._retry(snap, fresh):
                axis, mode, scale, limits = wanted
                busy = self._armed is not None           # another axis' wheel: it brakes first
                if self._drives.handwheel(axis, mode, scale, limits):
                    self._armed, self._refused = wanted, None
                else:
                    self._armed = None
                    self._refused, self._refused_at, self._refused_busy = wanted, time.monotonic(), busy
        if wanted is not None and wanted == self._refused:
            why = self._why_refused()
        self._why = why
        self._live = (snap is not None and self._armed is not None and snap.handwheel_state == WheelState.LIVE
                      and snap.handwheel_axis == self._armed[0])
        self._tell()

    def _read_selector(self, snap: WorkerSnapshot) -> None:
        axes = self._settings.config.axes
        on = [i for i, a in enumerate(axes) if self._signals.value(f"jog_enable_{a}", snap)]
        value = self._signals.value
        scale = 2 if value("jog_scale_x100", snap) else 1 if value("jog_scale_x10", snap) else 0
        now = (on[0] if len(on) == 1 else None, scale)
        if now != self._last_selector:      # a wheel the loop stopped stays off until the selector moves
            self._last_selector = now
            self._axis, self._scale = now

    def _why_not(self, snap: WorkerSnapshot | None) -> str:
        """Why the wheel may not move its axis now ("" when it may, or has none)."""
        i = self._axis
        if i is None:
            return ""
        ax = self._settings.config.machine.axes[i]
        if snap is None or snap.state is not WorkerState.ENABLED or self._machine is not MachineState.IDLE:
            return f"the machine is {self._machine.label.lower()}"
        if not self._positions.homed[i]:
            return f"axis {ax.name} is not homed: home it first"
        cap = self._signals.jog_speed_cap()
        if cap is not None and cap <= 0.0:
            return "the door is open: the handwheel needs it closed on this machine"
        pos = float(self._positions.reference_pos()[i])
        if not ax.wrapped and not ax.min_pos - 1e-9 <= pos <= ax.max_pos + 1e-9:
            return f"axis {ax.name} stands outside its soft limits [{ax.min_pos:g}, {ax.max_pos:g}]"
        return ""

    def _retry(self, snap: WorkerSnapshot | None, fresh: bool) -> bool:
        """Ask again for what the loop refused: once the other axis it braked stands, or every
        ``RETRY_S`` while the loop's wheel is off."""
        if not fresh or snap is None or snap.handwheel_state != WheelState.OFF:
            return False
        return self._refused_busy or time.monotonic() - self._refused_at > RETRY_S

    def _why_refused(self) -> str:
        return "the 1 ms loop refused the handwheel (the axis is moving, or set-points are queued)"

    def _follow(self) -> _Follow:
        """What the loop is to follow for the axis given (``_why_not`` said it may)."""
        assert self._axis is not None
        i = self._axis
        cfg = self._settings.config
        ax = cfg.machine.axes[i]
        cap = self._signals.jog_speed_cap()
        offset = float(self._positions.home_offset[i])
        lo, hi = (-math.inf, math.inf) if ax.wrapped else (float(ax.min_pos), float(ax.max_pos))
        wheel = cfg.wiring.handwheel
        v = float(ax.v_motion) if cap is None else min(float(ax.v_motion), cap)
        limits = (v, float(ax.a_motion), float(ax.j_motion), lo + offset, hi + offset)
        mode = 1 if wheel.mode is WheelMode.VELOCITY else 0
        return i, mode, wheel.steps[self._scale] / wheel.counts_per_detent, limits

    def _tell(self) -> None:
        cfg = self._settings.config
        wheel = cfg.wiring.handwheel
        status = HandwheelStatus(configured=self._configured,
                                 axis=cfg.axes[self._axis] if self._axis is not None else "",
                                 step=wheel.steps[self._scale], scale_index=self._scale, live=self._live,
                                 why=self._why if self._axis is not None else "", selector=self._selector)
        if status != self.status:
            self.status = status
            self._out.handwheelChanged.emit(status)

    # ------------------------------------------------------------------ events
    def _transition(self, _old: MachineState, new: MachineState) -> None:
        self._machine = new
        if new is not MachineState.IDLE and self._armed is not None:
            self._drives.handwheel_off()          # braking, if it moves: the loop holds the new motion
            self._armed = None
        if new in (MachineState.ESTOP, MachineState.ALARM, MachineState.DISCONNECTED):
            self._axis = None                     # after a stop of the machine: off until selected again
        self._update(self._drives.last_snapshot)

    def _config_changed(self, *_args: object) -> None:
        self._axis, self._scale, self._armed, self._refused = None, 0, None, None
        self._last_selector = None
        self._sim_pending = 0
        self._tell()
