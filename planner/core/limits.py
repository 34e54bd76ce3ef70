"""The machine's limits as the planner holds them (``LimitSet``), and the shares of them that
curvature may take: what the look-ahead caps a curved move's speed with, and what a blend's
size and speed are judged by."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from planner.core.machine import MachineSpec

__all__ = ["ACCEL_NORMAL_SHARE", "BLEND_CROSS_SHARE", "BLEND_DK_SHARE", "BLEND_NORMAL_SHARE",
           "JERK_CROSS_SHARE", "JERK_NORMAL_SHARE", "KINK_JERK_FLOOR", "LimitSet", "break_budget",
           "joint_step_budget", "kink_caps"]

ACCEL_NORMAL_SHARE = math.cos(math.radians(30.0))  # LinuxCNC's BLEND_ACC_RATIO_NORMAL
JERK_NORMAL_SHARE = 0.5
JERK_CROSS_SHARE = 0.6
# corner blends (clothoid pairs): normal-direction jerk (cross term + v^3 dkappa/ds) <= 0.9 J,
# of which the changing curvature up to 0.8 J; the tangential part then has
# sqrt(1 - 0.9^2) = 0.436 J, of which kappa^2 v^3 takes up to 0.3 J
BLEND_CROSS_SHARE = 0.9
BLEND_DK_SHARE = 0.8
BLEND_NORMAL_SHARE = 0.3
#: the share of an axis' jerk a joint's direction change may always take, however much of it
#: the moves' own jerk uses there: a tenth of the meter's tolerance, so that kinks the size of
#: rounding (1e-9 of a turn) are crossed at speed and no sample is over the limit
KINK_JERK_FLOOR = 1e-5


@dataclass(frozen=True, slots=True)
class LimitSet:
    """Path and axis limits as arrays (per-axis values in mm or deg units). The path limits are
    for moves with a linear axis in them (mm/s ...); ``*_rot`` for moves of rotary axes alone,
    along their rotary distance (deg/s ...; infinite: the axes' own limits govern), as LinuxCNC
    applies F in deg/min to them."""

    v_path: float
    a_path: float
    j_path: float
    rapid_v: float
    ts_s: float
    v_axis: np.ndarray
    a_axis: np.ndarray
    j_axis: np.ndarray
    rotary: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=bool))
    corner_step_mm_s: float = 0.0
    v_path_rot: float = math.inf
    a_path_rot: float = math.inf
    j_path_rot: float = math.inf
    rapid_v_rot: float = math.inf

    @staticmethod
    def from_machine(machine: MachineSpec, ts_s: float | None = None) -> LimitSet:
        lim = machine.limits
        return LimitSet(
            v_path=lim.v_max_mm_s, a_path=lim.a_max_mm_s2, j_path=lim.j_max_mm_s3,
            rapid_v=lim.rapid_mm_s, ts_s=machine.planner.ts_s if ts_s is None else ts_s,
            v_axis=np.array([a.v_motion for a in machine.axes], dtype=float),
            a_axis=np.array([a.a_motion for a in machine.axes], dtype=float),
            j_axis=np.array([a.j_motion for a in machine.axes], dtype=float),
            rotary=np.array([a.rotary for a in machine.axes], dtype=bool),
            corner_step_mm_s=machine.planner.corner_velocity_step_mm_s,
            v_path_rot=lim.v_max_deg_s, a_path_rot=lim.a_max_deg_s2, j_path_rot=lim.j_max_deg_s3,
            rapid_v_rot=lim.rapid_deg_s,
        )

    def rotary_only(self, start: np.ndarray, end: np.ndarray) -> np.ndarray:
        """Per move (rows of ``start``/``end``): whether only rotary axes move in it."""
        if not self.rotary.any() or not len(start):
            return np.zeros(len(start), dtype=bool)
        delta = np.abs(np.asarray(end) - np.asarray(start))
        return ~(delta[:, ~self.rotary] > 0.0).any(axis=1) & (delta[:, self.rotary] > 0.0).any(axis=1)

    def path(self, rotary_only: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Per move: (feed speed cap, acceleration, jerk, rapid speed) along its path."""
        def pick(linear: float, angular: float) -> np.ndarray:
            return np.where(rotary_only, angular, linear)

        return (pick(self.v_path, self.v_path_rot), pick(self.a_path, self.a_path_rot),
                pick(self.j_path, self.j_path_rot), pick(self.rapid_v, self.rapid_v_rot))


def break_budget(lim: LimitSet) -> np.ndarray:
    """Per axis: the acceleration a one-sample direction change may take at a joint (A_k less
    what the profile's jerk may add over two samples, at least a tenth of A_k)."""
    return np.maximum(lim.a_axis - 2.0 * lim.ts_s * lim.j_axis, 0.1 * lim.a_axis)


def joint_step_budget(lim: LimitSet, j_in: np.ndarray, j_out: np.ndarray, t_in: np.ndarray,
                      t_out: np.ndarray) -> np.ndarray:
    """Per joint and axis (n, d): how much the axis' velocity may change in one sample at a
    joint crossed with a change of direction (mm/s).

    A direction change crossed at speed v changes the axis' velocity by v |dt_k| within one
    sample: its third difference is up to v |dt_k| Ts, a jerk of v |dt_k| / Ts^2 on top of the
    jerk the two moves' profiles have there (at most j |t_k|, their path jerk times the axis'
    share of the tangent on either side). What is left of the axis' limit, times Ts^2, is the
    budget (at least ``KINK_JERK_FLOOR`` of the limit); a configured corner velocity step
    (``corner_step_mm_s``) raises it to that step."""
    ts = lim.ts_s
    used = np.maximum(j_in[:, None] * np.abs(t_in), j_out[:, None] * np.abs(t_out))
    room = np.maximum(lim.j_axis[None, :] - used, KINK_JERK_FLOOR * lim.j_axis[None, :])
    return np.maximum(room * ts * ts, lim.corner_step_mm_s)


def kink_caps(dt: np.ndarray, step: np.ndarray) -> np.ndarray:
    """Per joint: the speed whose one-sample velocity change v |dt_k| keeps within ``step``
    (``joint_step_budget``) on every axis; dt (n, d) the change of the unit tangent."""
    with np.errstate(divide="ignore", invalid="ignore"):
        v = np.where(dt > 0.0, step / dt, np.inf)
    return v.min(axis=1) if v.shape[0] else np.zeros(0)
