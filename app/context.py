"""What the panel is started with (options from the command line) and what its pages share."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from app.paths import DEFAULT_STATE_DIR, DEMO_PROGRAM

if TYPE_CHECKING:  # Qt-free at import time: __main__ reads this before Qt may start
    from app.dialogs import Dialogs
    from app.i18n import I18n
    from app.machine.controller import MachineController
    from app.panel_settings import SettingsStore
    from app.program_document import ProgramDocument
    from app.program_folders import ProgramFolders
    from app.program_model import ProgramModel
    from app.service_access import ServiceAccess



@dataclass(frozen=True, slots=True)
class PanelOptions:
    demo: bool = False
    config_path: Path | None = None
    program_path: Path | None = None
    screenshot_path: Path | None = None
    page: str = "auto"
    language: str | None = None   # None: the saved choice (English at first start)
    width_px: int = 1280
    height_px: int = 800
    state_dir: Path | None = None   # where settings, alarms and positions persist
    run_for_s: float = 0.0   # with --screenshot in demo: press cycle start, shoot this much later
    reset_service_password: bool = False   # the integrator's recovery: reset it and exit
    program_dirs: tuple[Path, ...] = ()    # more folders the operator may open and save in
    opcua_port: int | None = None           # --opcua-port: serve OPC UA there (configured security)
    opcua_insecure: bool = False            # --opcua-insecure: security None, 127.0.0.1 only

    @property
    def effective_program(self) -> Path | None:
        if self.program_path is not None:
            return self.program_path
        return DEMO_PROGRAM if self.demo else None

    @property
    def effective_state_dir(self) -> Path:
        return self.state_dir if self.state_dir is not None else DEFAULT_STATE_DIR


@dataclass
class PanelContext:
    """Shared by every page: the controller (commands + signals) and the panel's own models."""

    options: PanelOptions
    state_dir: Path
    controller: MachineController
    i18n: I18n
    settings: SettingsStore
    dialogs: Dialogs
    document: ProgramDocument
    program: ProgramModel
    access: ServiceAccess | None = None   # the service level's lock (set by build_context)
    folders: ProgramFolders | None = None  # where Open and Save as may go (set by build_context)

    @property
    def service_unlocked(self) -> bool:
        return self.access is not None and self.access.unlocked
