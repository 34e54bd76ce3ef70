"""The OPC UA server in its own thread and event loop.

The controller hands it each status snapshot with ``publish`` (one reference assignment:
nothing waits); the server's loop reads the newest at most ``rate_hz`` times a second, writes
what changed into the address space and sends the alarm and message events. A failure to
start (port in use, a bad certificate) is reported in ``status`` and through ``on_status``,
never raised into the caller: the machine keeps running without its server.
"""

from __future__ import annotations

import asyncio
import logging
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from asyncua import Server, ua
from asyncua.crypto.security_policies import SecurityPolicyBasic256Sha256, SecurityPolicyNone

from machine_status import ControllerSnapshot
from opcua_server.channel import GuardedServer, SessionGuard, TrustedClients
from opcua_server.diagnostics import Diagnostics
from opcua_server.errors import OpcUaError
from opcua_server.ids import nid
from opcua_server.mapping import MessageTracker, ProgramTracker, view_of
from opcua_server.model import MachineToolModel
from opcua_server.settings import Identity, OpcUaSettings, SecurityMode
from planner.core.gcpause import gc_paused

__all__ = ["OpcUaServer", "ServerStatus"]

_log = logging.getLogger(__name__)

#: how often the server's diagnostics summary is counted again
_DIAGNOSTICS_PERIOD_S = 1.0

_POLICY_TYPES = {SecurityMode.SIGN_AND_ENCRYPT: ua.SecurityPolicyType.Basic256Sha256_SignAndEncrypt,
                 SecurityMode.SIGN: ua.SecurityPolicyType.Basic256Sha256_Sign,
                 SecurityMode.NONE: ua.SecurityPolicyType.NoSecurity}
#: the secure channel each mode's endpoint takes: its policy URI and message security mode
_SECURE = SecurityPolicyBasic256Sha256.URI
_CHANNELS = {SecurityMode.SIGN_AND_ENCRYPT: (_SECURE, ua.MessageSecurityMode.SignAndEncrypt),
             SecurityMode.SIGN: (_SECURE, ua.MessageSecurityMode.Sign),
             SecurityMode.NONE: (SecurityPolicyNone.URI, ua.MessageSecurityMode.None_)}


@dataclass(frozen=True, slots=True)
class ServerStatus:
    running: bool = False
    endpoint: str = ""
    error: str = ""                # why it is not serving ("" while it is or before it started)
    thumbprint: str = ""           # the server certificate's SHA-1 ("" with security None alone)
    security: str = ""             # what ``OpcUaSettings.describe`` says
    clients: int = 0


class _ReadOnlyRules:
    """Every request of a reading client and none that changes anything: no write, no node
    added or deleted, no history update, and no method call but ConditionRefresh and
    ConditionRefresh2 (which replay the active alarms to the caller's subscription). Opening a
    session is open to anyone; the rest needs a session activated by a user (or anonymously,
    when that is allowed)."""

    def __init__(self) -> None:
        from asyncua.crypto.permission_rules import USER_TYPES, UserRole

        ids = ua.ObjectIds
        session = {ids.CreateSessionRequest_Encoding_DefaultBinary,
                   ids.ActivateSessionRequest_Encoding_DefaultBinary,
                   ids.CloseSessionRequest_Encoding_DefaultBinary,
                   ids.GetEndpointsRequest_Encoding_DefaultBinary,
                   ids.FindServersRequest_Encoding_DefaultBinary,
                   ids.CloseSecureChannelRequest_Encoding_DefaultBinary}
        refused = {ids.WriteRequest_Encoding_DefaultBinary, ids.CallRequest_Encoding_DefaultBinary}
        self._open = {nid(t) for t in session}
        self._reading = {nid(t) for t in USER_TYPES if t not in refused}
        self._call = nid(ids.CallRequest_Encoding_DefaultBinary)
        self._refresh = {nid(ids.ConditionType_ConditionRefresh), nid(ids.ConditionType_ConditionRefresh2)}
        self._user = UserRole.User

    def check_validity(self, user: object, action_type_id: object, body: Any) -> bool:
        if action_type_id in self._open:
            return True
        if getattr(user, "role", None) is not self._user:
            return False
        if action_type_id == self._call:
            return self._refreshes_only(body)
        return action_type_id in self._reading

    def _refreshes_only(self, body: Any) -> bool:
        from asyncua.ua.ua_binary import struct_from_binary

        try:
            params = struct_from_binary(ua.CallParameters, body.copy())
        except Exception:  # noqa: BLE001 - a request that does not decode calls nothing allowed
            return False
        methods = params.MethodsToCall or []
        return bool(methods) and all(m.MethodId in self._refresh for m in methods)


class OpcUaServer:
    def __init__(self, settings: OpcUaSettings, software_revision: str, axes: tuple[tuple[str, bool], ...],
                 machine_name: str, state_dir: str | Path,
                 on_status: Callable[[ServerStatus], None] | None = None) -> None:
        self.settings, self.software_revision, self.axes = settings, software_revision, axes
        self.machine_name = machine_name or "Machine"
        self.state_dir = Path(state_dir)
        self._on_status = on_status
        self._latest: ControllerSnapshot | None = None
        self._status = ServerStatus(endpoint=settings.endpoint, security=settings.describe())
        self._thread: threading.Thread | None = None
        self._loop: asyncio.AbstractEventLoop | None = None
        self._stop: asyncio.Event | None = None
        self._ready = threading.Event()
        self._started_at = time.monotonic()
        self.updates = 0               # snapshots written into the address space
        self.model: MachineToolModel | None = None    # the address space, once built (its thread)
        self.identity: Identity | None = None         # what it serves as Identification, once built
        self.application_uri = ""                     # its ApplicationUri, once built
        self.guard: SessionGuard | None = None        # who may open a session, once built

    # ------------------------------------------------------------------ the controller's side
    def publish(self, snapshot: ControllerSnapshot) -> None:
        self._latest = snapshot

    @property
    def status(self) -> ServerStatus:
        return self._status

    def start(self) -> None:
        if self._thread is not None:
            return
        self._thread = threading.Thread(target=self._main, name="opcua-server", daemon=True)
        self._thread.start()

    def wait_ready(self, timeout_s: float) -> ServerStatus:
        """Wait until it serves or failed (commissioning and tests; the panel never waits)."""
        self._ready.wait(timeout_s)
        return self._status

    def stop(self, timeout_s: float = 5.0) -> None:
        loop, stop, thread = self._loop, self._stop, self._thread
        if loop is not None and stop is not None and not loop.is_closed():
            try:
                loop.call_soon_threadsafe(stop.set)
            except RuntimeError:        # the loop ended on its own
                pass
        if thread is not None:
            thread.join(timeout_s)
        self._thread = None

    # ------------------------------------------------------------------ the server's thread
    def _set_status(self, status: ServerStatus) -> None:
        self._status = status
        if self._on_status is not None:
            self._on_status(status)

    def _main(self) -> None:
        library = logging.getLogger("asyncua")
        if library.level == logging.NOTSET:     # its notes on the nodesets are not the operator's
            library.setLevel(logging.ERROR)
        one_line_logs()
        loop = asyncio.new_event_loop()
        self._loop = loop
        try:
            loop.run_until_complete(self._serve())
        except OpcUaError as exc:
            self._set_status(ServerStatus(endpoint=self.settings.endpoint, error=str(exc),
                                          security=self.settings.describe()))
        except Exception as exc:  # noqa: BLE001 - the machine runs on without its server
            _log.exception("OPC UA server failed")
            self._set_status(ServerStatus(endpoint=self.settings.endpoint,
                                          error=f"OPC UA server failed: {exc}",
                                          security=self.settings.describe()))
        finally:
            self._ready.set()
            pending = asyncio.all_tasks(loop)      # the sessions' and subscriptions' own tasks
            for task in pending:
                task.cancel()
            if pending:
                loop.run_until_complete(_drain(pending))
            loop.close()

    async def _build(self) -> tuple[Server, MachineToolModel, str]:
        """The server with its endpoint, security and address space (not yet listening), and
        its certificate's thumbprint ("" without one)."""
        from opcua_server.model import build_model
        from opcua_server.security import (
            ReadOnlyUsers,
            UserFile,
            ensure_certificate,
            folder,
            installation_id,
            thumbprint,
        )

        s = self.settings
        base = folder(self.state_dir)
        installation = installation_id(base)
        self.identity = s.identity(self.machine_name, self.software_revision, installation)
        self.application_uri = s.application_uri_for(installation)
        users = UserFile(base / "users")
        server = GuardedServer(user_manager=ReadOnlyUsers(users, s.anonymous))
        await server.init()
        server.iserver.max_session_timeout_ms = s.session_timeout_s * 1000.0
        server.set_endpoint(s.bind_endpoint)
        server.set_server_name(f"cnc-panel OPC UA server ({self.machine_name})")
        await server.set_application_uri(self.application_uri)
        server.set_security_policy([_POLICY_TYPES[m] for m in s.security],
                                   permission_ruleset=_ReadOnlyRules())  # type: ignore[arg-type]
        tokens: list[type] = [ua.UserNameIdentityToken]
        if s.anonymous:
            tokens.append(ua.AnonymousIdentityToken)
        server.set_identity_tokens(tokens)
        print_ = ""
        secure = any(m is not SecurityMode.NONE for m in s.security)
        if secure:
            key, cert = await ensure_certificate(base, self.application_uri)
            await server.load_certificate(str(cert))
            await server.load_private_key(str(key))
            print_ = thumbprint(cert)
        trusted = TrustedClients(base / "trusted", base / "rejected") if secure else None
        server.guard = self.guard = SessionGuard({_CHANNELS[m] for m in s.security}, trusted,
                                                 max_sessions=s.max_clients)
        model = self.model = await build_model(server, self.identity, self.axes, self.machine_name)
        return server, model, print_

    async def _serve(self) -> None:
        self._stop = asyncio.Event()
        s = self.settings
        # the address space is some hundred thousand objects that live as long as the server:
        # built with the collector paused and then frozen, no later full collection walks them
        # (one triggered by the server's own allocations held the GIL, and the panel, 0.1 s)
        with gc_paused(freeze=True):
            server, model, print_ = await self._build()
        programs, messages = ProgramTracker(), MessageTracker()
        snap = self._latest
        if snap is not None:
            await model.update(view_of(snap, programs.state(snap)), 0)
            for event in messages.events(snap):
                await model.emit(event)
        try:
            await server.start()
        except OSError as exc:
            raise OpcUaError(f"OPC UA: cannot listen on {s.bind_endpoint}: {exc.strerror or exc} "
                             f"([opcua] port = {s.port})") from None
        self._set_status(ServerStatus(running=True, endpoint=s.endpoint, thumbprint=print_,
                                      security=s.describe()))
        self._ready.set()
        assert self.guard is not None
        diagnostics = Diagnostics(server, self.guard.counts)
        await diagnostics.enable()
        period = 1.0 / s.rate_hz
        last = snap
        counted = time.monotonic()
        try:
            while not self._stop.is_set():
                try:
                    await asyncio.wait_for(self._stop.wait(), period)
                except TimeoutError:
                    pass
                if time.monotonic() - counted >= _DIAGNOSTICS_PERIOD_S:
                    counted = time.monotonic()
                    await diagnostics.update()
                snap = self._latest
                if snap is None or snap is last:
                    continue
                last = snap
                hours = int((time.monotonic() - self._started_at) // 3600)
                await model.update(view_of(snap, programs.state(snap)), hours)
                for event in messages.events(snap):
                    await model.emit(event)
                self.updates += 1
            snap = self._latest          # what was published while it stopped: the last word
            if snap is not None and snap is not last:
                await model.update(view_of(snap, programs.state(snap)), 0)
        finally:
            await server.stop()
            self._set_status(ServerStatus(endpoint=s.endpoint, security=s.describe()))


class _OneLine(logging.Filter):
    """asyncua's records as one short line: no traceback, nothing of a client's bytes beyond
    ``_LOG_CHARS`` (a malformed message would otherwise be logged whole, with its stack)."""

    def filter(self, record: logging.LogRecord) -> bool:
        if record.exc_info or record.exc_text:
            exc = record.exc_info[1] if record.exc_info else None
            record.msg = f"{record.getMessage()} ({type(exc).__name__})" if exc else record.getMessage()
            record.args, record.exc_info, record.exc_text = (), None, None
        text = record.getMessage()
        if len(text) > _LOG_CHARS or "\n" in text:
            text = " ".join(text.split())
            record.msg = text[:_LOG_CHARS] + (" ..." if len(text) > _LOG_CHARS else "")
            record.args = ()
        return True


_LOG_CHARS = 200
_ONE_LINE = _OneLine()


def one_line_logs() -> None:
    """Every asyncua logger (their modules are imported by now) logs through ``_OneLine``."""
    names = [n for n in logging.root.manager.loggerDict if n == "asyncua" or n.startswith("asyncua.")]
    for name in names:
        logger = logging.getLogger(name)
        if _ONE_LINE not in logger.filters:
            logger.addFilter(_ONE_LINE)


async def _drain(tasks: set[asyncio.Task[object]]) -> None:
    await asyncio.gather(*tasks, return_exceptions=True)
