"""The inputs the loop watches every cycle: the E-stop chain and the limit switches.

All input words of a cycle sit in one array (the drives' 0x60FD first, then the terminals'
inputs); each watch is a word index, a bit mask and the level that makes it *active*. One
cycle evaluates every watch with four NumPy calls on preallocated arrays; only a change (or
an active watch) goes on to Python, which is rare: the loop reacts there (``CycleLoop``).

Limit switches (LinuxCNC's ``joint.N.pos-lim-sw-in`` / ``neg-lim-sw-in``): an axis on its
switch stops the machine unless limits are overridden; while overridden, the axis may move
away from the switch but not toward it (a set-point further toward that side is a stop).
The override ends by itself once no limit switch reads active.
"""

from __future__ import annotations

import numpy as np

from .types import InputWatch, WatchAction

__all__ = ["Watches"]


class Watches:
    """Evaluates the watched inputs of one cycle into ``active`` (a view into the live record)."""

    def __init__(self, watches: tuple[InputWatch, ...], live_watch: np.ndarray) -> None:
        self.watches = watches
        k = len(watches)
        self.k = k
        self.word = np.array([w.word for w in watches], dtype=np.int64)
        self.mask = np.array([1 << w.bit for w in watches], dtype=np.int64)
        self.level = np.array([w.level for w in watches], dtype=bool)
        self.tmp = np.zeros(k, dtype=np.int64)
        self.bits = np.zeros(k, dtype=bool)
        self.active = np.zeros(k, dtype=bool)
        self.live = live_watch[:k]
        self.chain = [i for i, w in enumerate(watches) if w.action is WatchAction.ESTOP_CHAIN]
        self.limits = [i for i, w in enumerate(watches) if w.action is WatchAction.LIMIT]
        self.override = False
        self.chain_was_open = False

    def evaluate(self, words: np.ndarray) -> bool:
        """This cycle's state of every watch; True when one is active."""
        if not self.k:
            return False
        np.take(words, self.word, out=self.tmp)
        np.bitwise_and(self.tmp, self.mask, out=self.tmp)
        np.not_equal(self.tmp, 0, out=self.bits)
        np.equal(self.bits, self.level, out=self.active)
        np.copyto(self.live, self.active, casting="unsafe")
        return bool(self.active.any())

    def chain_open(self) -> bool:
        active = self.active
        return any(active[i] for i in self.chain)

    def blocking_limit(self) -> bool:
        """An axis on a limit switch while limits are not overridden (the drives stay off)."""
        active = self.active
        return not self.override and any(active[i] for i in self.limits)

    def limit_hit(self, moved: np.ndarray) -> InputWatch | None:
        """The limit switch that stops the machine this cycle, or None: an active one when limits
        are not overridden, else one whose axis moved toward it (``moved``: this cycle's
        set-point change per axis). The override ends once no limit reads active."""
        active = self.active
        any_active = False
        for i in self.limits:
            if not active[i]:
                continue
            any_active = True
            w = self.watches[i]
            if not self.override or moved[w.axis] * w.side > 0.0:
                return w
        if not any_active:
            self.override = False
        return None
