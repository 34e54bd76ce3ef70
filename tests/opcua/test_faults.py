"""The server under clients that misbehave, on 127.0.0.1 and bounded in count and time: the
control keeps running, the server keeps answering, and sessions, sockets and threads are given
back."""

from __future__ import annotations

import os
import random
import socket
import struct
import subprocess
import sys
import threading
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from asyncua import Client
from asyncua.server.internal_session import InternalSession

from opcua_server.browse import find_machine
from tests.opcua.conftest import ClientThread, Served, make_served

_VANISHING = """
import asyncio, sys
from asyncua import Client
async def main():
    c = Client(sys.argv[1], timeout=10)
    await c.connect()
    sub = await c.create_subscription(20, None)
    await sub.subscribe_data_change(await c.nodes.objects.get_children())
    print("subscribed", flush=True)
    await asyncio.sleep(60)
asyncio.run(main())
"""


def _fds() -> int:
    return len(os.listdir("/proc/self/fd"))


async def _read_name(url: str) -> str:
    async with Client(url, timeout=10) as c:
        return (await (await find_machine(c)).read_browse_name()).Name


def _wait(cond: Any, limit_s: float = 20.0) -> bool:
    end = time.monotonic() + limit_s
    while time.monotonic() < end:
        if cond():
            return True
        time.sleep(0.05)
    return bool(cond())


@pytest.fixture
def served(qapp: Any, tmp_path: Path) -> Iterator[Served]:
    s = make_served(qapp, tmp_path / "state", session_timeout_s=2.0)
    yield s
    s.ctl.shutdown()


def test_fifty_clients_in_a_row_and_one_that_vanishes_leave_nothing_behind(
        served: Served, client_thread: ClientThread) -> None:
    name = served.ctl.config.machine.name
    assert client_thread.run(_read_name(served.url)) == name
    sessions, fds, threads = InternalSession._current_connections, _fds(), threading.active_count()

    # a client in another process subscribes, then is killed: no CloseSession, no goodbye
    vanishing = subprocess.Popen([sys.executable, "-c", _VANISHING, served.url], stdout=subprocess.PIPE,
                                 text=True)
    try:
        assert vanishing.stdout is not None and vanishing.stdout.readline().strip() == "subscribed"
        served.step(0.2)
    finally:
        vanishing.kill()
        vanishing.wait(10)
    for _ in range(50):
        assert client_thread.run(_read_name(served.url)) == name
    served.step(0.2)
    # the vanished client's session (and its subscription) ends with the session timeout
    assert _wait(lambda: InternalSession._current_connections == sessions)
    assert _wait(lambda: _fds() <= fds + 2), (fds, _fds())
    assert threading.active_count() <= threads + 1
    assert served.ctl.remote.status is not None and served.ctl.remote.status.running


def _hello(size_override: int | None = None) -> bytes:
    url = b"opc.tcp://127.0.0.1/"
    body = struct.pack("<IIIII", 0, 65536, 65536, 0, 0) + struct.pack("<i", len(url)) + url
    size = 8 + len(body) if size_override is None else size_override
    return b"HELF" + struct.pack("<I", size) + body


def test_random_bytes_and_cut_messages_on_the_socket_are_dropped_and_the_server_answers_on(
        served: Served, client_thread: ClientThread) -> None:
    rng = random.Random(40501)
    payloads = [bytes(rng.getrandbits(8) for _ in range(rng.randint(1, 600))) for _ in range(20)]
    hello = _hello()
    payloads += [hello[:5], hello[:12], _hello(size_override=4), _hello(size_override=1 << 30)[:40],
                 b"OPNF" + struct.pack("<I", 200) + b"\x00" * 20, b"MSGF" + struct.pack("<I",
                                                                                        16) + b"\xff" * 8,
                 hello + b"\x00" * 10]
    fds = _fds()
    for data in payloads:
        with socket.create_connection(("127.0.0.1", served.port), timeout=5) as s:
            s.sendall(data)
            s.settimeout(0.3)
            try:
                s.recv(4096)
            except (TimeoutError, ConnectionError):
                pass
    served.step(0.2)
    assert client_thread.run(_read_name(served.url)) == served.ctl.config.machine.name
    assert _wait(lambda: _fds() <= fds + 2), (fds, _fds())
    assert served.ctl.state.value == "idle"


def test_idle_sockets_do_not_lock_real_clients_out(served: Served, client_thread: ClientThread) -> None:
    """200 idle connections (none sends a byte), more than may wait for a session and more
    than the sessions allowed: each new one closes the oldest that waits, and a real client
    still reads the machine."""
    from opcua_server.channel import PENDING_CONNECTIONS

    server = served.ctl.remote.server
    assert server is not None and server.guard is not None
    idle = [socket.create_connection(("127.0.0.1", served.port), timeout=5)
            for _ in range(200)]
    try:
        served.step(0.2)
        assert client_thread.run(_read_name(served.url)) == served.ctl.config.machine.name
        assert server.guard.counts.evicted >= 200 - PENDING_CONNECTIONS
    finally:
        for s in idle:
            s.close()


def _opn_with_policy(uri: bytes) -> bytes:
    """An OpenSecureChannel message naming the security policy ``uri`` (then cut short)."""
    body = struct.pack("<I", 0) + struct.pack("<i", len(uri)) + uri + struct.pack("<ii", -1, -1)
    body += struct.pack("<II", 1, 1) + b"\x01\x00\xbe\x01" + b"\x00" * 40
    return b"OPNF" + struct.pack("<I", 8 + len(body)) + body


def test_a_malformed_message_is_logged_in_one_short_line_without_the_client_s_bytes(
        served: Served, client_thread: ClientThread, caplog: pytest.LogCaptureFixture) -> None:
    import logging

    secret = b"x" * 100_000
    caplog.set_level(logging.ERROR, logger="asyncua")
    with socket.create_connection(("127.0.0.1", served.port), timeout=5) as s:
        s.sendall(_hello() + _opn_with_policy(b"http://opcfoundation.org/UA/SecurityPolicy#" + secret))
        s.settimeout(2)
        try:
            while s.recv(65536):
                pass
        except (TimeoutError, ConnectionError):
            pass
    served.step(0.2)
    records = [r for r in caplog.records if r.name.startswith("asyncua")]
    assert records, "the malformed message was not logged at all"
    lines = [caplog.handler.format(r) for r in records]
    long = [line for line in lines if "\n" in line or len(line) >= 400 or "x" * 300 in line]
    assert long == []
    assert client_thread.run(_read_name(served.url)) == served.ctl.config.machine.name
