"""Who may open a session, decided where the session is opened.

asyncua serves discovery (GetEndpoints, FindServers) on any secure channel, which OPC UA
requires: a client learns the endpoints over security None before it chooses one. But it
also lets CreateSession and ActivateSession through on a channel of a security the server
does not offer (a None channel to a secure-only server), and it checks a client certificate
only when CreateSession carries one, without asking whether the channel was opened with that
certificate's key. :class:`SessionGuard` closes both:

- a session is created and activated only on a channel whose policy and mode an endpoint
  offers (``BadSecurityPolicyRejected`` otherwise, before the client sends a password);
- on a secure channel, the certificate CreateSession names must be the one the channel was
  opened with (the asymmetric OpenSecureChannel proved its private key), and that
  certificate must be trusted (``trusted/``), valid in time, for its application URI and
  for client use; a refused certificate is kept in ``rejected/``;
- a session activated again on another channel (OPC UA's reconnect) must come over a channel
  opened with the certificate it was created with.

:class:`GuardedServer` is asyncua's server with every connection's processor guarded.
"""

from __future__ import annotations

import asyncio
import hashlib
import logging
import socket
import weakref
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from asyncua import Server, ua
from asyncua.common.utils import ServiceError
from asyncua.crypto import uacrypto
from asyncua.crypto.security_policies import SecurityPolicyNone
from asyncua.server.binary_server_asyncio import BinaryServer, OPCUAProtocol
from asyncua.server.uaprocessor import UaProcessor
from asyncua.ua.ua_binary import struct_from_binary

from opcua_server.ids import nid

__all__ = ["GuardedServer", "SessionGuard", "TrustedClients"]

_log = logging.getLogger(__name__)

_CREATE = nid(ua.ObjectIds.CreateSessionRequest_Encoding_DefaultBinary)
_ACTIVATE = nid(ua.ObjectIds.ActivateSessionRequest_Encoding_DefaultBinary)
_CLOSE = nid(ua.ObjectIds.CloseSessionRequest_Encoding_DefaultBinary)
#: certificates kept in ``rejected/`` at the most (a client retrying with new ones fills no disk)
KEEP_REJECTED = 100
#: connections that wait for an activated session at once, at the most, and how long one may wait
PENDING_CONNECTIONS = 16
PENDING_S = 10.0


class TrustedClients:
    """The client certificate check: valid in time, for its application URI and for client
    use, and trusted (a file in ``trusted/``, read again when that folder changes). A refused
    certificate is kept in ``rejected/`` so the integrator can trust it by moving the file."""

    def __init__(self, trusted: Path, rejected: Path) -> None:
        self.trusted, self.rejected = trusted, rejected
        self._validator: Any = None
        self._stamp: float = -1.0

    async def _current(self) -> Any:
        """The validator over the trusted folder as it is now; None while it holds no
        certificate (then every client is untrusted)."""
        from asyncua.crypto.truststore import TrustStore
        from asyncua.crypto.validator import CertificateValidator, CertificateValidatorOptions

        stamp = self.trusted.stat().st_mtime
        if stamp != self._stamp:
            files = [p for p in self.trusted.iterdir() if p.suffix.lower() in (".der", ".pem")]
            validator = None
            if files:
                store = TrustStore([self.trusted], [])
                await store.load()
                options = (CertificateValidatorOptions.TRUSTED_VALIDATION
                           | CertificateValidatorOptions.PEER_CLIENT)
                validator = CertificateValidator(options, store)
            self._validator, self._stamp = validator, stamp
        return self._validator

    async def check(self, der: bytes, app_description: ua.ApplicationDescription) -> None:
        """Return when the certificate is accepted; raise ``ServiceError`` with the status
        otherwise, the certificate kept in ``rejected/``."""
        try:
            cert = uacrypto.x509_from_der(der)
        except ValueError:
            raise ServiceError(ua.StatusCodes.BadCertificateInvalid) from None
        try:
            validator = await self._current()
            if validator is None:
                raise ServiceError(ua.StatusCodes.BadCertificateUntrusted)
            await validator(cert, app_description)
        except ServiceError:
            self._keep(der)
            raise
        except (OSError, ValueError) as exc:      # a trusted file that cannot be read
            _log.warning("OPC UA: the trusted certificates in %s cannot be read: %s", self.trusted, exc)
            self._keep(der)
            raise ServiceError(ua.StatusCodes.BadCertificateUntrusted) from None

    def _keep(self, der: bytes) -> None:
        try:
            if len(list(self.rejected.glob("*.der"))) < KEEP_REJECTED:
                (self.rejected / f"{hashlib.sha1(der).hexdigest().upper()}.der").write_bytes(der)
        except OSError:
            pass


@dataclass
class GuardCounts:
    """What passed through the guarded connections, for the server's diagnostics
    (ServerDiagnosticsSummary)."""

    security_rejected: int = 0      # sessions refused for the channel's security or certificate
    evicted: int = 0                # connections closed that waited for a session while new ones came
    rejected_sessions: int = 0      # sessions refused for any reason (those above included)
    created_sessions: int = 0
    closed_sessions: int = 0        # ended by the client's CloseSession
    rejected_requests: int = 0      # requests answered with a service fault


class SessionGuard:
    """The checks above, for the endpoints the server offers: ``offered`` holds (policy URI,
    message security mode) pairs; at most ``max_sessions`` connections hold an activated
    session, and at most ``max_pending`` connections wait for one (a new one closes the
    oldest that waits: idle sockets cannot lock real clients out)."""

    def __init__(self, offered: set[tuple[str, ua.MessageSecurityMode]],
                 trusted: TrustedClients | None, max_sessions: int = 64,
                 max_pending: int = PENDING_CONNECTIONS) -> None:
        self.offered = offered
        self.trusted = trusted
        self.max_sessions, self.max_pending = max_sessions, max_pending
        self.counts = GuardCounts()
        # the certificate each live session was created with (None over security None)
        self._created: weakref.WeakKeyDictionary[Any, bytes | None] = weakref.WeakKeyDictionary()

    def _refuse(self, status: int, why: str) -> ServiceError:
        self.counts.security_rejected += 1
        _log.warning("OPC UA: session refused: %s", why)
        return ServiceError(status)

    def _offered(self, policy: Any) -> None:
        if (policy.URI, policy.Mode) not in self.offered:
            raise self._refuse(ua.StatusCodes.BadSecurityPolicyRejected,
                               f"a channel of {policy.URI.rsplit('#', 1)[-1]} {policy.Mode.name}, "
                               "which no endpoint offers")

    async def admit_create(self, policy: Any, params: ua.CreateSessionParameters) -> None:
        self._offered(policy)
        if policy.URI == SecurityPolicyNone.URI:      # nothing signs or encrypts: no certificate to check
            return
        peer = policy.peer_certificate
        if not peer or params.ClientCertificate != peer:
            raise self._refuse(ua.StatusCodes.BadCertificateInvalid,
                               "the client certificate is not the one its channel was opened with")
        if self.trusted is not None:
            try:
                await self.trusted.check(peer, params.ClientDescription)
            except ServiceError as exc:
                raise self._refuse(exc.code, f"the client certificate is not accepted ({exc})") from None

    def created(self, session: Any, policy: Any) -> None:
        self.counts.created_sessions += 1
        self._created[session] = _certificate(policy)

    def admit_activate(self, policy: Any, session: Any) -> None:
        """``session``: the live session the request names (None: unknown, asyncua refuses it)."""
        self._offered(policy)
        if session in self._created and self._created[session] != _certificate(policy):
            raise self._refuse(ua.StatusCodes.BadSecurityChecksFailed,
                               "a session activated over a channel opened with another certificate")


def _certificate(policy: Any) -> bytes | None:
    """The certificate a channel was opened with (None over security None)."""
    return None if policy.URI == SecurityPolicyNone.URI else policy.peer_certificate


def _activated(protocol: OPCUAProtocol) -> bool:
    session = protocol.processor.session if protocol.processor is not None else None
    return session is not None and bool(session.is_activated())


class _GuardedProcessor(UaProcessor):
    def __init__(self, guard: SessionGuard, clients: list[OPCUAProtocol], *args: Any) -> None:
        super().__init__(*args)
        self._guard = guard
        self._clients = clients

    async def _process_message(self, typeid: Any, requesthdr: Any, seqhdr: Any, body: Any) -> Any:
        counts = self._guard.counts
        try:
            return await self._guarded(typeid, requesthdr, seqhdr, body)
        except Exception:
            counts.rejected_requests += 1
            if typeid in (_CREATE, _ACTIVATE):
                counts.rejected_sessions += 1
            raise

    async def _guarded(self, typeid: Any, requesthdr: Any, seqhdr: Any, body: Any) -> Any:
        policy = self._connection.security_policy
        if typeid == _CREATE:
            params = struct_from_binary(ua.CreateSessionParameters, body.copy())
            await self._guard.admit_create(policy, params)
            result = await super()._process_message(typeid, requesthdr, seqhdr, body)
            if self.session is not None:
                self._guard.created(self.session, policy)
            return result
        if typeid == _ACTIVATE:
            session = self.session
            if session is None:
                session = self.iserver.lookup_external_session(requesthdr.AuthenticationToken)
            self._guard.admit_activate(policy, session)
            if session is None or not session.is_activated():
                held = sum(1 for c in self._clients if _activated(c))
                if held >= self._guard.max_sessions:
                    raise ServiceError(ua.StatusCodes.BadTooManySessions)
        elif typeid == _CLOSE and self.session is not None:
            self._guard.counts.closed_sessions += 1
        return await super()._process_message(typeid, requesthdr, seqhdr, body)


class _GuardedProtocol(OPCUAProtocol):
    guard: SessionGuard

    def connection_made(self, transport: asyncio.BaseTransport) -> None:
        waiting = [c for c in self.clients if not _activated(c)]
        for old in waiting[:max(0, len(waiting) - self.guard.max_pending + 1)]:
            if old.transport is not None:
                self.guard.counts.evicted += 1
                old.transport.close()
        super().connection_made(transport)
        if self.processor is not None:           # accepted (not over the connection limit)
            processor = _GuardedProcessor(self.guard, self.clients, self.iserver, self.transport, self.limits)
            processor.set_policies(self.policies)
            self.processor = processor


class _GuardedBinaryServer(BinaryServer):
    def __init__(self, guard: SessionGuard, *args: Any) -> None:
        super().__init__(*args)
        self._guard = guard

    def _make_protocol(self) -> OPCUAProtocol:
        protocol = _GuardedProtocol(iserver=self.iserver, policies=self._policies, clients=self.clients,
                                    closing_tasks=self.closing_tasks, limits=self.limits)
        protocol.guard = self._guard
        return protocol


class GuardedServer(Server):
    """asyncua's server whose connections pass through ``guard`` (set before ``start``)."""

    guard: SessionGuard

    async def start(self) -> None:
        # the guard keeps the sessions and the waiting connections within their own bounds;
        # asyncua's count of connections is their sum
        self.iserver.max_connections = self.guard.max_sessions + self.guard.max_pending
        self.iserver.max_pending_activation_seconds = PENDING_S
        if self.iserver.certificate is not None:
            uacrypto.check_certificate(self.iserver.certificate, self._application_uri, socket.gethostname())
        await self._setup_server_nodes()
        await self.iserver.start()
        try:
            host, port = self._get_bind_socket_info()
            self.bserver = _GuardedBinaryServer(self.guard, self.iserver, host, port, self.limits)
            self.bserver.set_policies(self._policies)
            await self.bserver.start()
        except Exception:
            await self.iserver.stop()
            raise
