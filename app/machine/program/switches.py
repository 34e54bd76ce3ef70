"""The operator's switches for a run: feed and rapid override (the override model's knobs,
``app.machine.state.overrides``), single block, optional stop and block delete
(``controller.switches``).

They are this part's alone: the motion, the job maker and the loader read them (``RunModes``);
the runner's commands check a change and make it here (``set_*``); the panel hears every change
(overridesChanged, modesChanged) and all of them when the bus comes up.
"""

from __future__ import annotations

from app.machine.infra.events import MachineEvents, PanelChannels
from app.machine.state.overrides import Override, Overrides

__all__ = ["RunSwitches"]


class RunSwitches:
    """Feed and rapid override (percent), single block, optional stop (M01), block delete."""

    def __init__(self, out: PanelChannels, events: MachineEvents, overrides: Overrides) -> None:
        self._out = out
        self._overrides = overrides
        self.single_block = False
        self.optional_stop = False
        # lines starting with '/' skipped; off as LinuxCNC starts. The program is read whole
        # before it runs, so the switch changes the program loaded: it is read again
        self.block_delete = False
        events.announce.connect(self._announce)

    @property
    def feed_pct(self) -> float:
        return self._overrides.feed_pct

    @property
    def rapid_pct(self) -> float:
        return self._overrides.rapid_pct

    def set_overrides(self, feed_pct: float | None = None, rapid_pct: float | None = None) -> str:
        """The feed and rapid knobs (the runner's commands): set, and the panel told; why not
        ("" when set: a value outside its range is refused, the knobs as they were)."""
        why = ""
        for override, pct in ((Override.FEED, feed_pct), (Override.RAPID, rapid_pct)):
            if pct is not None and not why:
                why = self._overrides.set(override, pct)
        self._out.overridesChanged.emit(self.feed_pct, self.rapid_pct)
        return why

    def set_modes(self, single_block: bool | None = None, optional_stop: bool | None = None,
                  block_delete: bool | None = None) -> None:
        """Checked switches (the runner's commands): stored, and the panel told (also when
        nothing changed: a refused switch is shown back as it stands)."""
        if single_block is not None:
            self.single_block = bool(single_block)
        if optional_stop is not None:
            self.optional_stop = bool(optional_stop)
        if block_delete is not None:
            self.block_delete = bool(block_delete)
        self._out.modesChanged.emit(self.single_block, self.optional_stop, self.block_delete)

    def _announce(self) -> None:
        self.set_overrides()
        self.set_modes()
