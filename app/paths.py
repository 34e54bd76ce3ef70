"""Where the panel finds its shipped files and keeps its state. A leaf: no Qt, nothing of app/."""

from __future__ import annotations

import os
from pathlib import Path

from resources import PROGRAMS, STYLES, TRANSLATIONS, shipped_machine, shipped_program

__all__ = ["DEFAULT_CONFIG", "DEFAULT_STATE_DIR", "DEMO_PROGRAM", "PROGRAMS", "STYLES", "TRANSLATIONS"]

DEMO_PROGRAM = shipped_program("pocket.nc")
DEFAULT_CONFIG = shipped_machine("xyz_mill")
# Positions, offsets, homed flags, alarms and panel settings persist here unless --state-dir
# names another folder (XDG's state directory: it survives updates, unlike a cache).
DEFAULT_STATE_DIR = Path(os.path.expanduser("~/.local/state/cnc-panel"))
