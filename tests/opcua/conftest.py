"""A machine on simulated drives with its OPC UA server on 127.0.0.1, and a real asyncua
client in a thread of its own (the controller's time is advanced by the test's thread)."""

from __future__ import annotations

import asyncio
import socket
import threading
import time
from collections.abc import Callable, Coroutine, Iterator
from dataclasses import replace
from pathlib import Path
from typing import Any, TypeVar

import pytest

T = TypeVar("T")


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


class ClientThread:
    """An event loop in a thread: ``run(coro)`` runs a coroutine there and returns its result."""

    def __init__(self) -> None:
        self.loop = asyncio.new_event_loop()
        self.thread = threading.Thread(target=self.loop.run_forever, daemon=True)
        self.thread.start()

    def run(self, coro: Coroutine[Any, Any, T], timeout: float = 60.0) -> T:
        return asyncio.run_coroutine_threadsafe(coro, self.loop).result(timeout)

    def close(self) -> None:
        self.loop.call_soon_threadsafe(self.loop.stop)
        self.thread.join(10)
        self.loop.close()


@pytest.fixture
def client_thread() -> Iterator[ClientThread]:
    ct = ClientThread()
    yield ct
    ct.close()


class Served:
    """The controller and its server, with a way to let machine time pass."""

    def __init__(self, ctl: Any, port: int, state_dir: Path) -> None:
        self.ctl, self.port, self.state_dir = ctl, port, state_dir
        self.url = f"opc.tcp://127.0.0.1:{port}/"

    def step(self, seconds: float, dt: float = 0.02) -> None:
        """Advance the machine's clock ``seconds`` (simulated), publishing as the panel does,
        at a pace the server's 50 Hz loop follows."""
        from PySide6.QtCore import QCoreApplication

        t = 0.0
        while t < seconds:
            self.ctl.advance(dt)
            QCoreApplication.processEvents()
            self.ctl.status.publish()
            time.sleep(0.004)
            t += dt

    def until(self, cond: Callable[[], bool], limit_s: float = 60.0) -> None:
        t = 0.0
        while not cond():
            self.step(0.1)
            t += 0.1
            assert t < limit_s, "condition never met"

    def settle(self) -> None:
        """Let the server's loop read the newest snapshot (its period is 20 ms)."""
        from PySide6.QtCore import QCoreApplication

        QCoreApplication.processEvents()
        self.ctl.status.publish()
        time.sleep(0.15)


def make_served(qapp: Any, state_dir: Path, secure: bool = False, cfg: Any = None, **changes: Any) -> Served:
    """The default machine (or ``cfg``) serving on a free port, with ``changes`` to its ``[opcua]``."""
    from app.machine.config import MachineConfig
    from app.machine.controller import MachineController

    port = free_port()
    cfg = cfg or MachineConfig.default()
    opcua = cfg.opcua.insecure_local(port) if not secure else replace(cfg.opcua, enabled=True,
                                                                      host="127.0.0.1",
                                                                      port=port)
    opcua = replace(opcua, rate_hz=50.0, **changes)
    ctl = MachineController(cfg, state_dir=state_dir, worker_mode="manual", opcua=opcua)
    server = ctl.remote.server
    assert server is not None
    status = server.wait_ready(60.0)
    assert status.running, status.error
    assert ctl.connect_bus()
    ctl.set_machine_zero_here()
    served = Served(ctl, port, state_dir)
    served.settle()
    return served


@pytest.fixture
def served(qapp: Any, tmp_path: Path) -> Iterator[Served]:
    s = make_served(qapp, tmp_path / "state")
    yield s
    s.ctl.shutdown()
