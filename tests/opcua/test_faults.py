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
