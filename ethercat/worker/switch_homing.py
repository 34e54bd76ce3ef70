"""Homing to a switch in position mode, cycle by cycle, as LinuxCNC's motion controller homes.

Per axis (``SwitchHoming``): if the axis starts on its switch it first moves off it against
the search direction; then it searches at ``search_vel`` until the switch closes and stops;
with a latch velocity of the search's sign it backs off until the switch opens and comes back
at ``latch_vel`` until it closes, with the opposite sign it leaves the switch at
``latch_vel``; the actual position of the cycle the switch changes is *latched*, and the
axis stops. With ``use_index`` it does not stop at the edge: it arms its drive's touch probe 1
on the encoder's zero impulse (0x60B8 = 0x15) and goes on at the latch velocity until the drive
reports the edge stored (0x60B9 bits 0 and 1); the drive's latched position (0x60BA) is then
the one reported, exact to a count whatever the cycle time. Every change of velocity is a
jerk-limited ramp (``accel``, ``jerk``). Each move is bounded by ``max_travel`` (a switch or an
index that never comes is an error naming the step).

The set-point of a homing axis is made here, one per cycle, from its velocity; several axes
home at once (LinuxCNC's equal HOME_SEQUENCE). What the latched position means (the switch's
machine coordinate, where to go next) is the controller's: the loop only reports it.

A gantry's two sides (``gantry.GantrySpec``) home together, each latching its own switch;
the follower then waits for its leader to stand latched and moves alone (step SQUARE, with the
handwheel's jerk-limited ``Follower``, landing exactly) until the two stand as far apart as
their latches less the two switches' offset: square.

The positions here are axis units of the drive's own count (``act``/``ref``).
"""

from __future__ import annotations

import math

import numpy as np

from ..bus import Bus
from ..cia402 import TP_ENABLED, TP_INDEX_FIRST_POSITIVE, TP_POSITIVE_STORED
from .gantry import GantrySpec
from .handwheel import Follower
from .types import HomingState, HomingStep, SwitchHoming

__all__ = ["SwitchHomer", "FAIL_NOT_FOUND", "FAIL_LIMIT", "FAIL_TIMEOUT", "FAIL_NO_INDEX", "FAIL_SQUARE",
           "FAIL_GANTRY_ALONE"]

FAIL_NOT_FOUND = 1      # the switch (or the index) did not change within max_travel
FAIL_LIMIT = 2          # a limit switch tripped (and the axis does not ignore limits)
FAIL_TIMEOUT = 3
FAIL_NO_INDEX = 4       # homing to the index on a drive without touch probe 1 in its process data
FAIL_SQUARE = 5         # squaring a gantry would move its follower further than max_travel
FAIL_GANTRY_ALONE = 6   # one side of a gantry asked to home without the other

_INDEX_STORED = TP_ENABLED | TP_POSITIVE_STORED
_TOUCH_PROBE_OBJECTS = (0x60B8, 0x60B9, 0x60BA)


class _Axis:
    """One axis' homing: its step, velocity and acceleration, the position its move began."""

    __slots__ = ("spec", "step", "v", "a", "v_target", "stopping", "start", "mask", "closed_level",
                 "next_step", "gantry", "leader", "follower", "target")

    def __init__(self, spec: SwitchHoming, gantry: GantrySpec | None = None) -> None:
        self.spec = spec
        self.step = HomingStep.IDLE
        self.v = 0.0
        self.a = 0.0
        self.v_target = 0.0
        self.stopping = False
        self.start = 0.0
        self.mask = 1 << spec.bit
        self.closed_level = spec.level
        self.next_step = HomingStep.IDLE
        #: a gantry's follower: its pair, its leader's homing (``begin``), the squaring move
        self.gantry = gantry
        self.leader: _Axis | None = None
        self.follower: Follower | None = None
        self.target = math.nan                   # where squaring takes it (NaN: not yet known)


class SwitchHomer:
    """Homing to switches of the axes asked (see the module docstring)."""

    def __init__(self, specs: tuple[SwitchHoming, ...], ts_s: float, homing_state: np.ndarray,
                 homed: np.ndarray, steps: np.ndarray, latched: np.ndarray, timeout_cycles: int,
                 gantries: tuple[GantrySpec, ...] = ()) -> None:
        self.ts = ts_s
        self.by_axis: dict[int, SwitchHoming] = {s.axis: s for s in specs}
        self.gantry_of: dict[int, GantrySpec] = {g.follower: g for g in gantries}
        self.sides: dict[int, int] = {**{g.axis: g.follower for g in gantries},
                                      **{g.follower: g.axis for g in gantries}}
        self.axes: list[_Axis] = []
        self.state = homing_state
        self.homed = homed
        self.steps = steps
        self.latched = latched
        self.timeout_cycles = timeout_cycles
        self.cycles = 0
        self.failure = 0                   # FAIL_* of the axis that failed
        self.failed_axis = -1
        self.failed_step = HomingStep.IDLE
        # the bus' touch probe arrays and the counts -> units scale (``bind``)
        self.tp_function = np.zeros(0, dtype=np.uint16)
        self.tp_status = np.zeros(0, dtype=np.uint16)
        self.tp_value = np.zeros(0, dtype=np.int32)
        self.gain = np.ones(0)
        self.offset = np.zeros(0)
        self.has_touch_probe: tuple[bool, ...] = ()

    def bind(self, bus: Bus, gain: np.ndarray, offset: np.ndarray) -> None:
        """Use ``bus``' touch probe arrays (the index of homing with ``use_index``) and the
        axes' scale (units = (counts - offset) / gain)."""
        self.tp_function = bus.touch_probe_function
        self.tp_status = bus.touch_probe_status
        self.tp_value = bus.touch_probe_value
        self.gain, self.offset = gain, offset
        self.has_touch_probe = tuple(all(bus.maps_object(i, o) for o in _TOUCH_PROBE_OBJECTS)
                                     for i in range(bus.n_drives))

    @property
    def active(self) -> bool:
        return bool(self.axes)

    def has(self, axis: int) -> bool:
        return axis in self.by_axis

    def ignores_limits(self, axis: int) -> bool:
        """Whether ``axis`` homes now with its limit switches ignored (its HOME_IGNORE_LIMITS)."""
        for h in self.axes:
            if h.spec.axis == axis:
                return h.spec.ignore_limits
        return False

    def begin(self, axis_mask: int, words: np.ndarray) -> bool:
        """Start the axes of ``axis_mask`` together; False (nothing started) when one of them has
        no switch homing configured."""
        wanted = [a for a in range(63) if axis_mask >> a & 1]
        self.failure = 0
        self.failed_axis = -1
        if not wanted or any(a not in self.by_axis for a in wanted):
            return False
        for a in wanted:
            if a in self.sides and self.sides[a] not in wanted:
                self.failure, self.failed_axis, self.failed_step = FAIL_GANTRY_ALONE, a, HomingStep.IDLE
                return False
            if self.by_axis[a].use_index and not (a < len(self.has_touch_probe) and self.has_touch_probe[a]):
                self.failure, self.failed_axis, self.failed_step = FAIL_NO_INDEX, a, HomingStep.INDEX
                return False                      # refused, and ``failure`` says why
        self.axes = [_Axis(self.by_axis[a], self.gantry_of.get(a)) for a in wanted]
        by_axis = {h.spec.axis: h for h in self.axes}
        for h in self.axes:
            if h.gantry is not None:
                h.leader = by_axis[h.gantry.axis]
                h.follower = Follower(self.ts)
        self.cycles = 0
        for h in self.axes:
            self.tp_function[h.spec.axis] = 0
        for h in self.axes:
            a = h.spec.axis
            self.state[a] = HomingState.RUNNING
            self.homed[a] = 0
            on_switch = self._closed(h, words)
            self._go(h, HomingStep.OFF_SWITCH if on_switch else HomingStep.SEARCH, 0.0)
        return True

    def cancel(self) -> None:
        for h in self.axes:
            a = h.spec.axis
            if a < len(self.tp_function):
                self.tp_function[a] = 0
            if self.state[a] == HomingState.RUNNING:
                self.state[a] = HomingState.ERROR
            self.steps[a] = HomingStep.IDLE
        self.axes = []

    # ------------------------------------------------------------------ per cycle
    def _closed(self, h: _Axis, words: np.ndarray) -> bool:
        return (int(words[h.spec.word]) & h.mask != 0) == h.closed_level

    def _go(self, h: _Axis, step: HomingStep, position: float) -> None:
        spec = h.spec
        h.step = step
        self.steps[spec.axis] = step
        h.stopping = False
        h.start = position
        if step is HomingStep.OFF_SWITCH or step is HomingStep.BACK_OFF:
            h.v_target = -spec.search_vel
        elif step is HomingStep.SEARCH:
            h.v_target = spec.search_vel
        elif step is HomingStep.LATCH or step is HomingStep.INDEX:
            h.v_target = spec.latch_vel
        else:
            h.v_target = 0.0

    def _stop_then(self, h: _Axis, step: HomingStep) -> None:
        h.v_target = 0.0
        h.stopping = True
        h.next_step = step

    def _ramp(self, h: _Axis) -> None:
        """One cycle of a jerk-limited velocity ramp toward ``v_target``: along the way to it, the
        largest acceleration that the jerk limit can still bring back to 0 before the velocity
        passes the target (the continuous bound a^2 / 2j, above the discrete ramp's), within
        one jerk step of the last and the acceleration limit."""
        spec, ts = h.spec, self.ts
        j = spec.jerk
        dv = h.v_target - h.v
        s = 1.0 if dv > 0.0 else -1.0 if dv < 0.0 else (-1.0 if h.a > 0.0 else 1.0)
        a_s = s * h.a
        room = max(abs(dv), 0.0)
        bound = j * (math.sqrt(ts * ts + 2.0 * room / j) - ts)
        a_next = min(max(bound, a_s - j * ts), a_s + j * ts, spec.accel)
        h.a = s * a_next
        h.v += h.a * ts
        if h.v_target == 0.0 and abs(h.v) < 1e-12 and abs(h.a) <= j * ts:
            h.v, h.a = 0.0, 0.0               # at rest: exactly

    def step(self, ref: np.ndarray, act: np.ndarray, words: np.ndarray) -> bool:
        """Advance every homing axis one cycle and write its set-point into ``ref``. Returns
        False when an axis failed (``failure``, ``failed_axis``, ``failed_step``): the caller
        stops the motion and raises the alarm."""
        self.cycles += 1
        if self.cycles > self.timeout_cycles:
            return self._fail(self.axes[0], FAIL_TIMEOUT)
        done = 0
        for h in self.axes:
            spec = h.spec
            a = spec.axis
            step = h.step
            if step is HomingStep.DONE:
                done += 1
                continue
            if step is HomingStep.SQUARE:
                if not self._square(h, ref):
                    return self._fail(h, FAIL_SQUARE)
                continue
            closed = self._closed(h, words)
            if not h.stopping:
                if step is HomingStep.SEARCH and closed:
                    self._stop_then(h, HomingStep.BACK_OFF if spec.latch_vel * spec.search_vel > 0
                                    else HomingStep.LATCH)
                elif (step is HomingStep.OFF_SWITCH or step is HomingStep.BACK_OFF) and not closed:
                    self._stop_then(h, HomingStep.SEARCH if step is HomingStep.OFF_SWITCH
                                    else HomingStep.LATCH)
                elif step is HomingStep.LATCH and closed == (spec.latch_vel * spec.search_vel > 0):
                    # the edge: closing when latching toward the switch, opening when leaving it
                    self.latched[a] = act[a]
                    if spec.use_index:
                        self._go(h, HomingStep.INDEX, float(ref[a]))
                        self.tp_function[a] = TP_INDEX_FIRST_POSITIVE
                    else:
                        self._stop_then(h, HomingStep.DONE)
                elif step is HomingStep.INDEX and int(self.tp_status[a]) & _INDEX_STORED == _INDEX_STORED:
                    # enabled and stored: the drive saw this arming (its status was 0 while the
                    # function was 0), so the edge is this search's
                    self.latched[a] = (float(self.tp_value[a]) - self.offset[a]) / self.gain[a]
                    self.tp_function[a] = 0
                    self._stop_then(h, HomingStep.DONE)
                elif abs(ref[a] - h.start) > spec.max_travel:
                    return self._fail(h, FAIL_NOT_FOUND)
            self._ramp(h)
            ref[a] += h.v * self.ts
            if h.stopping and h.v == 0.0 and h.a == 0.0:
                nxt = h.next_step
                if nxt is HomingStep.DONE and h.gantry is not None:
                    self._go(h, HomingStep.SQUARE, float(ref[a]))
                elif nxt is HomingStep.DONE:
                    self._done(h)
                else:
                    self._go(h, nxt, float(ref[a]))
        if done == len(self.axes):
            self.axes = []
        return True

    def _square(self, h: _Axis, ref: np.ndarray) -> bool:
        """A gantry's follower, latched: once its leader stands latched too, it moves alone
        until the pair is square, then it is done. False: that move is too long."""
        leader, g, follower = h.leader, h.gantry, h.follower
        assert leader is not None and g is not None and follower is not None
        if leader.step is not HomingStep.DONE:
            return True                            # the leader still homes: wait where latched
        a = h.spec.axis
        if math.isnan(h.target):
            l = g.axis
            h.target = float(ref[l]) + float(self.latched[a]) - float(self.latched[l]) - g.switch_offset
            if abs(h.target - float(ref[a])) > h.spec.max_travel:
                return False
            follower.start(float(ref[a]), abs(h.spec.search_vel), h.spec.accel, h.spec.jerk)
        ref[a] = follower.step(h.target)
        if follower.at_rest and ref[a] == h.target:
            self._done(h)
        return True

    def _done(self, h: _Axis) -> None:
        a = h.spec.axis
        h.step = HomingStep.DONE
        self.steps[a] = HomingStep.DONE
        self.state[a] = HomingState.DONE
        self.homed[a] = 1

    def limit_tripped(self, axis: int) -> bool:
        """A limit switch of ``axis`` tripped while it homes: the homing fails (False) unless the
        axis ignores its limits."""
        for h in self.axes:
            if h.spec.axis == axis and not h.spec.ignore_limits:
                return self._fail(h, FAIL_LIMIT)
        return True

    def _fail(self, h: _Axis, why: int) -> bool:
        self.failure = why
        self.failed_axis = h.spec.axis
        self.failed_step = h.step
        self.cancel()
        return False
