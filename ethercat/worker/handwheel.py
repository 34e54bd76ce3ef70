"""The handwheel (MPG), cycle by cycle: an encoder's counts move one axis, jerk-limited.

The counts come from an encoder terminal (``HandwheelSpec.terminal``, an EL5101's counter).
Each cycle the counter's change since the last cycle (modulo its 16 or 32 bits, so a counter
that wraps moves nothing extra) is added to the wheel's *total* and the axis is sent toward

    target = origin + total * scale            (scale: axis units per count)

as LinuxCNC's ``axis.N.jog-counts`` and ``jog-scale``. Two modes, as LinuxCNC's
``jog-vel-mode``:

- POSITION: every count moves the axis by its scale, however fast the wheel turns; a wheel
  turned faster than the axis can follow is caught up within the limits.
- VELOCITY: counts that would put the target further ahead than the axis can stop from its
  top speed are dropped, so the axis stops soon after the wheel does.

Either way the total stays within the axis' soft limits (counts beyond them are dropped: the
axis stops at the limit and comes back with the first count the other way).

The set-point is made by ``Follower`` in two stages. The first is an acceleration-limited
follower in discrete time: each cycle it takes the largest step toward the target from which
a stop with the acceleration limit, cycle by cycle, still ends on the target, within the
velocity limit and one acceleration step of the last step; it lands on the target exactly.
The second is a moving average over N cycles of the first's positions, N >= 2 a / (j Ts):
averaging keeps each sampled velocity and acceleration within those of the first stage and
bounds the sampled jerk by 2 a / (N Ts) <= j. The axis stands exactly on the target N cycles
after the first stage does.

Counts that change by more than ``max_counts_per_cycle`` in one cycle (a terminal that came
back with a new count, a broken wire) move nothing: the wheel stops and reports it, as it
does when its terminal stops answering. Nothing here allocates per cycle.
"""

from __future__ import annotations

import enum
import math

import numpy as np

__all__ = ["Follower", "Handwheel", "HandwheelMode", "WheelFault", "WheelState", "stop_distance"]

#: the longest moving average (cycles); a slower jerk limit lowers the first stage's acceleration
MAX_AVERAGE = 4096


class HandwheelMode(enum.IntEnum):
    POSITION = 0
    VELOCITY = 1


class WheelState(enum.IntEnum):
    OFF = 0          # the axis is not the wheel's
    LIVE = 1         # counts move the axis
    STOPPING = 2     # switched off or faulted while moving: braking, then OFF


class WheelFault(enum.IntEnum):
    NONE = 0
    JUMP = 1         # the counter jumped (a: the counts)
    LOST = 2         # the encoder terminal stopped answering


def stop_distance(v: float, a: float, j: float, ts_s: float) -> float:
    """The furthest the wheel's axis goes after the wheel stops, in velocity mode at velocity
    ``v`` (units/s) with the limits ``a`` and ``j``: what the first stage may still have ahead
    (its stop from ``v`` and one cycle) and what the average lags behind it."""
    n = _average_cycles(a, j, ts_s)
    a1 = min(a, j * ts_s * n / 2.0)
    step, acc = v * ts_s, a1 * ts_s * ts_s
    return _braking(step, acc) + step + (n - 1) * step / 2.0


def _average_cycles(a: float, j: float, ts_s: float) -> int:
    return max(1, min(MAX_AVERAGE, math.ceil(2.0 * a / (j * ts_s) - 1e-9)))


def _braking(u: float, acc: float) -> float:
    """How far a step of ``u`` per cycle goes while it shrinks by ``acc`` every cycle to 0."""
    k = math.floor(u / acc + 1e-12)
    return k * u - acc * k * (k + 1) / 2.0


class Follower:
    """The two stages (module docstring) for one axis, in axis units."""

    def __init__(self, ts_s: float) -> None:
        self.ts = ts_s
        self.buf = np.zeros(MAX_AVERAGE)
        self.n = 1
        self.i = 0
        self.total = 0.0
        self.p = 0.0          # the first stage's position and step (units per cycle)
        self.u = 0.0
        self.y = 0.0          # the output
        self.still = 0        # cycles the first stage has stood still
        self.step_max = 0.0
        self.acc = 0.0

    def start(self, position: float, v: float, a: float, j: float) -> None:
        """At rest at ``position`` with the limits ``v``, ``a``, ``j`` (units/s, /s^2, /s^3)."""
        ts = self.ts
        self.n = _average_cycles(a, j, ts)
        a1 = min(a, j * ts * self.n / 2.0)
        self.step_max, self.acc = v * ts, a1 * ts * ts
        self.buf[:self.n] = position
        self.total = position * self.n
        self.i = 0
        self.p = self.y = position
        self.u = 0.0
        self.still = self.n

    def set_velocity(self, v: float) -> None:
        """A new top speed from now on (the door opened: the setup speed); a lower one is
        reached with the acceleration limit."""
        self.step_max = v * self.ts

    @property
    def at_rest(self) -> bool:
        return self.u == 0.0 and self.still >= self.n

    def stop_point(self) -> float:
        """Where the first stage stops braking from now on."""
        return self.p + math.copysign(_braking(abs(self.u), self.acc), self.u)

    @property
    def lead(self) -> float:
        """How far ahead of the first stage a target may be for it to stop on the target from
        its top speed (velocity mode keeps the target within this)."""
        return _braking(self.step_max, self.acc) + self.step_max

    def shift(self, step: float) -> None:
        """Every stage moved by ``step`` at once (the output jumps by it): what a caller whose
        own part jumped by -``step`` adds, so that the sum goes on without a jump."""
        self.p += step
        self.y += step
        self.total += step * self.n
        np.add(self.buf, step, out=self.buf)
        self.still = 0

    def step(self, target: float) -> float:
        """One cycle toward ``target``: the output position."""
        if self.u == 0.0 and target == self.p and self.still >= self.n:
            return self.y                     # at rest on it: every stage stays as it is
        d = target - self.p
        dist, acc = abs(d), self.acc
        # the largest step u with u + (its braking distance) <= dist: k whole braking steps
        k = math.floor((math.sqrt(1.0 + 8.0 * dist / acc) - 1.0) / 2.0)
        while k > 0 and acc * k * (k + 1) / 2.0 > dist:
            k -= 1
        while acc * (k + 1) * (k + 2) / 2.0 <= dist:
            k += 1
        reach = (dist + acc * k * (k + 1) / 2.0) / (k + 1)
        u = math.copysign(min(reach, self.step_max), d) if d != 0.0 else 0.0
        u = min(max(u, self.u - acc), self.u + acc)
        if u == d:
            self.p = target                   # landed: exactly on it
        else:
            self.p += u
        self.u = u
        self.still = self.still + 1 if u == 0.0 else 0
        buf, i = self.buf, self.i
        self.total += self.p - buf[i]
        buf[i] = self.p
        self.i = i + 1 if i + 1 < self.n else 0
        # once the first stage has stood for a whole average, every entry is its position
        self.y = self.p if self.still >= self.n else self.total / self.n
        return self.y


class Handwheel:
    """The wheel in the loop: which axis it moves, its mode, scale and limits, its counter."""

    def __init__(self, ts_s: float, counter_bits: int, max_counts_per_cycle: int,
                 live_state: np.ndarray | None = None, live_axis: np.ndarray | None = None) -> None:
        """``live_state``, ``live_axis``: where the loop's snapshot shows the state and axis."""
        self.follower = Follower(ts_s)
        self.live_state = live_state if live_state is not None else np.zeros((), dtype=np.int64)
        self.live_axis = live_axis if live_axis is not None else np.zeros((), dtype=np.int64)
        self.live_axis[...] = -1
        self.axis = -1
        self._set(WheelState.OFF)
        self.mode = HandwheelMode.POSITION
        self.scale = 0.0
        self.origin = 0.0
        self.counts = 0                  # the total since armed (its target: origin + counts * scale)
        self.lo_counts = 0
        self.hi_counts = 0
        self.last = 0                    # the counter's last reading
        self.modulus = 1 << counter_bits
        self.half = self.modulus >> 1
        self.max_counts = max_counts_per_cycle
        self.stop_target = 0.0
        self.fault = WheelFault.NONE
        self.fault_counts = 0

    def arm(self, axis: int, mode: int, scale: float, limits: np.ndarray, position: float,
            count: int) -> bool:
        """Axis ``axis`` follows the wheel from ``position`` (its set-point now) with ``scale``
        units per count; ``limits``: v, a, j, lowest and highest position. False (nothing
        changes) when the arguments cannot be followed; False too while another axis moves,
        which then brakes to rest (ask again once it stands)."""
        v, a, j, lo, hi = (float(x) for x in limits[:5])
        if mode not in (0, 1):
            return False
        if self.state is not WheelState.OFF and axis != self.axis and not (
                self.state is WheelState.LIVE and self.follower.at_rest):
            self.disarm()                    # the other axis brakes to rest first
            return False
        tol = 1e-9 * max(1.0, abs(position))          # the rounding of a home offset added to a limit
        if not (scale != 0.0 and math.isfinite(scale) and v > 0.0 and a > 0.0 and j > 0.0
                and lo - tol <= position <= hi + tol):
            return False
        if self.state is WheelState.OFF or axis != self.axis:
            self.follower.start(position, v, a, j)
            self.origin = position
        elif self.state is WheelState.LIVE:  # a new step, mode or speed: the counts turned so far go
            self.origin += self.counts * self.scale
            self.follower.set_velocity(v)
        else:                                # stopping: on from where it stops
            self.origin = self.stop_target
            self.follower.set_velocity(v)
        self.axis, self.mode, self.scale = axis, HandwheelMode(mode), scale
        self.counts = 0
        c1, c2 = (lo - self.origin) / scale, (hi - self.origin) / scale
        self.lo_counts = math.ceil(min(c1, c2) - 1e-9) if math.isfinite(min(c1, c2)) else -(1 << 62)
        self.hi_counts = math.floor(max(c1, c2) + 1e-9) if math.isfinite(max(c1, c2)) else 1 << 62
        self.last = int(count)
        self.fault = WheelFault.NONE
        self._set(WheelState.LIVE)
        return True

    def _set(self, state: WheelState) -> None:
        self.state = state
        self.live_state[...] = int(state)
        self.live_axis[...] = self.axis

    def disarm(self) -> None:
        """Stop: the axis brakes to rest and the wheel lets it go."""
        if self.state is WheelState.LIVE:
            self.stop_target = self.follower.stop_point()
            self._set(WheelState.STOPPING)

    def release(self) -> bool:
        """Let the axis go: True when it stands (at once), else it brakes first (False)."""
        if self.state is WheelState.LIVE and self.follower.at_rest:
            self.off()
        self.disarm()
        return self.state is WheelState.OFF

    def off(self) -> None:
        """At once (the drives stopped by themselves: E-stop, fault, disabled)."""
        self.axis = -1
        self._set(WheelState.OFF)

    def step(self, count: int, ref: np.ndarray) -> bool:
        """One cycle: ``count`` the counter read last, the axis' set-point written into ``ref``.
        False in the cycle the counter jumped (``fault``): the wheel is then stopping."""
        f = self.follower
        ok = True
        if self.state is WheelState.LIVE:
            delta = (int(count) - self.last + self.half) % self.modulus - self.half
            self.last = int(count)
            if abs(delta) > self.max_counts:
                self.fault, self.fault_counts = WheelFault.JUMP, delta
                self.disarm()
                ok = False
            else:
                total = self.counts + delta
                if self.mode is HandwheelMode.VELOCITY:
                    room = f.lead / abs(self.scale)
                    ahead = (f.p - self.origin) / self.scale
                    total = min(max(total, math.ceil(ahead - room)), math.floor(ahead + room))
                self.counts = min(max(total, self.lo_counts), self.hi_counts)
        if self.state is WheelState.LIVE:
            target = self.origin + self.counts * self.scale
        else:
            target = self.stop_target
        ref[self.axis] = f.step(target)
        if self.state is WheelState.STOPPING and f.at_rest:
            self.off()
        return ok
