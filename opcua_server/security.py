"""The server's certificate, its trusted clients and its users, all in the state folder.

``<state>/opcua/``: ``server_key.pem`` (0600) and ``server_cert.der``, made on first start
(self-signed, for the application URI and the host name); ``trusted/`` holds the client
certificates the integrator accepts (DER or PEM), ``rejected/`` the ones that were refused, to
be moved to ``trusted/`` by hand; ``users`` (0600) holds ``name:salt:hash`` lines
(PBKDF2-SHA256), written by ``cnc-opcua --add-user``.
"""

from __future__ import annotations

import hashlib
import hmac
import os
import secrets
import socket
import uuid
from pathlib import Path
from typing import Any

from asyncua.server.user_managers import UserManager

from opcua_server.errors import OpcUaError

__all__ = ["UserFile", "ensure_certificate", "folder", "installation_id", "thumbprint"]

_ITERATIONS = 200_000


def folder(state_dir: str | os.PathLike[str]) -> Path:
    path = Path(state_dir) / "opcua"
    for sub in (path, path / "trusted", path / "rejected"):
        sub.mkdir(mode=0o700, parents=True, exist_ok=True)
    return path


def installation_id(base: Path) -> str:
    """This installation's own id (a UUID made on first start, kept in ``<state>/opcua/installation``):
    two panels, on one host or on copies of one disk image, serve different ApplicationUris and
    ProductInstanceUris unless the configuration names them."""
    path = base / "installation"
    try:
        text = path.read_text(encoding="ascii").strip()
        return str(uuid.UUID(text))
    except (OSError, ValueError, UnicodeDecodeError):
        pass
    made = str(uuid.uuid4())
    tmp = path.with_suffix(".tmp")
    try:
        tmp.write_text(made + "\n", encoding="ascii")
        os.replace(tmp, path)
    except OSError as exc:
        raise OpcUaError(f"cannot keep this installation's id in {path}: {exc.strerror or exc}") from None
    return made


async def ensure_certificate(base: Path, application_uri: str) -> tuple[Path, Path]:
    """The key and certificate, made when either is missing or the certificate does not name
    this host and ``application_uri``."""
    from asyncua.crypto.cert_gen import setup_self_signed_certificate
    from cryptography.x509.oid import ExtendedKeyUsageOID

    key, cert = base / "server_key.pem", base / "server_cert.der"
    old_umask = os.umask(0o077)
    try:
        await setup_self_signed_certificate(
            key, cert, application_uri, socket.gethostname(),
            [ExtendedKeyUsageOID.CLIENT_AUTH, ExtendedKeyUsageOID.SERVER_AUTH],
            {"countryName": "TR", "organizationName": "cnc-panel", "commonName": "cnc-panel OPC UA server"})
    except (OSError, ValueError) as exc:
        raise OpcUaError(f"cannot make the server certificate in {base}: {exc}") from None
    finally:
        os.umask(old_umask)
    key.chmod(0o600)
    return key, cert


def thumbprint(cert_path: Path) -> str:
    """SHA-1 of the DER certificate, as OPC UA tools show it."""
    return hashlib.sha1(cert_path.read_bytes()).hexdigest().upper()


def _hash(password: str, salt: bytes) -> bytes:
    return hashlib.pbkdf2_hmac("sha256", password.encode("utf-8"), salt, _ITERATIONS)


class UserFile:
    """The users who may read the machine (no user may write: the server has nothing to write)."""

    def __init__(self, path: Path) -> None:
        self.path = path
        self._users: dict[str, tuple[bytes, bytes]] = {}
        self.reload()

    def reload(self) -> None:
        users: dict[str, tuple[bytes, bytes]] = {}
        if self.path.exists():
            for n, line in enumerate(self.path.read_text(encoding="utf-8").splitlines(), 1):
                if not line.strip() or line.startswith("#"):
                    continue
                parts = line.split(":")
                if len(parts) != 3:
                    raise OpcUaError(f"{self.path}:{n}: a user line is name:salt:hash")
                try:
                    users[parts[0]] = (bytes.fromhex(parts[1]), bytes.fromhex(parts[2]))
                except ValueError:
                    raise OpcUaError(f"{self.path}:{n}: salt and hash are hexadecimal") from None
        self._users = users

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(sorted(self._users))

    def add(self, name: str, password: str) -> None:
        if not name or ":" in name or name != name.strip():
            raise OpcUaError(f"user name {name!r}: not empty, no ':' and no spaces around it")
        if len(password) < 8:
            raise OpcUaError("the password needs at least 8 characters")
        salt = secrets.token_bytes(16)
        self._users[name] = (salt, _hash(password, salt))
        lines = [f"{n}:{s.hex()}:{h.hex()}" for n, (s, h) in sorted(self._users.items())]
        tmp = self.path.with_suffix(".tmp")
        fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600)
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write("\n".join(lines) + "\n")
        os.replace(tmp, self.path)

    def check(self, name: str | None, password: str | None) -> bool:
        entry = self._users.get(name or "")
        if entry is None or password is None:
            return False
        salt, digest = entry
        return hmac.compare_digest(_hash(password, salt), digest)


class ReadOnlyUsers(UserManager):
    """asyncua's user manager: a known user with the right password, or anonymous when allowed,
    gets the plain User role (read and browse)."""

    def __init__(self, users: UserFile, anonymous: bool) -> None:
        self.users, self.anonymous = users, anonymous

    def get_user(self, iserver: Any, username: str | None = None, password: str | None = None,
                 certificate: Any = None) -> Any:
        from asyncua.crypto.permission_rules import User, UserRole

        if username is None:        # the anonymous token (the only other one the server offers)
            return User(role=UserRole.User) if self.anonymous else None
        if username is not None and self.users.check(username, password):
            return User(role=UserRole.User, name=username)
        return None
