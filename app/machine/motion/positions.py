"""Where the axes are: the drives' positions, the home offsets and the homed flags.

Machine coordinates are the drive position less the home offset (set by homing). The poll
writes the positions the drives report; homing and machine zero write the offsets and flags;
nothing else does.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from app.machine.config import MachineConfig
from app.machine.infra.drives import DriveLink
from app.machine.infra.events import MachineEvents, PanelChannels
from app.machine.ports import Settings

__all__ = ["Positions"]


class Positions:
    """Drive positions (actual and last set-point), home offsets, homed flags
    (``controller.positions``)."""

    def __init__(self, settings: Settings, out: PanelChannels, events: MachineEvents,
                 drives: DriveLink) -> None:
        self._out = out
        self._drives = drives
        n = len(settings.config.axes)
        self.raw_pos = np.zeros(n)       # actual, drive units less nothing: machine + home offset
        self.ref_raw = np.zeros(n)       # the last set-point the drives were sent
        self._home_offset = np.zeros(n)
        self._homed = [False] * n
        events.config_changed.connect(self._config_changed)
        events.announce.connect(lambda: self._out.homedChanged.emit(self.homed))

    @property
    def homed(self) -> tuple[bool, ...]:
        return tuple(self._homed)

    @property
    def home_offset(self) -> np.ndarray:
        return self._home_offset

    @property
    def machine_position(self) -> tuple[float, ...]:
        """Actual position, machine coordinates."""
        return tuple(float(x) for x in self.machine_pos())

    @property
    def reference_position(self) -> tuple[float, ...]:
        """Last set-point sent to the drives (machine coordinates)."""
        return tuple(float(x) for x in self.reference_pos())

    def machine_pos(self) -> np.ndarray:
        """Actual position, machine coordinates."""
        return self.raw_pos - self._home_offset

    def reference_pos(self) -> np.ndarray:
        """The last set-point sent to the drives, machine coordinates."""
        return self.ref_raw - self._home_offset

    # ------------------------------------------------------------------ writers
    def update(self, actual: Sequence[float] | np.ndarray, reference: Sequence[float] | np.ndarray) -> None:
        """What the drives report (the poll)."""
        self.raw_pos = np.asarray(actual, dtype=float).copy()
        self.ref_raw = np.asarray(reference, dtype=float).copy()

    def restore(self, raw: Sequence[float], home_offset: Sequence[float], homed: Sequence[bool]) -> None:
        """The state saved at the last shutdown (or power cut)."""
        self.raw_pos = np.array(raw, dtype=float)
        self.ref_raw = self.raw_pos.copy()
        self._home_offset = np.array(home_offset, dtype=float)
        self._homed = [bool(h) for h in homed]

    def unhome_all(self) -> None:
        """Every axis loses its homed state (the position may be lost; not told: the caller
        says why)."""
        self._homed = [False] * len(self._homed)

    def take_actual(self, actual: Sequence[float] | np.ndarray, tolerance: float,
                    unknown: Sequence[int] = ()) -> list[int]:
        """The drives' positions at connect: an axis that reports another position than saved,
        or whose place the positions cannot tell (``unknown``), loses its homed state (the
        indices are returned)."""
        now = np.asarray(actual, dtype=float)
        moved = np.abs(now - self.raw_pos) > max(tolerance, 1e-9)
        moved[list(unknown)] = True
        lost = [i for i, (h, m) in enumerate(zip(self._homed, moved)) if h and m]
        if lost:
            for i in lost:
                self._homed[i] = False
            self._out.homedChanged.emit(self.homed)
        self.raw_pos = now.copy()
        self.ref_raw = now.copy()
        return lost

    def homing_started(self, i: int) -> None:
        self._homed[i] = False
        self._out.homedChanged.emit(self.homed)

    def homed_by_drive(self, i: int) -> None:
        """The drive's homing ended: its own zero is machine zero."""
        self._home_offset[i] = 0.0
        self._homed[i] = True
        self._out.homedChanged.emit(self.homed)

    def homed_at_switch(self, i: int, home_offset: float) -> None:
        """Axis ``i`` homed to its switch: ``home_offset`` makes the latched position the switch's
        machine coordinate."""
        self._home_offset[i] = home_offset
        self._homed[i] = True
        self._out.homedChanged.emit(self.homed)

    def zero_here(self, axes: Sequence[int]) -> None:
        """The current position is machine zero on ``axes``; they are homed."""
        for i in axes:
            self._home_offset[i] = self.raw_pos[i]
            self._homed[i] = True
        self._out.homedChanged.emit(self.homed)

    def _config_changed(self, cfg: MachineConfig, axes_changed: bool) -> None:
        if not axes_changed:
            return
        n = len(cfg.axes)
        self.raw_pos = np.zeros(n) if not self._drives.attached else self.raw_pos[:n]
        self._home_offset = np.zeros(n)
        self._homed = [False] * n
        self._out.homedChanged.emit(self.homed)
