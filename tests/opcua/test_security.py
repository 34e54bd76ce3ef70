"""The secure-only server through asyncua's client driven step by step: a session is opened
only on a channel of a security an endpoint offers, by a client that proved the key of a
trusted certificate; every refusal reads nothing, and a refused certificate is filed."""

from __future__ import annotations

import asyncio
import shutil
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from asyncua import Client, ua
from asyncua.crypto import uacrypto

from opcua_server.browse import find_machine
from tests.opcua.conftest import ClientThread, Served, make_served

PASSWORD = "correct horse"


def client_certificate(folder: Path, uri: str = "urn:test:client") -> tuple[Path, Path]:
    from asyncua.crypto.cert_gen import setup_self_signed_certificate
    from cryptography.x509.oid import ExtendedKeyUsageOID

    folder.mkdir(parents=True, exist_ok=True)
    key, cert = folder / "client_key.pem", folder / "client_cert.der"
    asyncio.run(setup_self_signed_certificate(key, cert, uri, "localhost", [ExtendedKeyUsageOID.CLIENT_AUTH],
                                              {"commonName": "test client"}))
    return key, cert


class Secure:
    """A secure-only server (Basic256Sha256 SignAndEncrypt, users only) with one user and,
    unless ``trust`` is False, one trusted client certificate."""

    def __init__(self, served: Served, base: Path, key: Path, cert: Path) -> None:
        self.served, self.base, self.key, self.cert = served, base, key, cert
        self.server_cert = base / "server_cert.der"

    def client(self) -> Client:
        """A client of the user, not yet secured (``secure`` sets its certificate)."""
        c = Client(self.served.url, timeout=10)
        c.application_uri = "urn:test:client"
        c.set_user("mes")
        c.set_password(PASSWORD)
        return c

    async def secure(self, c: Client, key: Path | None = None, cert: Path | None = None) -> None:
        await c.set_security_string(
            f"Basic256Sha256,SignAndEncrypt,{cert or self.cert},{key or self.key},{self.server_cert}")

    @property
    def rejected(self) -> list[Path]:
        return sorted((self.base / "rejected").glob("*.der"))

    @property
    def refused(self) -> int:
        server = self.served.ctl.remote.server
        assert server is not None and server.guard is not None
        return server.guard.counts.security_rejected


def _make(qapp: Any, tmp_path: Path, trust: bool) -> Secure:
    from opcua_server.security import UserFile, folder

    state = tmp_path / "state"
    base = folder(state)
    UserFile(base / "users").add("mes", PASSWORD)
    key, cert = client_certificate(tmp_path / "client")
    if trust:
        shutil.copy(cert, base / "trusted" / "client.der")
    served = make_served(qapp, state, secure=True)
    return Secure(served, base, key, cert)


@pytest.fixture
def secure(qapp: Any, tmp_path: Path) -> Iterator[Secure]:
    s = _make(qapp, tmp_path, trust=True)
    yield s
    s.served.ctl.shutdown()


async def _read(c: Client) -> str:
    """The machine's serial number, read over the session the client holds."""
    machine = await find_machine(c)
    di = await c.get_namespace_index("http://opcfoundation.org/UA/DI/")
    serial = await machine.get_child([f"{di}:Identification", f"{di}:SerialNumber"])
    return str(await serial.read_value())


def _status(exc: BaseException) -> str:
    return type(exc).__name__


async def _steps_to_channel(c: Client) -> None:
    await c.connect_socket()
    await c.send_hello()
    await c.open_secure_channel()


def test_a_trusted_client_with_its_key_reads_the_machine(secure: Secure, client_thread: ClientThread) -> None:
    async def attempt() -> str:
        c = secure.client()
        await secure.secure(c)
        async with c:
            return await _read(c)

    assert client_thread.run(attempt()).endswith(secure.served.ctl.config.machine.name)
    assert secure.refused == 0 and secure.rejected == []


def test_a_session_over_a_none_channel_is_refused_before_the_password_is_sent(
        secure: Secure, client_thread: ClientThread, monkeypatch: pytest.MonkeyPatch) -> None:
    # a client that goes on over None whatever endpoints the server lists (asyncua's own
    # client would stop at finding no None endpoint; others do not)
    monkeypatch.setattr(Client, "find_endpoint", staticmethod(lambda endpoints, mode, uri: endpoints[0]))

    async def attempt() -> tuple[str, list[str]]:
        c = secure.client()
        sent: list[str] = []
        original = c.uaclient.activate_session

        async def activate(params: Any) -> Any:         # what reaches the wire after CreateSession
            sent.append(type(params.UserIdentityToken).__name__)
            return await original(params)

        c.uaclient.activate_session = activate  # type: ignore[method-assign]
        try:
            await c.connect()
        except Exception as exc:  # noqa: BLE001 - the refusal is what is looked at
            return _status(exc), sent
        try:
            return "read " + await _read(c), sent
        finally:
            await c.disconnect()

    status, sent = client_thread.run(attempt())
    assert status == "BadSecurityPolicyRejected"
    assert sent == []                                   # no ActivateSession, so no password in clear
    assert secure.refused == 1


def test_discovery_stays_open_on_a_none_channel(secure: Secure, client_thread: ClientThread) -> None:
    async def endpoints() -> list[tuple[str, int]]:
        c = Client(secure.served.url, timeout=10)
        found = await c.connect_and_get_server_endpoints()
        return [(e.SecurityPolicyUri.rsplit("#", 1)[-1], int(e.SecurityMode)) for e in found]

    assert client_thread.run(endpoints()) == [("Basic256Sha256", int(ua.MessageSecurityMode.SignAndEncrypt))]


def test_a_trusted_certificate_without_its_key_opens_no_session(secure: Secure,
                                                                client_thread: ClientThread) -> None:
    """A None channel whose CreateSession names the trusted client's certificate (public, so
    anyone may have it): nothing proves the key."""
    async def attempt() -> str:
        c = secure.client()
        c.user_certificate = uacrypto.x509_from_der(secure.cert.read_bytes())
        await _steps_to_channel(c)
        try:
            await c.create_session()
            return "created"
        except ua.UaStatusCodeError as exc:
            return _status(exc)
        finally:
            c.disconnect_socket()

    assert client_thread.run(attempt()) == "BadSecurityPolicyRejected"
    assert secure.refused == 1


def test_create_session_must_name_the_certificate_its_channel_was_opened_with(
        secure: Secure, client_thread: ClientThread, tmp_path: Path) -> None:
    """A channel opened with an untrusted key, its CreateSession naming the trusted
    certificate or none at all: refused, and the channel's own certificate never checked in."""
    other_key, other_cert = client_certificate(tmp_path / "other")

    async def attempt(named: bytes | None) -> str:
        c = secure.client()
        await secure.secure(c, other_key, other_cert)
        await _steps_to_channel(c)
        c.security_policy.host_certificate = named
        try:
            await c.create_session()
            return "created"
        except ua.UaStatusCodeError as exc:
            return _status(exc)
        finally:
            c.disconnect_socket()

    assert client_thread.run(attempt(secure.cert.read_bytes())) == "BadCertificateInvalid"
    assert client_thread.run(attempt(None)) == "BadCertificateInvalid"
    assert secure.refused == 2


def test_an_untrusted_certificate_is_refused_and_filed(secure: Secure, client_thread: ClientThread,
                                                       tmp_path: Path) -> None:
    other_key, other_cert = client_certificate(tmp_path / "other")

    async def attempt() -> str:
        c = secure.client()
        await secure.secure(c, other_key, other_cert)
        try:
            await c.connect()
        except Exception as exc:  # noqa: BLE001 - the refusal is what is looked at
            return _status(exc)
        await c.disconnect()
        return "connected"

    assert client_thread.run(attempt()) == "BadCertificateUntrusted"
    assert [p.read_bytes() for p in secure.rejected] == [other_cert.read_bytes()]


def test_with_no_trusted_certificate_the_first_client_is_refused_and_filed(
        qapp: Any, tmp_path: Path, client_thread: ClientThread) -> None:
    s = _make(qapp, tmp_path, trust=False)
    try:
        async def attempt() -> str:
            c = s.client()
            await s.secure(c)
            try:
                await c.connect()
            except Exception as exc:  # noqa: BLE001 - the refusal is what is looked at
                return _status(exc)
            await c.disconnect()
            return "connected"

        assert client_thread.run(attempt()) == "BadCertificateUntrusted"
        assert [p.read_bytes() for p in s.rejected] == [s.cert.read_bytes()]
        # trusted by moving the file, as README tells the integrator: the next try is served
        s.rejected[0].rename(s.base / "trusted" / "client.der")

        async def again() -> str:
            c = s.client()
            await s.secure(c)
            async with c:
                return await _read(c)

        assert client_thread.run(again()).endswith(s.served.ctl.config.machine.name)
    finally:
        s.served.ctl.shutdown()


def test_a_session_is_not_activated_again_over_a_none_channel(secure: Secure,
                                                              client_thread: ClientThread) -> None:
    """OPC UA's reconnect: ActivateSession for a live session on a new channel. Over a None
    channel it would carry the session's authentication token and password in clear."""
    async def attempt() -> str:
        good = secure.client()
        await secure.secure(good)
        await good.connect()
        try:
            token = good.uaclient.protocol.authentication_token
            thief = secure.client()
            await _steps_to_channel(thief)
            thief.uaclient.protocol.authentication_token = token
            params = ua.ActivateSessionParameters()
            params.UserIdentityToken = ua.AnonymousIdentityToken()
            params.UserIdentityToken.PolicyId = "anonymous"
            try:
                await thief.uaclient.activate_session(params)
                return "activated"
            except ua.UaStatusCodeError as exc:
                return _status(exc)
            finally:
                thief.disconnect_socket()
        finally:
            await good.disconnect()

    assert client_thread.run(attempt()) == "BadSecurityPolicyRejected"
    assert secure.refused == 1
