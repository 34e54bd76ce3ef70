"""The simulated machine around the simulated drives: terminals, switches and forced inputs.

``SimIo`` is the part of ``SimBus`` that answers for the terminals (``ethercat.terminals``)
and for the switches of a simulated machine:

- A *switch* is an input bit (of a terminal, or of a drive's 0x60FD) that reads ``level``
  while an axis stands within a range of its drive's own position (axis units as the drive
  counts them, before any homing offset): a limit switch near the end of travel, a home
  switch, each as a real cam closes a contact. Given as ``SimSwitch`` records when the bus is
  made (``SimBus(switches=...)``), evaluated every cycle from the drives' actual positions.
- A *forced* input holds a bit at a level until released (``inject("terminal_input", k,
  input_value(bit, level))``, ``"drive_input"`` for a drive's 0x60FD): the E-stop chain
  opened, the door opened, a button pressed. A forced bit wins over a switch.
- Every other input bit of a terminal reads its *rest* word (``SimBus(input_rest=...)``): the
  level a healthy machine shows (chain closed, door closed, air on).
- Outputs are kept as written (``terminal_outputs``): a test reads the coolant valve there.
- An encoder terminal counts ``encoder_counts`` injected (``inject("encoder_add", k, n)``, a
  handwheel turned), 16 bit as the EL5101's counter.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from .errors import ConfigurationError
from .terminals import TerminalKind, TerminalSpec

__all__ = ["SimIo", "SimSwitch", "input_value"]

#: ``inject("terminal_input" | "drive_input", index, value)``: bits 0-4 the bit, bit 5 the
#: level, bit 6 set: release the bit (back to its switch or rest level)
RELEASE = 1 << 6


def input_value(bit: int, level: bool, release: bool = False) -> int:
    """The ``value`` of an input injection (see ``RELEASE``)."""
    return (int(bit) & 31) | int(bool(level)) << 5 | (RELEASE if release else 0)


@dataclass(frozen=True, slots=True)
class SimSwitch:
    """A switch: bit ``bit`` of terminal ``terminal`` (or of drive ``drive``'s 0x60FD when
    ``terminal`` < 0) reads ``level`` while axis ``axis`` stands within [lo, hi] (axis units
    of the drive's own count), else the other level."""

    axis: int
    bit: int
    lo: float
    hi: float
    level: bool = True
    terminal: int = -1
    drive: int = -1

    def __post_init__(self) -> None:
        if not 0 <= self.bit < 32:
            raise ConfigurationError(f"simulated switch on bit {self.bit}: bits are 0..31")
        if not self.lo <= self.hi:
            raise ConfigurationError(
                f"simulated switch of axis {self.axis}: range [{self.lo}, {self.hi}] is empty")
        if (self.terminal < 0) == (self.drive < 0):
            raise ConfigurationError("a simulated switch sits on one terminal or one drive")


class SimIo:
    """Terminals and switches of a simulated bus (see the module docstring)."""

    def __init__(self, terminals: Sequence[TerminalSpec], n_drives: int, units_per_count: Sequence[float],
                 switches: Sequence[SimSwitch] = (), input_rest: Sequence[int] = ()) -> None:
        self.terminals = tuple(terminals)
        m = len(self.terminals)
        self.n_drives = n_drives
        rest = list(input_rest) + [0] * (m - len(input_rest))
        if len(rest) != m:
            raise ConfigurationError(f"{len(input_rest)} rest words for {m} terminals")
        self.rest = np.array(rest, dtype=np.uint32)
        for s in switches:
            if not 0 <= s.axis < n_drives:
                raise ConfigurationError(f"simulated switch on axis {s.axis}: there are {n_drives} drives")
            if s.terminal >= m or s.drive >= n_drives:
                raise ConfigurationError(f"simulated switch on terminal {s.terminal} / drive {s.drive}: "
                                         "no such slave")
            if s.terminal >= 0 and self.terminals[s.terminal].kind is not TerminalKind.DIGITAL_IN:
                raise ConfigurationError(f"simulated switch on {self.terminals[s.terminal].label}: "
                                         "not a digital input terminal")
        # the switches as arrays: axis, its units per count (signed), target word (terminals
        # first, then drives), mask, level, range in axis units
        self.switches = tuple(switches)
        upc = np.asarray(units_per_count, dtype=float)
        self._sw_axis = np.array([s.axis for s in switches], dtype=np.int64)
        self._sw_upc = np.array([upc[s.axis] for s in switches], dtype=float)
        self._sw_lo = np.array([s.lo for s in switches], dtype=float)
        self._sw_hi = np.array([s.hi for s in switches], dtype=float)
        self._sw_word = np.array([s.terminal if s.terminal >= 0 else m + s.drive for s in switches],
                                 dtype=np.int64)
        self._sw_mask = np.array([1 << s.bit for s in switches], dtype=np.int64)
        self._sw_level = np.array([s.level for s in switches], dtype=bool)
        # forced bits per word (terminals, then drives): mask and levels
        self.forced_mask = np.zeros(m + n_drives, dtype=np.int64)
        self.forced_bits = np.zeros(m + n_drives, dtype=np.int64)
        self.counts = np.zeros(m, dtype=np.int64)
        self.outputs = np.zeros(m, dtype=np.uint64)

    @property
    def active(self) -> bool:
        """Whether drive inputs need this part's word (switches or forced bits on drives)."""
        return bool(self.switches) or bool(self.forced_mask[len(self.terminals):].any())

    def force(self, word: int, value: int) -> None:
        mask = 1 << (value & 31)
        if value & RELEASE:
            self.forced_mask[word] &= ~mask
            self.forced_bits[word] &= ~mask
            return
        self.forced_mask[word] |= mask
        if value >> 5 & 1:
            self.forced_bits[word] |= mask
        else:
            self.forced_bits[word] &= ~mask

    def words(self, position_counts: np.ndarray, drive_words: np.ndarray) -> np.ndarray:
        """Every input word of this cycle: terminals' first, then the drives' 0x60FD as the
        drives give them with switches and forced bits laid over. ``position_counts``: the
        drives' actual positions (raw counts, direction as the drive counts)."""
        m = len(self.terminals)
        out = np.empty(m + self.n_drives, dtype=np.int64)
        out[:m] = self.rest
        out[m:] = drive_words
        if self.switches:
            pos = position_counts[self._sw_axis] * self._sw_upc
            inside = (pos >= self._sw_lo) & (pos <= self._sw_hi)
            # switches on one bit are in parallel (normally open) or in series (normally
            # closed): the bit reads its switches' level while any of them is closed
            closed: dict[tuple[int, int], tuple[bool, bool]] = {}
            for w, mask, level, hit in zip(self._sw_word.tolist(), self._sw_mask.tolist(),
                                           self._sw_level.tolist(), inside.tolist()):
                was = closed.get((w, mask))
                closed[(w, mask)] = (level, hit or (was is not None and was[1]))
            for (w, mask), (level, hit) in closed.items():
                out[w] = out[w] | mask if hit == level else out[w] & ~mask
        out = (out & ~self.forced_mask) | (self.forced_bits & self.forced_mask)
        return out

    def encoder_add(self, k: int, counts: int) -> None:
        if not 0 <= k < len(self.terminals) or self.terminals[k].kind is not TerminalKind.ENCODER:
            raise ConfigurationError(f"terminal {k} is not an encoder terminal")
        self.counts[k] = (int(self.counts[k]) + counts) & 0xFFFF
