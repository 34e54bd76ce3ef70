"""LinuxCNC 2.9's lathe cycles G70 (finishing) and G71/G72 (roughing along Z / along X), the
geometry of ``interp_g7x.cc`` in Python so programs read the same.

A profile is a list of segments in the XZ plane as complex numbers ``z + 1j * x``. The cycles
turn and mirror the profile so that it runs with Z and X decreasing, offset it by the finishing
allowance, and cut it in passes of depth ``i``; the moves come out through a ``Motion`` (the
mirroring undone). Nothing here knows the interpreter: it calls ``Motion.straight``,
``Motion.rapid`` and ``Motion.arc`` with program coordinates.
"""

from __future__ import annotations

import math
from collections.abc import Callable

__all__ = ["G7xError", "Motion", "Profile", "RoundSegment", "StraightSegment", "chamfer", "fillet"]

_TOL = 1e-6
_I = 1j
#: pocket passes above this are an endless loop (LinuxCNC 2.9 loops on some profiles)
_MAX_PASSES = 100_000


class G7xError(Exception):
    """What the cycle cannot do with the profile (LinuxCNC's "G7X error: ...")."""


class Motion:
    """Where the cycle's moves go: ``straight(end)``, ``rapid(end)``, ``arc(ccw, centre, end)``."""

    def __init__(self, straight: Callable[[complex], None], rapid: Callable[[complex], None],
                 arc: Callable[[bool, complex, complex], None]) -> None:
        self.straight, self.rapid, self.arc = straight, rapid, arc


def _norm(c: complex) -> float:
    return c.real * c.real + c.imag * c.imag


def _line_meets_circle(a: complex, b: complex, on_circle: complex, center: complex, near: complex) -> complex:
    """Where the line through ``a`` and ``b`` meets the circle about ``center`` through
    ``on_circle``, of the two points the one nearer ``near`` (the line's nearest point where
    they miss): the line turned onto the real axis at ``b``, as LinuxCNC computes it."""
    rot = (a - b).conjugate() / abs(a - b)
    pe = (on_circle - b) * rot
    pc = (center - b) * rot
    d = _norm(pc - pe) - pc.imag * pc.imag
    d = 0.0 if d < 0 else math.sqrt(d)
    s1 = (pc.real + d) / rot + b
    s2 = (pc.real - d) / rot + b
    return s1 if abs(near - s1) < abs(near - s2) else s2


class _Segment:
    def __init__(self, start: complex, end: complex) -> None:
        self.start, self.end = start, end
        self.finish = 0.0

    def monotonic(self) -> bool:
        return (self.end - self.start).real <= 1e-3

    def do_finish(self, prev: _Segment, nxt: _Segment) -> None:
        pass

    def flip_imag(self) -> None:
        self.start, self.end = self.start.conjugate(), self.end.conjugate()

    def flip_real(self) -> None:
        self.start, self.end = -self.start.conjugate(), -self.end.conjugate()

    def rotate(self) -> None:
        self.start, self.end = -self.start * _I, -self.end * _I

    def move(self, d: complex) -> None:
        self.start += d
        self.end += d

    def corner_finish(self, prev: _Segment, nxt: _Segment) -> complex:
        p, n = prev.dup(), nxt.dup()
        p.offset(self.finish)
        n.offset(self.finish)
        if (p.end - n.start).real > 1e-2:
            self.finish = -self.finish
            p, n = prev.dup(), nxt.dup()
            p.offset(self.finish)
            n.offset(self.finish)
        if (p.end - n.start).real > 1e-2:
            raise G7xError(f"Corner finish failed at ({prev.end.real:g},{prev.end.imag:g})")
        p.intersect(n)
        center = (p.end + n.start) / 2.0
        p.offset(-self.finish)
        n.offset(-self.finish)
        self.start = prev.end = p.end
        self.end = nxt.start = n.start
        return center

    # the rest per kind
    def dup(self) -> _Segment:
        raise NotImplementedError

    def offset(self, distance: float) -> None:
        raise NotImplementedError

    def radius(self) -> float:
        raise NotImplementedError

    def intersect(self, other: _Segment) -> None:
        other.intersect_end(self)

    def intersect_end(self, p: _Segment) -> None:
        raise NotImplementedError

    def intersection_z(self, x: float) -> list[float]:
        raise NotImplementedError

    def draw(self, out: Motion) -> None:
        raise NotImplementedError

    def climb(self, loc: list[complex], out: Motion) -> bool:
        """Along the contour upwards from ``loc[0]``; True where it stops climbing."""
        raise NotImplementedError

    def climb_only(self, loc: list[complex], out: Motion) -> None:
        raise NotImplementedError

    def dive(self, loc: list[complex], x: float, out: Motion, fast: bool) -> bool:
        """Down the contour from ``loc[0]`` to the pass at ``x``; True where it does not dive."""
        raise NotImplementedError


class StraightSegment(_Segment):
    def dup(self) -> _Segment:
        s = StraightSegment(self.start, self.end)
        s.finish = self.finish
        return s

    def draw(self, out: Motion) -> None:
        out.straight(self.end)

    def offset(self, distance: float) -> None:
        d = _I * distance * (self.start - self.end) / abs(self.start - self.end)
        self.start += d
        self.end += d

    def radius(self) -> float:
        return abs(self.start - self.end)

    def intersection_z(self, x: float) -> list[float]:
        s, e = self.start, self.end
        if min(s.imag, e.imag) > x + _TOL or max(s.imag, e.imag) < x - _TOL:
            return []
        if abs((s - e).imag) < _TOL:
            return [s.real, e.real]
        return [(x - s.imag) / (e.imag - s.imag) * (e.real - s.real) + s.real]

    def climb(self, loc: list[complex], out: Motion) -> bool:
        if self.end.imag + _TOL < self.start.imag:
            return True
        if abs(loc[0] - self.start) > _TOL:
            raise G7xError("How did we get here?")
        out.straight(self.end)
        loc[0] = self.end
        return False

    def climb_only(self, loc: list[complex], out: Motion) -> None:
        if self.end.imag < self.start.imag:
            return
        found = self.intersection_z(loc[0].imag)
        if not found:
            return
        loc[0] = complex(found[0], loc[0].imag)
        out.straight(loc[0])
        out.straight(self.end)
        loc[0] = self.end

    def dive(self, loc: list[complex], x: float, out: Motion, fast: bool) -> bool:
        if self.start.imag <= self.end.imag + _TOL:
            return True
        if x < self.end.imag:
            (out.rapid if fast else out.straight)(self.end)
            loc[0] = self.end
            return False
        found = self.intersection_z(x)
        if not found:
            raise G7xError("x too large in straight dive")
        ep = complex(found[0], x)
        (out.rapid if fast else out.straight)(ep)
        loc[0] = ep
        return False

    def intersect_end(self, p: _Segment) -> None:
        if isinstance(p, RoundSegment):          # an arc followed by this line
            if abs(self.start - p.end) >= _TOL:
                self.start = p.end = _line_meets_circle(self.start, self.end, p.end, p.center, self.start)
            return
        rot = (self.start - self.end).conjugate() / abs(self.start - self.end)
        ps = (p.start - self.end) * rot
        pe = (p.end - self.end) * rot
        if (ps - pe).imag == 0:
            raise G7xError("Cannot intersect parallel lines")
        f = ps.imag / (ps - pe).imag
        point = (ps + f * (pe - ps)) / rot + self.end
        self.start = p.end = point


class RoundSegment(_Segment):
    def __init__(self, ccw: bool, start: complex, center: complex, end: complex) -> None:
        super().__init__(start, end)
        self.ccw = bool(ccw)
        self.center = center

    def dup(self) -> _Segment:
        s = RoundSegment(self.ccw, self.start, self.center, self.end)
        s.finish = self.finish
        return s

    def draw(self, out: Motion) -> None:
        out.arc(self.ccw, self.center, self.end)

    def offset(self, distance: float) -> None:
        r = abs(self.start - self.center)
        factor = (r + (1 if self.ccw else -1) * distance) / r
        self.start = factor * (self.start - self.center) + self.center
        self.end = factor * (self.end - self.center) + self.center

    def radius(self) -> float:
        return min(abs(self.start - self.end), abs(self.start - self.center))

    def flip_imag(self) -> None:
        self.ccw = not self.ccw
        super().flip_imag()
        self.center = self.center.conjugate()

    def flip_real(self) -> None:
        self.ccw = not self.ccw
        super().flip_real()
        self.center = -self.center.conjugate()

    def rotate(self) -> None:
        super().rotate()
        self.center = -self.center * _I

    def move(self, d: complex) -> None:
        super().move(d)
        self.center += d

    def monotonic(self) -> bool:
        if self.finish != 0:
            return True
        entry = (self.start - self.center).imag
        leave = (self.end - self.center).imag
        dz = (self.end - self.start).real
        if self.ccw:
            return entry >= -1e-3 and leave >= -1e-3 and dz <= -1e-3
        return entry <= 1e-3 and leave <= 1e-3 and dz <= -1e-3

    def _on_segment(self, p: complex) -> bool:
        a = ((self.start - self.center).conjugate() * (p - self.center)).imag
        b = ((self.end - self.center).conjugate() * (p - self.center)).imag
        if self.ccw:
            return a >= -_TOL and b <= _TOL
        return a <= _TOL and b >= -_TOL

    def intersection_z(self, x: float) -> list[float]:
        r = abs(self.start - self.center)
        c = self.center
        s = -(x - r - c.imag) * (x + r - c.imag)
        if s < -_TOL:
            return []
        s = math.sqrt(max(s, 0.0))
        out = []
        for z in (c.real + s, c.real - s):
            if self._on_segment(complex(z, x)):
                out.append(z)
        return out

    def _top(self) -> complex:
        """Where a counter-clockwise arc ending past its centre is left: its top."""
        if self.end.real < self.center.real:
            return complex(self.center.real, self.center.imag + abs(self.start - self.center))
        return self.end

    def climb(self, loc: list[complex], out: Motion) -> bool:
        if not self.ccw:
            if loc[0].real > self.center.real:
                return True
            if abs(loc[0] - self.end) > 1e-3:
                out.arc(self.ccw, self.center, self.end)
            loc[0] = self.end
            return False
        if loc[0].real < self.center.real:
            return True
        ep = self._top()
        if abs(loc[0] - ep) > 1e-3:
            out.arc(self.ccw, self.center, ep)
        loc[0] = ep
        return True

    def dive(self, loc: list[complex], x: float, out: Motion, fast: bool) -> bool:
        if abs(loc[0] - self.end) < _TOL or (loc[0] - self.end).real <= _TOL:
            loc[0] = self.end
            return False
        found = self.intersection_z(x) or self.intersection_z(x - _TOL)
        if self.ccw:
            if loc[0].real - _TOL > self.center.real:
                return True
            if not found or found[-1] > self.center.real:
                out.arc(self.ccw, self.center, self.end)
                loc[0] = self.end
                return False
            ep = complex(found[-1], x)
            out.arc(self.ccw, self.center, ep)
            loc[0] = ep
            return False
        if loc[0].real <= self.center.real:
            return True                  # climbing already
        if not found:
            out.arc(self.ccw, self.center, self.end)
            loc[0] = self.end
            return False
        if found[0] < self.center.real:
            return False                 # hit at the back only: the pocket steps x down
        ep = complex(found[0], x)
        out.arc(self.ccw, self.center, ep)
        loc[0] = ep
        return False

    def climb_only(self, loc: list[complex], out: Motion) -> None:
        found = self.intersection_z(loc[0].imag)
        if not found:
            return
        if not self.ccw:
            if found[-1] > self.center.real:
                return
            loc[0] = complex(found[-1], loc[0].imag)
            out.straight(loc[0])
            if abs(loc[0] - self.end) > 1e-3:
                out.arc(self.ccw, self.center, self.end)
            loc[0] = self.end
            return
        if found[0] < self.center.real:
            return
        loc[0] = complex(found[0], loc[0].imag)
        out.straight(loc[0])
        ep = self._top()
        if abs(loc[0] - ep) > 1e-3:
            out.arc(self.ccw, self.center, ep)
        loc[0] = ep

    def intersect_end(self, p: _Segment) -> None:
        if isinstance(p, RoundSegment):
            a = abs(self.start - self.center)
            b = abs(p.start - p.center)
            c = abs(self.center - p.center)
            cos_b = (c * c + a * a - b * b) / 2.0 / a / c
            cos_b2 = min(cos_b * cos_b, 1.0)
            rot = complex(cos_b, math.sqrt(1.0 - cos_b2))
            point = rot * (p.center - self.center) / c * a + self.center
            p.end = self.start = point
            return
        if abs(self.start - p.end) >= _TOL:     # a line followed by this arc
            self.start = p.end = _line_meets_circle(p.start, p.end, self.end, self.center, self.start)


class _Fillet(RoundSegment):
    def __init__(self, distance: float, at: complex) -> None:
        super().__init__(False, at, at, at)
        self.finish = distance

    def do_finish(self, prev: _Segment, nxt: _Segment) -> None:
        self.center = self.corner_finish(prev, nxt)
        self.ccw = (self.start - self.center).imag > 0 or (self.end - self.center).imag > 0
        self.finish = 0.0


class _Chamfer(StraightSegment):
    def __init__(self, distance: float, at: complex) -> None:
        super().__init__(at, at)
        self.finish = distance

    def do_finish(self, prev: _Segment, nxt: _Segment) -> None:
        self.corner_finish(prev, nxt)


def fillet(distance: float, at: complex) -> _Segment:
    """A round of ``distance`` at the corner ``at`` (the A word of a profile block)."""
    return _Fillet(distance, at)


def chamfer(distance: float, at: complex) -> _Segment:
    """A chamfer of ``distance`` at the corner ``at`` (the C word of a profile block)."""
    return _Chamfer(distance, at)


def _swapped(out: Motion, state: int) -> Motion:
    """The moves of a turned/mirrored profile as the program's: flip_state undone."""
    conj = state in (1, 2, 5, 6)            # a mirror reverses the arcs' direction

    def f(p: complex) -> complex:
        return {0: p, 1: -p.conjugate(), 2: p.conjugate(), 3: -p, 4: _I * p, 5: (_I * p).conjugate(),
                6: -(_I * p).conjugate(), 7: -_I * p}[state]

    return Motion(lambda e: out.straight(f(e)), lambda e: out.rapid(f(e)),
                  lambda ccw, c, e: out.arc(ccw != conj, f(c), f(e)))


class Profile:
    """The profile's segments (the first runs from the cycle's start point to the profile)."""

    def __init__(self, segments: list[_Segment] | None = None) -> None:
        self.segs: list[_Segment] = segments or []
        self.delta = 0.5
        self.escape = complex(0.3, 0.3)
        self.flip_state = 0
        self.pocket_starts: list[complex] = []
        self._passes = 0

    def copy(self) -> Profile:
        other = Profile([s.dup() for s in self.segs])
        other.delta, other.escape, other.flip_state = self.delta, self.escape, self.flip_state
        return other

    def _rotate(self) -> None:
        for s in self.segs:
            s.rotate()
        self.flip_state ^= 4

    def _swap(self) -> None:
        dir_x = (self.segs[0].end - self.segs[-1].end).imag
        dir_z = (self.segs[0].end - self.segs[-1].end).real
        if dir_x > 0:
            for s in self.segs:
                s.flip_imag()
            self.flip_state ^= 2
        if dir_z < 0:
            for s in self.segs:
                s.flip_real()
            self.flip_state ^= 1

    def _monotonic(self) -> None:
        first = self.segs[0]
        if (first.end - first.start).real > 0:
            first.start = complex(first.end.real, first.start.imag)
        if not all(s.monotonic() for s in self.segs):
            raise G7xError("Not monotonic")

    def _do_finish(self) -> None:
        for k in range(1, len(self.segs) - 1):
            self.segs[k].do_finish(self.segs[k - 1], self.segs[k + 1])
        self.segs = [s for s in self.segs if s.radius() >= 1e-3]

    def g70(self, out: Motion, x: float, z: float, d: float, e: float, p: float) -> None:
        """Finishing passes from distance ``d`` to ``e`` in ``p`` passes, each from (x, z)."""
        self.segs[0].start = complex(z, x)
        path = self.copy()
        path.segs.pop(0)
        path._swap()
        if not all(s.monotonic() for s in path.segs):
            path._rotate()
            path._swap()
        path._monotonic()
        if path.flip_state & 4:
            self._rotate()
        self._swap()
        self._do_finish()
        self._monotonic()
        swapped = _swapped(out, self.flip_state)
        passes = int(p)
        for k in range(passes, 0, -1):
            distance = (k - 1) * (d - e) / p + e
            path = self.copy()
            path._add_distance(distance)
            swapped.rapid(path.segs[0].start)
            swapped.rapid(path.segs[0].end)
            for s in path.segs[1:]:
                s.draw(swapped)

    def g71(self, out: Motion, cycle: int, x: float, z: float, u: float, w: float, d: float, i: float,
            r: float, rotate: bool = False) -> None:
        """Roughing in passes of depth ``i`` (along Z; G72: ``rotate``, along X) down to ``d``
        from the profile moved by (``u``, ``w``), retracting ``r``; ``cycle`` 0 cuts pockets,
        1 does not, 2 only the pockets."""
        self.segs[0].start = complex(z, x)
        if rotate:
            self._rotate()
        self._swap()
        self._do_finish()
        self._monotonic()
        self._add_distance(d)
        for s in self.segs:
            s.move(complex(w, u))
        swapped = _swapped(out, self.flip_state)
        self.delta = max(i, 2 * _TOL)
        self.escape = r * complex(1, 1)
        swapped.rapid(self.segs[0].start)
        if self.segs[-1].end.imag < self.segs[0].start.imag:
            ep = complex(self.segs[-1].end.real, self.segs[0].start.imag)
            self.segs.append(StraightSegment(self.segs[-1].end, ep))
        self.pocket_starts.append(self.segs[0].start)
        self._pocket(cycle, self.segs[0].start, 0, swapped)

    def _pocket(self, cycle: int, location: complex, p: int, out: Motion) -> None:
        segs = self.segs
        loc = [location]
        x = self.pocket_starts[-1].imag
        if cycle == 2:                       # skips the first roughing pass
            while p < len(segs):
                if segs[p].dive(loc, -1e9, out, p == 0):
                    break
                p += 1
            cycle = 3
        while p < len(segs):
            self._passes += 1
            if self._passes > _MAX_PASSES:
                raise G7xError(f"more than {_MAX_PASSES} roughing passes (the cycle does not progress)")
            while x - _TOL > loc[0].imag:
                x -= self.delta
            if segs[p].dive(loc, x, out, p == 0):
                if cycle == 1:               # along the final contour, and done
                    while p < len(segs):
                        segs[p].climb_only(loc, out)
                        p += 1
                else:                        # along the contour to the next pocket, then into it
                    while p < len(segs):
                        if segs[p].climb(loc, out):
                            if cycle == 3:
                                if loc[0].imag > self.pocket_starts[-1].imag and len(self.pocket_starts) > 1:
                                    self.pocket_starts.pop()
                                if len(self.pocket_starts) == 1:
                                    self.pocket_starts.append(loc[0])
                            self._pocket(cycle, loc[0], p, out)
                            return
                        p += 1
                return
            if abs(loc[0].imag - x) > _TOL:  # beyond this segment: on to the next
                p += 1
                continue
            for ip in range(p, len(segs)):
                found = segs[ip].intersection_z(loc[0].imag)
                if not found:
                    continue
                destination_z = found[0] if ip != p else found[-1]
                distance = abs(destination_z - loc[0].real)
                if destination_z - _TOL > loc[0].real:
                    continue                 # the diving curve at the starting point only
                if distance < _TOL:
                    if p == ip:
                        continue
                    if abs(loc[0] - segs[ip].start) < _TOL:
                        p = ip               # another curve, at its entry point
                        break
                    x -= self.delta          # a segment of no length: done
                    break
                dest = complex(destination_z, loc[0].imag)
                out.straight(dest)
                scale = min(1.0, distance / 2 / self.escape.real)
                dest += scale * self.escape
                out.rapid(dest)
                dest = loc[0] - (scale * self.escape).conjugate()
                out.rapid(dest)
                (out.rapid if p == 0 else out.straight)(loc[0])
                x -= self.delta
                break

    def _add_distance(self, distance: float) -> None:
        segs = self.segs
        v1 = segs[0].end - segs[0].start
        v2 = segs[-1].start - segs[0].start
        if (v1 / v2).imag < 0:
            distance = -distance
        first = segs.pop(0)
        current = 0.0
        while current != distance:
            step = min([1e9] + [s.radius() / 2 for s in segs])
            step = min(step, abs(distance - current))
            if distance < 0:
                step = -step
            kept = []
            for s in segs:
                s.offset(step)
                if s.radius() >= 1e-3:
                    kept.append(s)
            segs[:] = kept
            k = 0
            while k < len(segs) - 1:
                p, n = segs[k], segs[k + 1]
                if (p.end - n.start).real > 1e-2:   # a connecting arc
                    s, e = p.dup(), n.dup()
                    s.offset(-step)
                    e.offset(-step)
                    center = (s.end + e.start) / 2.0
                    segs.insert(k + 1, RoundSegment(distance > 0, p.end, center, n.start))
                    k += 1
                k += 1
            k = 0
            while k < len(segs) - 1:
                if not segs[k].monotonic():
                    if k > 0 and segs[k].radius() < segs[k - 1].radius():
                        del segs[k]
                    elif k > 0:
                        del segs[k - 1]
                    else:
                        del segs[k]
                    k = 0
                if k + 1 >= len(segs):
                    break
                if segs[k].radius() < 1e-3:
                    del segs[k]
                    k = 0
                else:
                    segs[k].intersect(segs[k + 1])
                k += 1
            current += step
        for k in range(len(segs) - 1):
            mid = (segs[k].end + segs[k + 1].start) / 2.0
            segs[k].end = segs[k + 1].start = mid
        first.end = segs[0].start
        segs.insert(0, first)
