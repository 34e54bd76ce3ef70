"""The one error type of the machine controller package (app.machine)."""

from __future__ import annotations

__all__ = ["ConfigError", "MachineError", "StateFolderBusy"]


class MachineError(RuntimeError):
    """Any error raised by the machine controller: a refused command, a bad state, a bus failure."""


class ConfigError(MachineError, ValueError):
    """The machine configuration file is missing, damaged or invalid.

    ``backup`` is the path of the previous good file (``<file>.bak``) when one exists, so the
    panel can offer it; the controller never falls back to silent defaults.
    """

    def __init__(self, message: str, path: str = "", backup: str | None = None) -> None:
        self.path = path
        self.backup = backup
        text = message if backup is None else f"{message} (a backup exists: {backup})"
        super().__init__(text)


class StateFolderBusy(MachineError):
    """Another control already uses this state folder: two controls on one folder would each
    believe their own positions and homed flags and overwrite the other's."""
