"""The machine configuration in force and the file it lives in.

At start the configuration is the one given, or the state folder's ``machine.toml`` (the shipped
3-axis mill copied there at the first start). A damaged file with a valid backup is recovered
from the backup and the operator told (``notice``); without one it is an error.
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

from app.machine.config import MachineConfig, load_config, recover_config, save_config
from app.machine.errors import ConfigError
from app.machine.infra.persist import StateStore
from app.machine.model import Budget
from resources import shipped_machine

__all__ = ["MachineSettings"]


class MachineSettings:
    """The applied configuration (``controller.settings``); changed by ``apply`` only."""

    def __init__(self, config: MachineConfig | str | os.PathLike[str] | None, store: StateStore) -> None:
        #: why the configuration at start is not the file as it was ("" when it is)
        self.notice = ""
        if isinstance(config, MachineConfig):
            self.path = Path(config.path) if config.path else store.path("machine.toml")
            self.config = config
            return
        if config is None:
            path = store.path("machine.toml")
            if not path.exists():
                shutil.copyfile(shipped_machine("xyz_mill"), path)
        else:
            path = Path(config)
        self.path = path
        try:
            self.config = load_config(path)
        except ConfigError as exc:
            if exc.backup is None:
                raise
            self.config, text = recover_config(path)
            self.notice = f"machine configuration damaged: {text}"

    @property
    def axes(self) -> tuple[str, ...]:
        """Axis names, in configuration order."""
        return self.config.axes

    @property
    def budget(self) -> Budget:
        """The share of the acceleration and jerk limits a plan may use (the rest is the time
        scale's: overrides and holds within every limit)."""
        c = self.config.controller
        return Budget(k_a=1.0 - c.accel_reserve, k_j=1.0 - c.jerk_reserve)

    def write(self, config: MachineConfig) -> MachineConfig:
        """Validate and write ``config`` atomically (the old file kept as .bak); the
        configuration as written. Raises ConfigError or OSError; nothing applied."""
        return save_config(config, self.path)

    def apply(self, config: MachineConfig) -> None:
        self.config = config
