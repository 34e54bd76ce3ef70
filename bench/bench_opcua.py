"""The OPC UA server under load: 20 clients (in another process) subscribed at 100 ms to the
machine's status while a program runs on the real-time worker. The same run without the
server gives the reference: the worker's late cycles and the controller's (GUI thread's)
longest pause must stay what they are; the server thread's CPU share is reported.

    python -m bench.bench_opcua [--seconds 20] [--clients 20]
"""

from __future__ import annotations

import argparse
import json
import os
import socket
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

ROOT = Path(__file__).resolve().parent.parent

_CLIENTS = """
import asyncio, sys
from asyncua import Client
from opcua_server.browse import find_machine
class Count:
    n = 0
    def datachange_notification(self, node, val, data):
        Count.n += 1
async def one(url, seconds):
    async with Client(url, timeout=10) as c:
        m = await find_machine(c)
        nodes = []
        async def walk(node, depth):
            for ch in await node.get_children():
                if await ch.read_node_class() == 2:
                    nodes.append(ch)
                if depth < 4:
                    await walk(ch, depth + 1)
        await walk(m, 0)
        sub = await c.create_subscription(100, Count())
        await sub.subscribe_data_change(nodes)
        print("subscribed", len(nodes), flush=True)
        await asyncio.sleep(seconds)
async def main():
    url, n, seconds = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
    await asyncio.gather(*(one(url, seconds) for _ in range(n)))
    print("notifications", Count.n, flush=True)
asyncio.run(main())
"""


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def _thread_cpu_s(native_id: int) -> float:
    fields = Path(f"/proc/self/task/{native_id}/stat").read_text().rsplit(")", 1)[1].split()
    ticks = os.sysconf("SC_CLK_TCK")
    return (int(fields[11]) + int(fields[12])) / ticks      # utime + stime


def run(serve: bool, clients: int, seconds: float) -> dict[str, float]:
    from PySide6.QtCore import QCoreApplication, QElapsedTimer, QEventLoop, QTimer

    from app.machine.controller import MachineController
    from app.paths import DEMO_PROGRAM
    from opcua_server.settings import OpcUaOverride

    app = QCoreApplication.instance() or QCoreApplication([])
    port = _free_port()
    state = tempfile.mkdtemp(prefix="bench-opcua-")
    ctl = MachineController(None, state_dir=state, worker_mode="process",
                            opcua=OpcUaOverride(port, True) if serve else None)
    proc = None
    try:
        if serve:
            server = ctl.remote.server
            assert server is not None and server.wait_ready(60).running
        assert ctl.connect_bus()
        ctl.set_machine_zero_here()
        assert ctl.load_program(DEMO_PROGRAM, wait=True)
        if serve:
            # the clients stand for other computers on the network: lowest priority here
            proc = subprocess.Popen(["nice", "-n", "19", sys.executable, "-c", _CLIENTS,
                                     f"opc.tcp://127.0.0.1:{port}/", str(clients),
                                     str(seconds + 30)], cwd=ROOT, stdout=subprocess.PIPE, text=True)
            assert proc.stdout is not None
            for _ in range(clients):
                assert proc.stdout.readline().startswith("subscribed")
        late0 = ctl.bus_status.late_cycles
        server_thread = next((t for t in threading.enumerate() if t.name == "opcua-server"), None)
        cpu0 = _thread_cpu_s(server_thread.native_id) if server_thread and server_thread.native_id else 0.0
        wall0 = time.monotonic()
        assert ctl.cycle_start(wait=True)
        longest_ms = 0.0
        gaps: list[float] = []
        clock = QElapsedTimer()
        clock.start()
        loop = QEventLoop()
        while time.monotonic() - wall0 < seconds:
            QTimer.singleShot(10, loop.quit)
            loop.exec()
            gap = clock.restart()
            gaps.append(float(gap))
            longest_ms = max(longest_ms, float(gap))
            if ctl.state.value not in ("running", "hold"):    # the program again, to fill the time
                ctl.cycle_start(from_start=True)
                clock.restart()          # the bench's own restart is not counted as a pause
        wall = time.monotonic() - wall0
        tid = server_thread.native_id if server_thread is not None else None
        cpu = _thread_cpu_s(tid) - cpu0 if tid else 0.0
        late = ctl.bus_status.late_cycles - late0
        updates = ctl.remote.server.updates if serve and ctl.remote.server is not None else 0
        gaps.sort()
        return {"late_cycles": float(late), "gui_longest_pause_ms": longest_ms - 10.0,
                "gui_p999_pause_ms": gaps[int(len(gaps) * 0.999)] - 10.0,
                "server_cpu_pct": 100.0 * cpu / wall, "updates_per_s": updates / wall}
    finally:
        ctl.shutdown()
        if proc is not None:
            proc.kill()
            proc.wait(10)
        del app


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser()
    p.add_argument("--seconds", type=float, default=20.0)
    p.add_argument("--clients", type=int, default=20)
    args = p.parse_args(argv)
    without = run(False, 0, args.seconds)
    with_server = run(True, args.clients, args.seconds)
    result = {"seconds": args.seconds, "clients": args.clients,
              "without_server": without, "with_server": with_server}
    print(f"without the server: {without['late_cycles']:.0f} late cycles, longest GUI pause "
          f"{without['gui_longest_pause_ms']:.1f} ms")
    print(f"with {args.clients} clients at 100 ms: {with_server['late_cycles']:.0f} late cycles, longest GUI "
          f"pause {with_server['gui_longest_pause_ms']:.1f} ms, server thread "
          f"{with_server['server_cpu_pct']:.1f} % of one core, "
          f"{with_server['updates_per_s']:.1f} snapshots/s written")
    print(json.dumps(result))
    return 0


if __name__ == "__main__":
    sys.exit(main())
