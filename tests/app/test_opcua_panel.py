"""The panel tells where its OPC UA server serves, and warns when it serves without security."""

from __future__ import annotations

import asyncio
from pathlib import Path
from typing import Any

from asyncua import Client
from PySide6.QtWidgets import QLabel

from opcua_server.browse import find_machine
from tests.opcua.conftest import free_port


def test_the_diagnostics_page_says_where_the_server_is_and_warns_of_security_none(
        qtbot: Any, qapp: Any, tmp_path: Path, dialogs: Any) -> None:
    from app.context import PanelOptions
    from app.machine.controller import MachineController
    from opcua_server.settings import OpcUaOverride
    from tests.app.conftest import make_window

    port = free_port()
    state = tmp_path / "state"
    ctl = MachineController(None, state_dir=state, worker_mode="manual", opcua=OpcUaOverride(port, True))
    try:
        window = make_window(qtbot, qapp, PanelOptions(state_dir=state, opcua_port=port, opcua_insecure=True),
                             dialogs, ctl)
        label = window.findChild(QLabel, "opcuaLabel")
        assert label is not None
        qtbot.waitUntil(lambda: (ctl.status.publish(), "serving" in label.text())[1], timeout=60000)
        assert f"opc.tcp://127.0.0.1:{port}/" in label.text()
        assert "security None" in label.text() and label.property("warning") is True

        async def read() -> str:
            async with Client(f"opc.tcp://127.0.0.1:{port}/") as c:
                return (await (await find_machine(c)).read_browse_name()).Name

        assert asyncio.run(read()) == ctl.config.machine.name
    finally:
        ctl.shutdown()
