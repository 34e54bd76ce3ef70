"""Build the PanelContext: controller on the configured bus, settings, translations."""

from __future__ import annotations

from pathlib import Path

from app.context import PanelContext, PanelOptions
from app.dialogs import Dialogs
from app.i18n import I18n
from app.panel_settings import SettingsStore
from app.program_document import ProgramDocument
from app.program_folders import ProgramFolders
from app.program_model import ProgramModel
from app.service_access import ServiceAccess


def build_context(options: PanelOptions, dialogs: Dialogs | None = None,
                  controller: object | None = None) -> PanelContext:
    from app.machine.controller import MachineController
    from opcua_server.settings import OpcUaOverride

    state_dir = Path(options.effective_state_dir)
    state_dir.mkdir(parents=True, exist_ok=True)
    if controller is None:
        opcua = OpcUaOverride(options.opcua_port, options.opcua_insecure) \
            if options.opcua_port is not None or options.opcua_insecure else None
        controller = MachineController(options.config_path, state_dir=state_dir, opcua=opcua)
    settings = SettingsStore(state_dir)
    context = PanelContext(
        options=options, state_dir=state_dir, controller=controller,  # type: ignore[arg-type]
        i18n=I18n(), settings=settings, dialogs=dialogs or Dialogs(),
        document=ProgramDocument(state_dir), program=ProgramModel(), access=ServiceAccess(settings),
        folders=ProgramFolders(state_dir, options.program_dirs),
    )
    return context
