"""Leadscrew compensation of one axis: backlash and a pitch-error table, as LinuxCNC's
``[JOINT_n]BACKLASH``, ``COMP_FILE`` and ``COMP_FILE_TYPE``.

The table is a text file of lines ``nominal forward reverse`` (machine units, ascending
nominal positions):

- type 0: ``forward`` and ``reverse`` are where the axis really is when commanded to
  ``nominal`` while moving up (down); the correction added is ``nominal - forward``
  (``nominal - reverse``);
- type 1: ``forward`` and ``reverse`` are the corrections themselves.

Blank lines and ``#`` comments are allowed; anything else that is not three numbers is an error
naming the file and the line (LinuxCNC stops reading at such a line and uses what it read).
Backlash ``b`` alone is the table of one line with corrections +b/2 and -b/2 (LinuxCNC's own
reading of BACKLASH).

Between the lines the corrections are interpolated by a natural cubic spline through them, and
beyond the first and last line continued along the spline's end slope. That curve is twice
continuously differentiable everywhere, so a move across the table has bounded jerk from the
correction (LinuxCNC interpolates linearly: at every line the slope changes at once, a jump of
the correction's acceleration and a spike of jerk at every sample that crosses it).

What the correction adds to the axis' motion is bounded by the curve's first three derivatives
(``CompCurve.bounds``) and by how much the slope differs between the two directions (a reversal
switches curves); ``take_up_limits`` gives what is left of a reserved share of the axis' limits
for taking up backlash, after the table's own worst case.
"""

from __future__ import annotations

import bisect
import math
import os
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from .errors import ConfigurationError

__all__ = ["MAX_CORRECTION", "CompCurve", "ScrewComp", "read_comp_file", "take_up_limits"]

#: the largest correction a table may hold (axis units): a bigger value is a typing error
#: (a type 0 file read as type 1, a digit dropped), not a screw's error
MAX_CORRECTION = 1.0


@dataclass(frozen=True, slots=True)
class CompCurve:
    """A natural cubic spline through ``(x[k], y[k])``: on segment k, with t = x - x[k],
    ``y[k] + b[k] t + c[k] t^2 + d[k] t^3``; beyond the ends the line along the end slope."""

    x: tuple[float, ...]
    y: tuple[float, ...]
    b: tuple[float, ...]
    c: tuple[float, ...]
    d: tuple[float, ...]
    end_slope: float

    @classmethod
    def through(cls, x: Sequence[float] | np.ndarray, y: Sequence[float] | np.ndarray) -> CompCurve:
        xs, ys = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
        n = len(xs)
        if n == 1:
            return cls((float(xs[0]),), (float(ys[0]),), (), (), (), 0.0)
        h = np.diff(xs)
        m = np.zeros(n)                      # second derivatives; natural: 0 at both ends
        if n > 2:
            # tridiagonal system for m[1..n-2] (Thomas algorithm)
            diag = 2.0 * (h[:-1] + h[1:])
            rhs = 6.0 * (np.diff(ys[1:]) / h[1:] - np.diff(ys[:-1]) / h[:-1])
            sub = h[1:-1].copy()
            for k in range(1, n - 2):
                w = sub[k - 1] / diag[k - 1]
                diag[k] -= w * sub[k - 1]
                rhs[k] -= w * rhs[k - 1]
            sol = np.zeros(n - 2)
            sol[-1] = rhs[-1] / diag[-1]
            for k in range(n - 4, -1, -1):
                sol[k] = (rhs[k] - sub[k] * sol[k + 1]) / diag[k]
            m[1:-1] = sol
        b = np.diff(ys) / h - h * (2.0 * m[:-1] + m[1:]) / 6.0
        c = m[:-1] / 2.0
        d = np.diff(m) / (6.0 * h)
        end = float(b[-1] + 2.0 * c[-1] * h[-1] + 3.0 * d[-1] * h[-1] ** 2)
        return cls(tuple(map(float, xs)), tuple(map(float, ys)), tuple(map(float, b)), tuple(map(float, c)),
                   tuple(map(float, d)), end)

    def __call__(self, x: float) -> float:
        """The correction at ``x`` (Python floats only: called every cycle)."""
        xs = self.x
        if len(xs) == 1:
            return self.y[0]
        if x <= xs[0]:
            return self.y[0] + self.b[0] * (x - xs[0])
        if x >= xs[-1]:
            return self.y[-1] + self.end_slope * (x - xs[-1])
        k = bisect.bisect_right(xs, x) - 1
        t = x - xs[k]
        return self.y[k] + t * (self.b[k] + t * (self.c[k] + t * self.d[k]))

    def bounds(self, lo: float, hi: float) -> tuple[float, float, float]:
        """The largest |y'|, |y''| and |y'''| over [lo, hi] (and the whole table)."""
        if len(self.x) == 1:
            return 0.0, 0.0, 0.0
        b, c, d, x = (np.array(v) for v in (self.b, self.c, self.d, self.x))
        h = np.diff(x)
        d1 = np.maximum(np.abs(b), np.abs(b + 2.0 * c * h + 3.0 * d * h * h))
        with np.errstate(divide="ignore", invalid="ignore"):
            t_vertex = np.where(d != 0.0, -c / (3.0 * d), -1.0)       # where y'' = 0 inside
        inside = (t_vertex > 0.0) & (t_vertex < h)
        d1 = np.where(inside, np.maximum(d1, np.abs(b + 2.0 * c * t_vertex + 3.0 * d * t_vertex ** 2)), d1)
        first = max(float(d1.max()), abs(self.end_slope) if hi > x[-1] else 0.0,
                    abs(float(b[0])) if lo < x[0] else 0.0)
        second = float(np.abs(np.append(2.0 * c, 0.0)).max())
        third = float(np.abs(6.0 * d).max())
        return first, second, third


@dataclass(frozen=True, slots=True)
class ScrewComp:
    """One axis' corrections: added to its set-points moving up (``forward``) and down
    (``reverse``), at machine positions; ``source`` says where they came from (the operator's
    words: "backlash 0.02", "x.comp")."""

    forward: CompCurve
    reverse: CompCurve
    source: str

    @classmethod
    def backlash(cls, backlash: float) -> ScrewComp:
        if not (math.isfinite(backlash) and 0.0 <= backlash <= MAX_CORRECTION):
            raise ConfigurationError(f"backlash {backlash:g}: 0 .. {MAX_CORRECTION:g}")
        return cls(CompCurve.through([0.0], [backlash / 2.0]), CompCurve.through([0.0], [-backlash / 2.0]),
                   f"backlash {backlash:g}")

    @property
    def nominal(self) -> tuple[float, ...]:
        return self.forward.x

    def bounds(self, lo: float, hi: float) -> tuple[float, float, float, float]:
        """Over the travel [lo, hi]: the largest |y'|, |y''|, |y'''| of either curve and the
        largest difference of the two slopes at one place (what a reversal switches)."""
        f, r = self.forward.bounds(lo, hi), self.reverse.bounds(lo, hi)
        diff = CompCurve.through(self.forward.x, np.subtract(self.forward.y, self.reverse.y))
        return max(f[0], r[0]), max(f[1], r[1]), max(f[2], r[2]), diff.bounds(lo, hi)[0]

    def largest(self, lo: float, hi: float) -> float:
        """The largest |correction| over the travel, from the curves at its ends, at every line
        and at 2001 points between (a check of the file, not a bound to the last digit)."""
        xs = np.concatenate([[lo, hi], np.clip(self.forward.x, lo, hi), np.linspace(lo, hi, 2001)])
        return float(max(abs(c(float(x))) for c in (self.forward, self.reverse) for x in xs))


def read_comp_file(path: str | os.PathLike[str], file_type: int, travel: tuple[float, float]) -> ScrewComp:
    """The table in ``path`` (LinuxCNC's COMP_FILE of ``file_type`` 0 or 1) for an axis with the
    travel ``travel``; ConfigurationError naming the file and line of the first problem."""
    if file_type not in (0, 1):
        raise ConfigurationError(f"{path}: COMP_FILE_TYPE {file_type}: 0 (actual positions) "
                                 "or 1 (corrections)")
    try:
        with open(path, encoding="utf-8") as fh:
            lines = fh.read().splitlines()
    except (OSError, UnicodeDecodeError) as exc:
        raise ConfigurationError(f"{path}: cannot read the compensation table: {exc}") from None
    lo, hi = travel
    nominal: list[float] = []
    forward: list[float] = []
    reverse: list[float] = []
    last_line = 0
    for number, line in enumerate(lines, 1):
        text = line.split("#", 1)[0].strip()
        if not text:
            continue
        where = f"{path}:{number}"
        words = text.split()
        try:
            values = [float(w) for w in words]
        except ValueError:
            values = []
        if len(values) != 3 or not all(math.isfinite(v) for v in values):
            raise ConfigurationError(f"{where}: expected three numbers (nominal forward reverse), "
                                     f"got {text!r}")
        nom, fwd, rev = values
        if nominal and nom <= nominal[-1]:
            raise ConfigurationError(f"{where}: nominal {nom:g} is not above {nominal[-1]:g} on line "
                                     f"{last_line}: the nominal positions must increase")
        if not lo <= nom <= hi:
            raise ConfigurationError(f"{where}: nominal {nom:g} is outside the axis' travel {lo:g} .. {hi:g}")
        if file_type == 0:
            fwd, rev = nom - fwd, nom - rev
        for name, v in (("forward", fwd), ("reverse", rev)):
            if abs(v) > MAX_CORRECTION:
                raise ConfigurationError(f"{where}: the {name} correction {v:g} is beyond "
                                         f"+-{MAX_CORRECTION:g} (type 0 holds actual positions, type 1 "
                                         "corrections)")
        nominal.append(nom)
        forward.append(fwd)
        reverse.append(rev)
        last_line = number
    if not nominal:
        raise ConfigurationError(f"{path}: the compensation table has no lines")
    comp = ScrewComp(CompCurve.through(nominal, forward), CompCurve.through(nominal, reverse),
                     os.path.basename(os.fspath(path)))
    biggest = comp.largest(lo, hi)
    if biggest > MAX_CORRECTION:
        raise ConfigurationError(f"{path}: interpolated over the travel {lo:g} .. {hi:g} the correction "
                                 f"reaches {biggest:.4g}, beyond +-{MAX_CORRECTION:g} (the end slope carried "
                                 "on beyond the table's last line: add lines up to the travel's ends)")
    return comp


def take_up_limits(comp: ScrewComp, travel: tuple[float, float], rated: tuple[float, float, float],
                   share: float, ts_s: float) -> tuple[float, float, float]:
    """The velocity, acceleration and jerk left for taking up a reversal's step (backlash, the
    difference of the two curves) when motion uses ``1 - share`` of the ``rated`` limits and the
    table's own part is at its worst over ``travel``: path + table + take-up stay within
    ``rated``. ConfigurationError when nothing is left."""
    v, a, j = rated
    vp, ap, jp = ((1.0 - share) * x for x in rated)
    d1, d2, d3, dd = comp.bounds(*travel)
    table_v = d1 * vp
    # a reversal switches curves where the sampled velocity is at most ap Ts: the table's
    # velocity steps by dd ap Ts in one sample
    table_a = d2 * vp * vp + d1 * ap + dd * ap
    table_j = d3 * vp ** 3 + 3.0 * d2 * vp * ap + d1 * jp + dd * ap / ts_s
    left = (share * v - table_v, share * a - table_a, share * j - table_j)
    needs = (("velocity", table_v, share * v, "/s"), ("acceleration", table_a, share * a, "/s^2"),
             ("jerk", table_j, share * j, "/s^3"))
    for name, need, have, unit in needs:
        if need >= have:
            raise ConfigurationError(
                f"{comp.source}: at full speed the table's corrections need {need:.4g} units{unit} of "
                f"{name}, more than the reserve of {share:g} leaves ({have:.4g}); raise comp_reserve or "
                "smooth the table")
    return left
