"""``cnc-opcua``: commissioning the OPC UA server.

Prints where the server listens and how (from the machine configuration's ``[opcua]``), the
server certificate's thumbprint (made now if it is missing), the users, the trusted and the
refused client certificates; ``--add-user NAME`` adds a user (password from
``CNC_OPCUA_PASSWORD`` or asked); ``--browse`` connects to the running server as a client
(with this tool's own certificate, trusted in the state folder) and prints the machine's
model, as asyncua's ``uals`` would.
"""

from __future__ import annotations

import argparse
import asyncio
import getpass
import os
import shutil
import sys
from pathlib import Path

from opcua_server.errors import OpcUaError

__all__ = ["main"]


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="cnc-opcua", description="The OPC UA server's endpoint, certificate, "
                                "users and model")
    p.add_argument("--config", type=Path, help="machine configuration TOML (default: the state folder's, "
                   "or the shipped XYZ mill)")
    p.add_argument("--state-dir", type=Path, help="state folder (default: the panel's)")
    p.add_argument("--add-user", metavar="NAME", help="add a user who may read the machine")
    p.add_argument("--browse", action="store_true", help="connect to the running server and print its model")
    p.add_argument("--user", help="user name for --browse (password from CNC_OPCUA_PASSWORD or asked)")
    p.add_argument("--url", help="server to browse (default: the configured endpoint)")
    return p


def _password(prompt: str) -> str:
    return os.environ.get("CNC_OPCUA_PASSWORD") or getpass.getpass(prompt)


def main(argv: list[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    from app.machine.config import MachineConfig, load_config
    from app.machine.errors import ConfigError
    from app.paths import DEFAULT_STATE_DIR
    from opcua_server.security import UserFile, ensure_certificate, folder, installation_id, thumbprint

    state = args.state_dir or DEFAULT_STATE_DIR
    try:
        if args.config:
            cfg = load_config(args.config)
        elif (state / "machine.toml").exists():
            cfg = load_config(state / "machine.toml")
        else:
            cfg = MachineConfig.default()
    except ConfigError as exc:
        print(f"cnc-opcua: {exc}", file=sys.stderr)
        return 2
    s = cfg.opcua
    try:
        base = folder(state)
        users = UserFile(base / "users")
        if args.add_user:
            users.add(args.add_user, _password(f"password for {args.add_user}: "))
            print(f"user {args.add_user} added to {users.path}")
        application_uri = s.application_uri_for(installation_id(base))
        _, cert = asyncio.run(ensure_certificate(base, application_uri))
    except OpcUaError as exc:
        print(f"cnc-opcua: {exc}", file=sys.stderr)
        return 2
    print(f"OPC UA server: {'enabled' if s.enabled else 'disabled ([opcua] enabled = false)'}")
    print(f"endpoint:      {s.describe()}")
    print(f"application:   {application_uri}")
    print(f"certificate:   {cert} (SHA-1 {thumbprint(cert)})")
    print(f"users:         {', '.join(users.names) or 'none (cnc-opcua --add-user NAME)'}")
    for kind in ("trusted", "rejected"):
        names = sorted(p.name for p in (base / kind).iterdir())
        print(f"{kind + ':':14} {', '.join(names) or 'none'}")
    if not args.browse:
        return 0
    url = args.url or s.endpoint
    try:
        lines = asyncio.run(_browse(url, s.insecure and not args.user, args.user, base, cert))
    except Exception as exc:  # noqa: BLE001 - whatever the network says, said once
        print(f"cnc-opcua: no answer from {url}: {exc or type(exc).__name__} (is the panel or cnc-run "
              "serving with [opcua] enabled?)", file=sys.stderr)
        return 1
    print("\n".join(lines))
    return 0


async def _browse(url: str, insecure: bool, user: str | None, base: Path, server_cert: Path) -> list[str]:
    from asyncua import Client
    from asyncua.crypto.cert_gen import setup_self_signed_certificate
    from cryptography.x509.oid import ExtendedKeyUsageOID

    from opcua_server.browse import find_machine, tree

    client = Client(url, timeout=10)
    if not insecure:
        own = base / "cnc-opcua"
        own.mkdir(mode=0o700, exist_ok=True)
        key, cert = own / "key.pem", own / "cert.der"
        await setup_self_signed_certificate(key, cert, "urn:cnc-panel:cnc-opcua", "localhost",
                                            [ExtendedKeyUsageOID.CLIENT_AUTH], {"commonName": "cnc-opcua"})
        shutil.copy(cert, base / "trusted" / "cnc-opcua.der")     # this tool, on the machine itself
        client.application_uri = "urn:cnc-panel:cnc-opcua"
        await client.set_security_string(f"Basic256Sha256,SignAndEncrypt,{cert},{key},{server_cert}")
        name = user or input("user: ")
        client.set_user(name)
        client.set_password(_password(f"password for {name}: "))
    async with client:
        machine = await find_machine(client)
        return [(await machine.read_browse_name()).Name, *await tree(machine, 1)]
