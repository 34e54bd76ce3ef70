"""The overrides in one model (``controller.overrides``): the operator's feed, rapid and spindle
overrides (the knobs, in percent: the panel's, a scenario's, any other source sets them through
the controller's commands, which refuse a value outside its range with the reason), the program's
lock on the spindle override (M48-M53 and taps turn it off: the spindle turns at S whatever the
knob says), and the spindle's cap (S x override never beyond the spindle's maximum speed).

The feed override's lock is the program's too (``Program.override_locks``): the time scale reads
it per move, where the path stands (``app.machine.motion.timescale``); its cap is the machine's
limits, which the time scale holds above 100 %.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

__all__ = ["FEED_MAX_PCT", "Override", "Overrides", "SPINDLE_MAX_PCT", "SPINDLE_MIN_PCT"]

#: the feed override's top: above 100 % the machine's limits cap the speed
FEED_MAX_PCT = 200.0
#: the spindle override's range
SPINDLE_MIN_PCT = 50.0
SPINDLE_MAX_PCT = 150.0


@dataclass(frozen=True, slots=True)
class _Range:
    low_pct: float
    high_pct: float


class Override(enum.Enum):
    """One of the three overrides, with its range."""

    FEED = _Range(0.0, FEED_MAX_PCT)
    RAPID = _Range(0.0, 100.0)
    SPINDLE = _Range(SPINDLE_MIN_PCT, SPINDLE_MAX_PCT)

    def refusal(self, percent: float) -> str:
        """Why ``percent`` cannot be set ("" when it can); each sentence whole, as the panel
        translates it."""
        r = self.value
        if r.low_pct <= percent <= r.high_pct:
            return ""
        if self is Override.FEED:
            return f"feed override must be 0-{r.high_pct:g} %, got {percent:g}"
        if self is Override.RAPID:
            return f"rapid override must be 0-{r.high_pct:g} %, got {percent:g}"
        return f"spindle override must be {r.low_pct:g}-{r.high_pct:g} %, got {percent:g}"


class Overrides:
    """The knobs (percent), the program's spindle lock, and the spindle's cap."""

    def __init__(self) -> None:
        self._pct = {o: 100.0 for o in Override}
        # the running program turned the spindle override off here (tapping, M49, M51 P0)
        self.spindle_locked = False

    @property
    def feed_pct(self) -> float:
        return self._pct[Override.FEED]

    @property
    def rapid_pct(self) -> float:
        return self._pct[Override.RAPID]

    @property
    def spindle_pct(self) -> float:
        """The spindle knob as set (``spindle_pct_at``: what the spindle takes)."""
        return self._pct[Override.SPINDLE]

    def set(self, override: Override, percent: float) -> str:
        """The knob of ``override`` to ``percent``; why not ("" when set)."""
        why = override.refusal(float(percent))
        if not why:
            self._pct[override] = float(percent)
        return why

    def lock_spindle(self, locked: bool) -> bool:
        """The program turned the spindle override off (True) or on again from here; whether
        that changed anything."""
        changed = locked != self.spindle_locked
        self.spindle_locked = locked
        return changed

    def spindle_pct_at(self, rpm: float, max_rpm: float) -> float:
        """The override the spindle takes at S ``rpm``: the knob's, or 100 % where the program
        locked it; capped so that S x override never exceeds ``max_rpm``."""
        top = 100.0 * max_rpm / rpm if rpm > 0 else SPINDLE_MAX_PCT
        return min(100.0 if self.spindle_locked else self.spindle_pct, top)
