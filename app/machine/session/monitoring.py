"""The OPC UA server beside the controller (``[opcua]``, or the command line's override).

The server runs in its own thread and reads the status snapshots this part hands it (one
reference per publication: the controller never waits for it). What becomes of the server is
told back in the controller's thread at the next poll: a failure to start (the port in use, a
certificate that cannot be made) is a warning alarm naming the key, and the machine runs on.
A new configuration with other ``[opcua]`` settings restarts it.
"""

from __future__ import annotations

import threading
from importlib import metadata
from pathlib import Path

from app.machine.config import MachineConfig
from app.machine.infra.events import MachineEvents
from app.machine.model import ControllerSnapshot, Severity
from app.machine.ports import AlarmSink, Settings
from opcua_server.server import OpcUaServer, ServerStatus
from opcua_server.settings import OpcUaOverride, OpcUaSettings

__all__ = ["RemoteMonitoring"]


def software_revision() -> str:
    try:
        return metadata.version("cnc-panel")
    except metadata.PackageNotFoundError:
        return "unknown"


class RemoteMonitoring:
    def __init__(self, settings: Settings, state_dir: Path, alarms: AlarmSink, events: MachineEvents,
                 override: OpcUaSettings | OpcUaOverride | None = None) -> None:
        """``override``: settings instead of the configuration's, or the command line's
        changes to it."""
        self._settings, self._state_dir, self._alarms = settings, state_dir, alarms
        self._override = override
        self._server: OpcUaServer | None = None
        self._latest: ControllerSnapshot | None = None
        self._reported: ServerStatus | None = None
        self._pending: ServerStatus | None = None
        self._lock = threading.Lock()
        events.shutdown.connect(self.stop)
        events.config_changed.connect(self._config_changed)

    @property
    def settings(self) -> OpcUaSettings:
        configured = self._settings.config.opcua
        if isinstance(self._override, OpcUaOverride):
            return self._override.apply(configured)
        return self._override if self._override is not None else configured

    @property
    def status(self) -> ServerStatus | None:
        """The server's status (None when it is not enabled)."""
        return self._server.status if self._server is not None else None

    @property
    def server(self) -> OpcUaServer | None:
        return self._server

    def start(self, snapshot: ControllerSnapshot | None) -> None:
        s = self.settings
        if not s.enabled or self._server is not None:
            return
        cfg = self._settings.config
        axes = tuple((a.name, a.rotary) for a in cfg.machine.axes)
        name = cfg.machine.name or "Machine"
        self._server = OpcUaServer(s, software_revision(), axes, name, self._state_dir,
                                   on_status=self._told)
        if snapshot is not None:
            self._server.publish(snapshot)
        self._server.start()

    def publish(self, snapshot: ControllerSnapshot) -> None:
        self._latest = snapshot
        server = self._server
        if server is not None:
            server.publish(snapshot)

    def stop(self) -> None:
        server, self._server = self._server, None
        if server is not None:
            server.stop()

    def _told(self, status: ServerStatus) -> None:      # the server's thread
        with self._lock:
            self._pending = status

    def poll(self, _snapshot: object = None) -> None:
        """In the controller's thread: a server that failed is an alarm (once per failure)."""
        with self._lock:
            status, self._pending = self._pending, None
        if status is None or status == self._reported:
            return
        self._reported = status
        if status.error:
            self._alarms.raise_alarm("opcua",
                                     f"{status.error}; the machine runs on without its OPC UA server",
                                     Severity.WARNING, "opcua_failed")

    def _config_changed(self, config: MachineConfig, axes_changed: bool) -> None:
        server = self._server
        if server is not None and server.settings == self.settings and not axes_changed:
            return
        self.stop()
        self.start(self._latest)
