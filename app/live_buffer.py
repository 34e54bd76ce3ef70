"""Preallocated ring buffer for live plots: appended at <= 30 Hz, read as ordered views."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np


class RingBuffer:
    def __init__(self, capacity: int, width: int) -> None:
        self.t = np.zeros(capacity)
        self.values = np.zeros((capacity, width))
        self.capacity = capacity
        self._next = 0
        self._count = 0

    def __len__(self) -> int:
        return self._count

    def clear(self) -> None:
        self._next = self._count = 0

    def append(self, t: float, values: Sequence[float] | np.ndarray) -> None:
        i = self._next
        self.t[i] = t
        self.values[i] = values
        self._next = (i + 1) % self.capacity
        self._count = min(self._count + 1, self.capacity)

    def ordered(self) -> tuple[np.ndarray, np.ndarray]:
        """(t, values) oldest first; a copy only when the buffer has wrapped."""
        if self._count < self.capacity:
            return self.t[: self._count], self.values[: self._count]
        order = np.r_[self._next:self.capacity, 0:self._next]
        return self.t[order], self.values[order]
