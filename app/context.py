"""What the panel is started with: options from the command line, resolved once."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

RESOURCES = Path(__file__).resolve().parent.parent / "resources"
DEMO_PROGRAM = RESOURCES / "programs" / "pocket.nc"
DEFAULT_CONFIG = RESOURCES / "machines" / "xyz_mill.toml"


@dataclass(frozen=True, slots=True)
class PanelOptions:
    demo: bool = False
    config_path: Path | None = None
    program_path: Path | None = None
    screenshot_path: Path | None = None
    page: str = "auto"
    language: str = "en"
    width_px: int = 1280
    height_px: int = 800
    state_dir: Path | None = None   # where settings, alarms and positions persist

    @property
    def effective_program(self) -> Path | None:
        if self.program_path is not None:
            return self.program_path
        return DEMO_PROGRAM if self.demo else None
