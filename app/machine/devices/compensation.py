"""Leadscrew compensation switched with the homed state: the table is in machine positions, so
the 1 ms loop applies it to an axis only while the axis is homed, with the home offset that
turns its set-points into machine positions (``ethercat.worker.compensation``)."""

from __future__ import annotations

from app.machine.infra.drives import DriveLink
from app.machine.infra.events import MachineEvents, PanelChannels
from app.machine.motion.positions import Positions
from app.machine.ports import Settings

__all__ = ["Compensation"]


class Compensation:
    """Tells the loop, for every compensated axis, whether it is homed and where machine zero
    is, whenever that changes and whenever the bus comes up (``controller.compensation``)."""

    def __init__(self, settings: Settings, drives: DriveLink, positions: Positions, out: PanelChannels,
                 events: MachineEvents) -> None:
        self._settings = settings
        self._drives = drives
        self._positions = positions
        #: per compensated axis: what the loop was told last (homed, home offset)
        self.told: dict[int, tuple[bool, float]] = {}
        out.homedChanged.connect(lambda _homed: self.update())
        events.announce.connect(self._bus_up)
        events.config_changed.connect(lambda _cfg, _axes: self.told.clear())

    def _bus_up(self) -> None:
        self.told.clear()
        self.update()

    def update(self) -> None:
        """Each compensated axis on while homed (off while not), once per change."""
        if not self._drives.attached:
            return
        homed = self._positions.homed
        offsets = self._positions.home_offset
        for spec in self._settings.config.compensation:
            i = spec.axis
            if i >= len(homed):
                continue
            now = (homed[i], float(offsets[i]))
            if self.told.get(i) != now and self._drives.compensate(i, *now):
                self.told[i] = now
