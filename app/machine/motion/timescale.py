r"""Feed override, rapid override and feed hold by time-scaling the planned trajectory.

The planner gives q_p(tau) (positions against planned time tau, every axis and the path).
The executor runs it as q(t) = q_p(tau(t)) with d tau / d t = sigma(t), the time scale:
sigma = 1 is the plan, 0.5 half speed, 0 standing still on the path (feed hold), up to 2
(200 %). Since only the time axis changes, the tool never leaves the programmed path and
ends exactly at the programmed end. Differentiating (for every axis and for the path):

    dq/dt     = q_p' sigma
    d2q/dt2   = q_p'' sigma^2 + q_p' sigma_dot
    d3q/dt3   = q_p''' sigma^3 + 3 q_p'' sigma sigma_dot + q_p' sigma_ddot

**Budget.** The program is planned with the full velocity limits V_k but only k_a A_k and
k_j J_k for acceleration and jerk (k_a = 1 - accel_reserve, k_j = 1 - jerk_reserve), for every
constraint k (the path and each axis). Write r_v, r_a, r_j for the largest |q_p'|/V_k,
|q_p''|/A_k, |q_p'''|/J_k over the constraints near tau (per 16-sample block, from finite
differences of the plan's samples; a window ahead of tau), and alpha = max |q_p'|/A_k,
beta = max |q_p''|/J_k, gamma = max |q_p'|/J_k (seconds, s, s^2). With m = min(sigma, 1)
the controller keeps

    (1)  |sigma_dot|  <= D1 = min( (1 - r_a m^2) / alpha , (1 - r_j m^3) / (6 beta m) )
    (2)  |sigma_ddot| <= D2 = (1 - r_j m^3) / (2 gamma)
    (3)  sigma        <= cap = max(1, min(1 / r_v, sqrt(k_a / r_a), cbrt(k_j / r_j)))

**Claim: no velocity, acceleration or jerk limit is exceeded.** For sigma <= 1 the plan gives
r_v <= 1, r_a <= k_a, r_j <= k_j. For 1 < sigma <= cap, (3) gives r_v sigma <= 1,
r_a sigma^2 <= k_a and r_j sigma^3 <= k_j, and |q_p'| <= V_k / sigma <= V_k,
|q_p''| sigma <= k_a A_k / sigma <= k_a A_k m. In both cases, for every constraint k:

    |dq/dt|   <= r_v sigma V_k <= V_k
    |d2q/dt2| <= A_k (r_a m^2 + alpha D1)                          <= A_k        by (1)
    |d3q/dt3| <= J_k (r_j m^3 + 3 beta m D1 + gamma D2)
              <= J_k (r_j m^3 + (1 - r_j m^3) / 2 + (1 - r_j m^3) / 2) = J_k   by (1), (2)

(the sigma > 1 case uses r_a, r_j at sigma = 1 scaled as shown, i.e. the m = 1 terms). The
bounds are evaluated over a window that covers the distance tau travels while sigma changes,
so they hold for every tau the step visits. ``check_limits`` measures it numerically.

**Control of sigma.** sigma follows its target (override, 0 for hold, capped by (3) ahead:
the cap of every block is met by braking along an envelope computed backwards from the caps,
sigma^2 falling at 2 * 0.7 D1 per unit of planned time with the D1 of the window the steps
will see there, and entered early by the planned time sigma covers while sigma_dot ramps up)
with a discrete-time braking law: sigma_dot_wanted is the largest
value from which steps of sigma_ddot = 0.7 D2_ref stop within the error e (continuous form
sqrt(1.4 D2_ref |e|)), reached with |sigma_ddot| <= D2 (semi-implicit Euler steps), where
D2_ref <= D2 is the worst-case bound (so braking is always feasible). A step that would cross
the target lands on it only when |sigma_dot| <= 1.9 D2_ref Ts (the law makes it about
0.7 D2_ref Ts unless the target jumped): one sample of |sigma_ddot| <= 1.9 D2_ref
<= 0.95 (1 - r_j m^3) / gamma with a negligible sigma_dot term, inside the jerk budget. When
the target jumps just ahead of a fast-moving sigma, sigma passes it and comes back under the
bounds (1), (2). A tighter D1 appearing at the far edge of the window is approached at the
rate D2 (no clipping of sigma_dot, which would be a jump in sigma_ddot).

A feed hold is sigma -> 0 under the same bounds: a jerk-limited stop along the path; resume
ramps sigma back up and the plan continues to the same end. Shorter: when a hold (or stop)
arrives while moving, the executor first tries ``planner.motion.stopping.plan_path_stop``, the
time-optimal jerk-limited stop of the path speed from the current (s, v, a) with per-axis
bounds from the geometry ahead (about half the distance and a third of the time of the ramp:
30 mm/s on an arc, 1.7 mm in 0.11 s instead of 5.2 mm in 0.43 s); it is used only if the
executed set-points, with the three before them, pass ``check_limits``, and never across a
corner or a planned full stop. It ends at rest at a planned time tau (sigma = 0), from
which a resume ramps sigma up as after any hold, so the run still ends exactly at the end.
A resume during that stop lets it finish first. Full stops of the plan (block
ends with zero speed: M00, M01, dwell, single block, program end) are pause points: tau stops
exactly there (speed and acceleration of the plan are zero there, so stopping tau is smooth),
and restarts at the target sigma.

A feed hold asked for while a tap is in the hole (G74/G84, G33.1: the moves whose feed follows
the spindle) waits until the tap has come out, where it ends at rest (``hold_deferred``): the
axes standing while the spindle turns would strip the thread or break the tap. A stop, an
alarm or a probe's contact holds at once.

**What the claim rests on.** (a) The plan keeps r_a <= k_a and r_j <= k_j (the planner's own
guarantee, made with the reduced limits); jerk at joints (tangent breaks, curvature jumps) is
the planner's joint figure, excluded here as in its limit report, and r_j is clipped to k_j
for the sigma dynamics. (b) r_*, alpha, beta, gamma are finite-difference maxima of the plan's
1 ms samples per 16-sample block, taken over a window of 0.25 s of planned time ahead (the
stop from 150 % covers less). (c) Cost: planning with k_a = 0.85, k_j = 0.7 lengthened the
shipped programs' cycle times by 0.7-2.3 %; a hold from 30 mm/s takes about 0.33 s (3.6 mm)
with the worst-case braking law. ``tests/machine/test_timescale.py`` checks every limit on
the executed set-points with overrides changing mid-move, a hold mid-arc and random programs
with random override/hold sequences (a 40-program sweep: worst ratio 0.87 for jerk, 0.82 for
axis acceleration, velocity 1 + 4e-8).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from app.machine.model import Budget, PauseKind, PausePoint
from app.machine.motion.plan_stats import BLOCK, BlockStats
from app.machine.state.overrides import FEED_MAX_PCT
from planner.core.machine import MachineSpec
from planner.core.program import FEED_HOLD_DEFERRED, Dwell, EventKind, Program
from planner.motion.interpolate import Interpolator, Segment
from planner.motion.meter import check_limits
from planner.motion.plan import Plan
from planner.motion.stopping import PathStop, plan_path_stop
from planner.motion.window import PlanWindow

__all__ = ["Budget", "PauseKind", "PausePoint", "ScaledChunk", "TimeScaledExecutor", "braking_rates",
           "pause_points", "ramp_bound_s", "reduced_machine"]

SIGMA_MAX = FEED_MAX_PCT / 100.0  # the largest feed override; above 1 the machine's limits cap it (3)
# planned time a plan made as it runs is held behind tau: a splice rewinds to the first
# set-point still queued in the worker, at most ``lead_s`` (1 s, the configuration's bound) and
# a chunk of real time back, 2 s of plan at 200 %
KEEP_BEHIND_S = 3.0


def reduced_machine(machine: MachineSpec, budget: Budget) -> MachineSpec:
    """The machine with acceleration and jerk limits (path and axes) scaled by the budget."""
    from dataclasses import replace

    axes = tuple(replace(a, a_max=a.a_max * budget.k_a, j_max=a.j_max * budget.k_j) for a in machine.axes)
    lim = replace(machine.limits, a_max_mm_s2=machine.limits.a_max_mm_s2 * budget.k_a,
                  j_max_mm_s3=machine.limits.j_max_mm_s3 * budget.k_j)
    return replace(machine, axes=axes, limits=lim)


def braking_rates(machine: MachineSpec, budget: Budget) -> tuple[float, float]:
    """The worst-case bounds D1_ref (|sigma_dot|, 1/s) and D2_ref (|sigma_ddot|, 1/s^2) of the
    braking law, from the machine's limits and the share the plan leaves to the time scale."""
    lim = machine.limits
    v_lin = max(lim.v_max_mm_s, lim.rapid_mm_s)
    t1 = max([v_lin / lim.a_max_mm_s2] + [min(a.v_motion, v_lin if not a.rotary else a.v_motion) / a.a_motion
                                          for a in machine.axes])
    t2 = max([lim.a_max_mm_s2 / lim.j_max_mm_s3] + [a.a_motion / a.j_motion for a in machine.axes])
    t3 = max([v_lin / lim.j_max_mm_s3] + [min(a.v_motion, v_lin if not a.rotary else a.v_motion) / a.j_motion
                                          for a in machine.axes])
    k_a, k_j = budget.k_a, budget.k_j
    return min((1.0 - k_a) / t1, (1.0 - k_j) / (6.0 * k_a * t2)), (1.0 - k_j) / (2.0 * t3)


def ramp_bound_s(machine: MachineSpec, budget: Budget) -> float:
    """Upper bound of the time the braking law takes to change sigma by ``SIGMA_MAX``: no hold
    takes longer (a stop from 200 % included)."""
    return _ramp_s(*braking_rates(machine, budget))


def _ramp_s(d1: float, d2: float) -> float:
    """The braking law's time to change sigma by ``SIGMA_MAX`` at the rates D1, D2."""
    return SIGMA_MAX / d1 + d1 / d2


@dataclass(frozen=True, slots=True, eq=False)
class ScaledChunk:
    q: np.ndarray  # (N, n_axes) set-points, mm|deg
    tau: np.ndarray  # (N,) planned time of each set-point
    sigma: np.ndarray  # (N,) time scale
    line: np.ndarray  # (N,) int source line
    move: np.ndarray  # (N,) int move index
    s_mm: np.ndarray  # (N,) cumulative path length
    pause: PausePoint | None  # set when the chunk ends at a pause point


@dataclass(frozen=True, slots=True, eq=False)
class _Envelope:
    """The braking envelope over a window of blocks (``TimeScaledExecutor._envelope``)."""

    start_tau: np.ndarray  # planned time each block starts at
    env: np.ndarray  # the highest sigma at each block from which every cap ahead is met
    env_min: float
    d1_first: float  # the braking rate D1 at the window's first block
    x_max: float  # the highest cap of the window, at most SIGMA_MAX
    has_fixed: np.ndarray  # per block: a move with the feed override off
    has_feed: np.ndarray
    has_rapid: np.ndarray


class TimeScaledExecutor:
    """Runs a plan at a time scale sigma (override / hold), producing set-points every Ts."""

    def __init__(self, plan: Plan | PlanWindow, machine: MachineSpec, budget: Budget,
                 pauses: list[PausePoint] | None = None, feed_override: float = 1.0,
                 rapid_override: float = 1.0, pause_feed: PauseFeed | None = None) -> None:
        # a whole plan, or one made as the run reaches it (``planner.motion.window``): the executor
        # reads it only around tau, from where a splice may rewind to as far as it brakes ahead
        window = plan if isinstance(plan, PlanWindow) else PlanWindow.of_plan(plan)
        self.window = window
        self.plan = window
        self.machine = machine
        self.budget = budget
        self.ts = window.ts_s
        self.pauses = sorted(pauses or [], key=lambda p: p.tau_s)
        # the pause points of a plan made as it runs, added as its segments are made
        if pause_feed is not None and window.segments_made:
            raise ValueError("the pause points of a plan made as it runs come from each of its segments: "
                             "give the executor a window not yet moved")
        self._pause_feed = pause_feed
        window.on_segment = self._segment_made if pause_feed is not None else None
        self.stats = BlockStats(window, machine)
        # the planner's own interpolation (exact, taylor or classic), at the scaled times
        self.interp = Interpolator(window.interpolation, window.ts_s)
        self.n_moves = window.n_moves
        if self.n_moves:
            self._advance_window(0.0, 0.0)
        if window.interpolation == "taylor" and self.n_moves:
            # Eq. 16 starts where the plan does, at rest at planned time 0, as cnc-plan's samples
            self.interp.at_state = (0.0, float(self.seg.s0[0]), 0.0, 0.0)
        self.tau = 0.0
        self.sigma = 0.0
        self.sigma_dot = 0.0
        self.feed_override = float(feed_override)
        self.rapid_override = float(rapid_override)
        self.hold = False
        # the operator's feed hold waits while a tap is in the hole (``hold_deferred``); a stop,
        # an alarm or a probe's contact holds at once
        self.hold_waits_for_tap = False
        self._locks = window.program.override_locks     # per move; None when nothing is locked
        self._pause_i = 0
        self.paused: PausePoint | None = None
        self.finished = self.n_moves == 0
        # worst-case (global) bounds for the braking law and the look-ahead distance
        self.d1_ref, self.d2_ref = braking_rates(machine, budget)
        self._win_valid_until = -1.0
        self._bounds = (1.0, 1.0, 1.0, 1.0, 1.0, 1.0)
        self._target_cache = 1.0
        # what ``_local_bounds`` found for a key (the window's blocks and what else it reads)
        self._bounds_memo: tuple[object, tuple[float, float, float, float, float, float]] = \
            (None, self._bounds)
        self._envelope_memo: tuple[object, _Envelope | None] = (None, None)
        self.capped_to: float | None = None  # the time scale the limits allow, when below the override
        self.override_off_here = False  # the program runs its own feed here (tapping, M49, M50 P0)
        self.sigma_start = True  # at a standstill of the plan (start or pause point)
        # hold / stop: the time-optimal stop along the path (planner.motion.stopping) when it keeps
        # every limit, else sigma -> 0 by the braking law above
        self.path_stops = True
        self._stop: PathStop | None = None
        self._stop_k = 0
        self._stop_tried = False
        self.stops_taken = 0  # how many holds used the path stop (diagnostics, tests)
        self._last = (np.zeros((0, len(machine.axes))), np.zeros(0), np.zeros(0, np.int64))
        self._rapid_move = window.program.rapid_moves
        self._rotary_only = window.program.rotary_only_moves

    # ------------------------------------------------------------------ the plan around tau
    @property
    def seg(self) -> Segment:
        """The plan's held segments as one (rows local; ``table.index``: the program's moves)."""
        return self.window.segment

    @property
    def t_end(self) -> float:
        """The plan's end (infinite until a plan made as it runs has made its last segment)."""
        return self.window.t_end

    @property
    def planned_end_s(self) -> float:
        """The plan's end, or its estimate while it is being made (for the time left)."""
        return self.window.cycle_time_s

    def move_start_s(self, move: int) -> float:
        """Cumulative path length where the program's move ``move`` starts (near tau)."""
        return self.window.move_start_s(move)

    def _segment_made(self, seg: Segment) -> None:
        assert self._pause_feed is not None
        self.pauses.extend(self._pause_feed.points_in(seg))

    def _advance_window(self, tau_back: float, tau_ahead: float) -> None:
        """Plan ahead to ``tau_ahead``, let go of what ends before ``tau_back``."""
        window = self.window
        if not window.done:
            window.ensure(tau_ahead)
        window.release(tau_back)

    # ------------------------------------------------------------------ state (splicing)
    _STATE = ("tau", "sigma", "sigma_dot", "feed_override", "rapid_override", "hold", "hold_waits_for_tap",
              "_pause_i", "paused",
              "finished", "_win_valid_until", "_bounds", "_target_cache", "sigma_start", "_stop", "_stop_k",
              "_stop_tried", "stops_taken", "_last", "_interp_state")

    @property
    def _interp_state(self) -> tuple[float, float, float, float] | None:
        return self.interp.at_state

    @_interp_state.setter
    def _interp_state(self, value: tuple[float, float, float, float] | None) -> None:
        self.interp.at_state = value

    def save_state(self) -> tuple:
        """Everything ``generate`` changes (scalars, immutable tuples and arrays it never writes
        into): with ``restore_state`` the controller rewinds the executor to a pushed chunk and
        regenerates from any set-point of it (same chunk start: bit-identical samples)."""
        return tuple(getattr(self, k) for k in self._STATE)

    def restore_state(self, state: tuple) -> None:
        for k, v in zip(self._STATE, state, strict=True):
            setattr(self, k, v)

    # ------------------------------------------------------------------ commands
    @property
    def time_to_ramp_s(self) -> float:
        """Upper bound of the time to change sigma by ``SIGMA_MAX`` (``ramp_bound_s``)."""
        return _ramp_s(self.d1_ref, self.d2_ref)

    def set_overrides(self, feed: float | None = None, rapid: float | None = None) -> None:
        if feed is not None:
            self.feed_override = min(max(float(feed), 0.0), SIGMA_MAX)
        if rapid is not None:
            self.rapid_override = min(max(float(rapid), 0.0), 1.0)

    def release_pause(self) -> None:
        """Continue after a pause point (M00, single block, dwell elapsed, ...)."""
        if self.paused is not None:
            if self.paused.kind is PauseKind.DWELL:
                # the dwell is timed by the caller
                self.tau = min(self.tau + self.paused.payload_as(Dwell).seconds, self.t_end)
            self.paused = None
            self.sigma_start = True

    @property
    def standing(self) -> bool:
        return self.sigma == 0.0 and self.sigma_dot == 0.0

    @property
    def in_tap(self) -> bool:
        """The plan is inside a tap (past its start, before its end: the tool in the hole).
        At a move's start (a pause point: the spindle reversing at the bottom) it is inside
        when the move before is the tap's too."""
        locks = self._locks
        if locks is None or not self.n_moves:
            return False
        seg = self.seg
        row = int(np.searchsorted(seg.t0, self.tau, side="right")) - 1
        if row < 0:
            return False
        move = int(seg.table.index[row])
        if not locks[move] & FEED_HOLD_DEFERRED:
            return False
        return self.tau > float(seg.t0[row]) or (move > 0 and bool(locks[move - 1] & FEED_HOLD_DEFERRED))

    @property
    def hold_deferred(self) -> bool:
        """A feed hold asked for, waiting until the tap runs out of the hole (where it ends at
        rest, and the hold takes it)."""
        return self.hold and self.hold_waits_for_tap and self.in_tap

    @property
    def holding(self) -> bool:
        """The hold acts now: sigma goes to 0, or is 0."""
        return self.hold and not self.hold_deferred

    @property
    def held(self) -> bool:
        """Held still on the path."""
        return self.holding and self.standing

    # ------------------------------------------------------------------ evaluation
    def evaluate(self, tau: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """The plan in closed form at arbitrary planned times: (q, line, move index, cumulative
        s). No state: for looking up where planned time tau is."""
        seg = self.seg
        m, s = seg.state(np.asarray(tau, dtype=float))
        q = seg.table.positions(m, s)
        return q, seg.table.line[m].astype(np.int64), seg.table.index[m].astype(np.int64), seg.s0[m] + s

    def _interpolate(self, tau: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Set-points at the scaled planned times, by the plan's interpolation (as ``evaluate``,
        but Taylor carries its state from one set-point to the next)."""
        seg = self.seg
        q, m, s = self.interp.at(seg, tau)
        return q, seg.table.line[m].astype(np.int64), seg.table.index[m].astype(np.int64), seg.s0[m] + s

    def _local_bounds(self) -> None:
        st = self.stats
        horizon = max(0.3, 1.2 * SIGMA_MAX * self.time_to_ramp_s)
        st.ensure(self.tau + horizon + 0.1)
        w = st.window(self.tau, self.tau + 0.25)
        # both results below are functions of the blocks a window covers (computed once, never
        # changed) and of the key they are kept under: the feeder asks every few set-points,
        # the blocks change every 16
        key_b = (w.start, w.stop)
        if self._bounds_memo[0] != key_b:
            self._bounds_memo = (key_b, self._window_bounds(w))
        self._bounds = self._bounds_memo[1]
        # target: override per block kind, capped (3), over the braking distance ahead
        w2 = st.window(self.tau, self.tau + horizon)
        holding = self.holding
        if w2.stop <= w2.start:
            self._target_cache = 0.0 if holding else min(self.feed_override, 1.0)
            return
        bt = self.ts * BLOCK
        nxt = self.pauses[self._pause_i] if self._pause_i < len(self.pauses) else None
        # (the block tau is in matters only when starting from a standstill of the plan)
        key_e = (w2.start, w2.stop, int(self.tau / bt) if self.sigma_start else -1, self.feed_override,
                 self.rapid_override, nxt.tau_s if nxt is not None else None,
                 self.budget.k_a, self.budget.k_j)
        if self._envelope_memo[0] != key_e:
            self._envelope_memo = (key_e, self._envelope(w2, nxt))
        e = self._envelope_memo[1]
        assert e is not None
        dist = e.start_tau - self.tau
        sig = max(self.sigma, 1e-3, 0.0 if holding else e.x_max)
        # braking starts only after sigma_dot has ramped up: at most D1 / (0.7 d2_ref) of real
        # time, less for a small drop (a triangle: 2 sqrt(drop / (0.7 d2_ref))); the envelope is
        # honoured over the planned time sigma covers meanwhile
        dl = 0.7 * self.d2_ref
        drop = max(sig - e.env_min, 0.0)
        lead = sig * min(e.d1_first / dl, 2.0 * np.sqrt(drop / dl)) * 1.3 + 2 * bt
        ahead = dist <= lead
        self._target_cache = float(e.env[ahead].min()) if ahead.any() else float(e.env[0])
        binding = ahead
        # what the operator asked for and the limits refuse here (reported, not an error)
        fixed = bool(e.has_fixed[binding].any())
        self.override_off_here = fixed
        asked = (1.0 if fixed else self.feed_override) if e.has_feed[binding].any() \
            or not e.has_rapid[binding].any() else self.rapid_override
        self.capped_to = self._target_cache if not holding and self._target_cache < asked - 1e-3 \
            and self._target_cache >= 1.0 else None

    def _window_bounds(self, w: slice) -> tuple[float, float, float, float, float, float]:
        """The largest normalised v, a, j and alpha, beta, gamma over the blocks ``w``."""
        c = self.stats.cols
        if w.stop <= w.start:
            return (0.0, 0.0, 0.0, 1e-9, 1e-9, 1e-9)
        return (float(c["rv"][w].max()), float(c["ra"][w].max()), float(c["rj"][w].max()),
                max(float(c["alpha"][w].max()), 1e-9), max(float(c["beta"][w].max()), 1e-9),
                max(float(c["gamma"][w].max()), 1e-9))

    def _envelope(self, w2: slice, nxt: PausePoint | None) -> _Envelope:
        """The highest sigma at each block of ``w2`` from which every cap ahead can be met."""
        st = self.stats
        c = st.cols
        k_a, k_j = self.budget.k_a, self.budget.k_j
        rv = c["rv"][w2]
        ra = c["ra"][w2]
        rj = c["rj"][w2]
        with np.errstate(divide="ignore"):
            cap = np.minimum(np.minimum(1.0 / rv, np.sqrt(k_a / ra)), np.cbrt(k_j / rj))
        cap = np.maximum(np.nan_to_num(cap, nan=SIGMA_MAX, posinf=SIGMA_MAX), 1.0)
        hr = st.has_rapid[w2]
        hf = st.has_feed[w2]
        # where the program turned the feed override off (tapping, M49, M50 P0) the feed is its own
        feed = np.where(st.has_fixed[w2], 1.0, self.feed_override)
        tgt = np.minimum(np.where(hf, feed, SIGMA_MAX),
                         np.where(hr, self.rapid_override, SIGMA_MAX))
        tgt = np.where(hr | hf, tgt, self.feed_override)
        x = np.minimum(cap, tgt)
        bt = self.ts * BLOCK
        start_tau = (np.arange(w2.start, w2.stop) * bt)
        if nxt is not None:
            # the plan stands at a pause point, and sigma starts again from the target there:
            # nothing after it is braked for (a tap at 100 % runs so to its end, its exact stop)
            x = np.where(start_tau > nxt.tau_s, SIGMA_MAX, x)
        if self.sigma_start:
            # starting from a standstill of the plan: what the blocks behind it ran at is past
            x = np.where(start_tau + bt <= self.tau, SIGMA_MAX, x)
        # The highest sigma at each block from which every cap ahead can still be met: braking at
        # the rate D1 the step bounds will allow there (for sigma >= 1 the worst of (1): the
        # largest |q'|/A and |q''|/J over the 0.25 s window the steps look at), in planned time
        # d(sigma^2)/d(tau) = -2 D1, with a 0.7 margin. A backward pass as a suffix minimum:
        # env_j^2 = min over i >= j of (x_i^2 + 2 (C_i - C_j)), C = cumulated 0.7 D1 bt.
        alpha_b = np.maximum(c["alpha"][w2], 1e-9)
        beta_b = np.maximum(c["beta"][w2], 1e-9)
        d1_b = np.minimum((1.0 - k_a) / alpha_b, (1.0 - k_j) / (6.0 * beta_b))
        span = min(BLOCK + 2, len(d1_b))
        pad = np.concatenate([d1_b[:1], d1_b, np.repeat(d1_b[-1:], span)])
        d1_w = np.lib.stride_tricks.sliding_window_view(pad, span + 1).min(axis=1)[:len(d1_b)]
        cum = np.concatenate([[0.0], np.cumsum(0.7 * d1_w * bt)[:-1]])
        suffix = np.minimum.accumulate((x * x + 2.0 * cum)[::-1])[::-1]
        env = np.sqrt(np.maximum(suffix - 2.0 * cum, 0.0))
        env = np.where(env >= x * (1.0 - 1e-12), x, env)     # its own cap, exactly (no rounding)
        return _Envelope(start_tau, env, float(env.min()), float(d1_w[0]), min(float(x.max()), SIGMA_MAX),
                         st.has_fixed[w2].copy(), hf.copy(), hr.copy())

    def _step_bounds(self, sigma: float) -> tuple[float, float]:
        rv, ra, rj, alpha, beta, gamma = self._bounds
        k_a, k_j = self.budget.k_a, self.budget.k_j
        m = min(sigma, 1.0)
        ra_u = min(ra, k_a) if sigma <= 1.0 else k_a
        rj_u = min(rj, k_j) if sigma <= 1.0 else k_j
        jr = max(1.0 - rj_u * m**3, 0.0)
        d1 = (1.0 - ra_u * m * m) / alpha
        if m > 0.0:
            d1 = min(d1, jr / (6.0 * beta * m))
        d2 = jr / (2.0 * gamma)
        return max(d1, 0.0), max(d2, 0.0)

    # ------------------------------------------------------------------ generation
    def _try_path_stop(self) -> None:
        """On a hold while moving: plan the time-optimal stop along the path from the current
        (s, v, a) and keep it only if the executed set-points (with the last three before it)
        stay within every limit (``check_limits``)."""
        self._stop_tried = True
        if not self.path_stops or self.sigma <= 0.0 or self.sigma_start:
            return
        nxt = self.pauses[self._pause_i] if self._pause_i < len(self.pauses) else None
        # the stop ends before the next pause point, and within the plan made so far
        tau_limit = min(nxt.tau_s if nxt is not None else self.t_end, self.window.covered_until)
        try:
            stop = plan_path_stop(self.plan, self.machine, self.tau, self.sigma, self.sigma_dot, tau_limit)
        except (ValueError, FloatingPointError, IndexError):  # pragma: no cover - keep the ramp
            stop = None
        if stop is None:
            return
        q0, s0, m0 = self._last
        if len(q0):
            q = np.concatenate([q0, stop.q])
            r = check_limits(q, np.concatenate([s0, stop.s_mm]), np.concatenate([m0, stop.move]),
                             self.machine, self.ts, self._rapid_move, self._rotary_only)
            if max(r[k] for k in ("tangential_v", "tangential_a", "tangential_j", "axis_v", "axis_a",
                                  "axis_j")) > 1.0 + 1e-6:  # as the tests: rounding of v = Vmax
                return
        self._stop = stop
        self._stop_k = 0
        self.stops_taken += 1

    def _next_stop_chunk(self, n: int) -> ScaledChunk:
        st = self._stop
        assert st is not None
        k0, k1 = self._stop_k, min(self._stop_k + n, len(st.q))
        self._stop_k = k1
        sl = slice(k0, k1)
        _, _, _, s_plan = self.evaluate(st.tau[sl])
        v_plan = np.gradient(s_plan) / self.ts if k1 - k0 > 1 else np.full(k1 - k0, 1.0)
        sig = np.clip(st.speed[sl] / np.maximum(np.abs(v_plan), 1e-9), 1e-9, SIGMA_MAX)
        self.tau = float(st.tau[k1 - 1])
        if k1 >= len(st.q):  # at rest on the path: resume ramps sigma up from here
            self._stop = None
            self.sigma, self.sigma_dot = 0.0, 0.0
            sig[-1] = 0.0
            if self.interp.at_state is not None:  # Taylor goes on from where the stop ended, at rest
                self.interp.at_state = (self.tau, float(st.s_mm[-1]), 0.0, 0.0)
        else:
            self.sigma, self.sigma_dot = float(sig[-1]), 0.0
        ch = ScaledChunk(st.q[sl].copy(), st.tau[sl].copy(), sig, st.line[sl].copy(), st.move[sl].copy(),
                         st.s_mm[sl].copy(), None)
        if self._stop is None:
            # one more set-point at rest: the stop's last (sampled) jerk and a resume's first
            # never fall into one third difference (a resume requested during the stop measured
            # 1.03-1.05 J_max across that junction without it)
            q, tau, sigma, line, move, s_mm = (np.concatenate([a, a[-1:]]) for a in (ch.q, ch.tau, ch.sigma,
                                                                                   ch.line, ch.move, ch.s_mm))
            ch = ScaledChunk(q, tau, sigma, line, move, s_mm, None)
        self._remember(ch)
        return ch

    def _remember(self, ch: ScaledChunk) -> None:
        q0, s0, m0 = self._last
        self._last = (np.concatenate([q0, ch.q])[-3:], np.concatenate([s0, ch.s_mm])[-3:],
                      np.concatenate([m0, ch.move])[-3:])

    def generate(self, n: int) -> ScaledChunk | None:
        """Up to ``n`` set-points; fewer when a pause point or the end is reached. None when
        paused (call ``release_pause``) or finished."""
        if self.finished or self.paused is not None or n <= 0:
            return None
        if not self.window.done or self.window.first_move:
            # as far as this call can go and the braking looks ahead; back to where a splice
            # may rewind to (the set-points queued in the worker, well under a second)
            reach = n * self.ts * SIGMA_MAX + 1.2 * SIGMA_MAX * self.time_to_ramp_s + 1.0
            self._advance_window(self.tau - KEEP_BEHIND_S, self.tau + reach)
        # a deferred hold (a tap in the hole) acts once the tap has ended, at a pause point:
        # ``generate`` returns there, so this holds for the whole call
        holding = self.holding
        if not holding:
            self._stop_tried = False
        elif self._stop is None and not self._stop_tried:
            self._try_path_stop()
        if self._stop is not None:
            return self._next_stop_chunk(n)
        ts = self.ts
        taus = np.empty(n)
        sigmas = np.empty(n)
        pause: PausePoint | None = None
        k = 0
        while k < n:
            if k % 16 == 0:
                self._local_bounds()
            d2_ref = self.d2_ref
            target = 0.0 if holding else self._target_cache
            sigma, sd = self.sigma, self.sigma_dot
            if self.sigma_start and not holding:
                # at a standstill of the plan itself: start directly at the target (the plan's
                # speed and acceleration are zero here, see the module docstring)
                sigma, sd = target, 0.0
                self.sigma = sigma  # the jump happens at the standstill, not over the step
                self.sigma_start = False
            elif self.sigma_start and holding:
                sigma, sd = 0.0, 0.0
            else:
                d1, d2 = self._step_bounds(sigma)
                e = target - sigma
                if abs(e) < 0.5 * d2_ref * ts * ts and abs(sd) < d2_ref * ts:
                    sigma, sd = target, 0.0
                else:
                    # discrete-time braking law with 70 % of the worst-case sigma_ddot: the largest
                    # sigma_dot from which steps of dl * ts stop within |e| (no overshoot)
                    dl = 0.7 * d2_ref
                    want = math.copysign(
                        min(d1, dl * ts * (math.sqrt(2.0 * abs(e) / (dl * ts * ts) + 0.25) - 0.5)), e)
                    acc = min(max((want - sd) / ts, -d2), d2)
                    # no hard clip of sigma_dot to D1: a tighter D1 appears at the window's far edge
                    # (0.25 s of plan ahead) and is reached at the rate D2, well before it applies
                    sd_new = sd + acc * ts
                    sigma_new = sigma + sd_new * ts  # semi-implicit Euler, as the braking law assumes
                    if (target - sigma_new) * e < 0.0 and abs(sd_new) <= 1.9 * d2_ref * ts:
                        sigma_new, sd_new = target, 0.0  # would cross the target: land on it
                    if sigma_new <= 0.0:
                        sigma_new, sd_new = 0.0, 0.0
                    sigma, sd = sigma_new, sd_new
            tau_new = self.tau + 0.5 * (self.sigma + sigma) * ts
            self.sigma, self.sigma_dot = sigma, sd
            nxt = self.pauses[self._pause_i] if self._pause_i < len(self.pauses) else None
            limit_tau = nxt.tau_s if nxt is not None else self.t_end
            if tau_new >= limit_tau:
                tau_new = limit_tau
                self.tau = tau_new
                taus[k] = tau_new
                sigmas[k] = sigma
                k += 1
                if nxt is not None:
                    pause = nxt
                    self._pause_i += 1
                    self.paused = nxt
                    if nxt.kind is PauseKind.END or limit_tau >= self.t_end:
                        self.finished = nxt.kind is PauseKind.END or self._pause_i >= len(self.pauses)
                else:
                    self.finished = True
                self.sigma_dot = 0.0
                break
            self.tau = tau_new
            taus[k] = tau_new
            sigmas[k] = sigma
            k += 1
        taus = taus[:k]
        q, line, move, s = self._interpolate(taus)
        ch = ScaledChunk(q, taus, sigmas[:k].copy(), line, move, s, pause)
        self._remember(ch)
        return ch

    def progress(self) -> float:
        return 1.0 if self.t_end <= 0 else min(self.tau / self.t_end, 1.0)


_PAUSE_KINDS = {kind: PauseKind(kind.value) for kind in (
    EventKind.PAUSE, EventKind.OPTIONAL_PAUSE, EventKind.TOOL_CHANGE, EventKind.DWELL, EventKind.SPINDLE,
    EventKind.END, EventKind.TOOL_SET, EventKind.OFFSETS, EventKind.OUTPUT, EventKind.TOOL_DATA,
    EventKind.PROBE_START, EventKind.PROBE, EventKind.INPUT, EventKind.TAPPING)}


class PauseFeed:
    """The pause points of a program's plan, segment by segment in order as they are made
    (``points_in``): from its stopping events, every block end in single-block mode (the plan
    must then have been made with exact stops), and its end."""

    def __init__(self, program: Program, single_block: bool, optional_stop: bool) -> None:
        self.n = len(program.moves)
        self.single_block = single_block
        events = [ev for ev in program.events
                  if ev.kind in _PAUSE_KINDS and ev.after_move < self.n
                  and (optional_stop or ev.kind is not EventKind.OPTIONAL_PAUSE)
                  # events before the first move act at the start (dwell: the plan's timeline
                  # starts after it)
                  and not (ev.after_move < 0 and ev.kind is EventKind.DWELL)]
        self._events = sorted(events, key=lambda ev: ev.after_move)
        self._next = 0

    def points_in(self, seg: Segment) -> list[PausePoint]:
        """The pause points within ``seg`` (the next segment of the plan)."""
        n_seg = len(seg.table)
        if n_seg == 0:
            return []
        lo = int(seg.table.index[0])
        hi = lo + n_seg
        t_end_move = seg.t0 + seg.profiles.duration
        pts: list[PausePoint] = []
        events = self._events
        while self._next < len(events) and events[self._next].after_move < hi:
            ev = events[self._next]
            self._next += 1
            i = ev.after_move
            tau = float(t_end_move[i - lo]) if i >= 0 else 0.0
            pts.append(PausePoint(tau, _PAUSE_KINDS[ev.kind], ev.line, max(i, 0), ev.payload, ev.message))
        if self.single_block:
            lines = seg.table.line
            pts.extend(PausePoint(float(t_end_move[r]), PauseKind.SINGLE_BLOCK, int(lines[r]), lo + r)
                       for r in range(min(n_seg, self.n - 1 - lo)))
        pts.sort(key=lambda p: (p.tau_s, p.line))
        if hi >= self.n:
            pts.append(PausePoint(float(seg.t_end), PauseKind.END, int(seg.table.line[-1]), self.n - 1))
        return pts


def pause_points(plan: Plan, single_block: bool, optional_stop: bool) -> list[PausePoint]:
    """Pause points of a whole plan (``PauseFeed`` over its one segment)."""
    if not len(plan.segment.table):
        return []
    return PauseFeed(plan.program, single_block, optional_stop).points_in(plan.segment)
