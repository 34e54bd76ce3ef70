"""Run a `Segment` on a network interface: AF_PACKET raw socket, EtherType 0x88A4.

Needs root or CAP_NET_RAW. The socket is bound to the EtherCAT protocol only, so the
emulator never sees its own answers (the kernel loops outgoing frames back only to
ETH_P_ALL sockets). A control socket (AF_UNIX stream, one JSON request per line and
connection) lets tests and integrators inject faults without touching the link:

    {"op": "status"}                                -> segment status
    {"op": "fault", "slave": 1, "code": 8976}       -> drive 1 trips fault 0x2310
    {"op": "fault", "slave": 1, "code": 8976, "persistent": true} / {"op": "clear_fault", "slave": 1}
    {"op": "jam", "slave": 0, "on": true}           -> load blocked (following error)
    {"op": "lose", "slave": 2} / {"op": "restore", "slave": 2}  -> slave gone / back (power cycled)
    {"op": "inputs", "slave": 1, "value": 65536}   -> the drive's digital inputs 0x60FD (a probe ...),
                                                       a terminal's input channels
    {"op": "encoder", "slave": 3, "add": 40}       -> an encoder terminal counts 40 more (a
                                                       handwheel turned; its 16-bit counter wraps)
    {"op": "stop"}                                  -> the emulator exits
"""

from __future__ import annotations

import gc
import json
import os
import select
import signal
import socket
import threading
from collections.abc import Sequence
from typing import Any

from ..errors import AdapterError, ConfigurationError
from .segment import ETHERTYPE_ECAT, Segment
from .terminal import TerminalObjects

HOUSEKEEPING_NS = 2_000_000


def open_raw_socket(ifname: str) -> socket.socket:
    """A raw socket on `ifname` receiving EtherCAT frames only."""
    try:
        sock = socket.socket(socket.AF_PACKET, socket.SOCK_RAW, socket.htons(ETHERTYPE_ECAT))
    except PermissionError as exc:
        raise AdapterError(f"raw socket needs root or CAP_NET_RAW: {exc}") from exc
    try:
        sock.bind((ifname, ETHERTYPE_ECAT))
    except OSError as exc:
        sock.close()
        raise AdapterError(f"cannot bind to interface {ifname!r}: {exc}") from exc
    sock.setblocking(False)
    return sock


class EmulatorServer:
    """Answers frames on `ifname` with `segment` until `stop()` (or SIGTERM in `run`)."""

    def __init__(self, segment: Segment, ifname: str, control_path: str | None = None) -> None:
        self.segment = segment
        self.ifname = ifname
        self.control_path = control_path
        self._stop = threading.Event()
        self._sock = open_raw_socket(ifname)
        self._ctrl: socket.socket | None = None
        if control_path:
            if os.path.exists(control_path):
                os.unlink(control_path)
            self._ctrl = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
            self._ctrl.bind(control_path)
            self._ctrl.listen(4)
            self._ctrl.setblocking(False)

    def stop(self) -> None:
        self._stop.set()

    def serve_forever(self) -> None:
        poller = select.poll()
        poller.register(self._sock.fileno(), select.POLLIN)
        if self._ctrl is not None:
            poller.register(self._ctrl.fileno(), select.POLLIN)
        seg = self.segment
        sock = self._sock
        buf = bytearray(2048)
        clock = seg.clock_ns
        next_housekeeping = clock()
        try:
            while not self._stop.is_set():
                events = poller.poll(2)
                for fd, _ev in events:
                    if fd == sock.fileno():
                        while True:
                            try:
                                n = sock.recv_into(buf)
                            except BlockingIOError:
                                break
                            answer = seg.process_frame(memoryview(buf)[:n])
                            if answer is not None:
                                try:
                                    sock.send(answer)
                                except OSError:
                                    pass
                    elif self._ctrl is not None:
                        self._handle_control()
                now = clock()
                if now >= next_housekeeping:
                    seg.housekeeping()
                    next_housekeeping = now + HOUSEKEEPING_NS
        finally:
            self.close()

    def close(self) -> None:
        self._sock.close()
        if self._ctrl is not None:
            self._ctrl.close()
            self._ctrl = None
            if self.control_path and os.path.exists(self.control_path):
                os.unlink(self.control_path)

    # ------------------------------------------------------------------ control
    def _handle_control(self) -> None:
        assert self._ctrl is not None
        try:
            conn, _ = self._ctrl.accept()
        except BlockingIOError:
            return
        with conn:
            conn.settimeout(0.5)
            try:
                raw = b""
                while not raw.endswith(b"\n"):
                    chunk = conn.recv(4096)
                    if not chunk:
                        break
                    raw += chunk
                reply = self.command(json.loads(raw.decode() or "{}"))
            except (ValueError, KeyError, IndexError, TypeError, ConfigurationError) as exc:
                reply = {"ok": False, "error": str(exc)}
            except OSError:
                return
            try:
                conn.sendall(json.dumps(reply).encode() + b"\n")
            except OSError:
                pass

    def command(self, req: dict[str, Any]) -> dict[str, Any]:
        """Execute one control request (see the module docstring)."""
        op = req.get("op")
        seg = self.segment
        if op == "status":
            return {"ok": True, **seg.status()}
        if op == "stop":
            self.stop()
            return {"ok": True}
        slave = seg.slaves[int(req["slave"])]
        model, objects = slave.model, slave.objects
        if op in ("fault", "clear_fault", "jam") and model is None:
            raise ConfigurationError(f"slave {slave.position} is a terminal: {op!r} is a drive's")
        if op == "fault" and model is not None:
            model.inject_fault(int(req.get("code", 0x2310)), bool(req.get("persistent", False)))
        elif op == "clear_fault" and model is not None:
            model.clear_fault()
        elif op == "jam" and model is not None:
            model.set_jam(bool(req.get("on", True)))
        elif op == "lose":
            slave.lost = True
        elif op == "restore":
            slave.power_cycle()
            slave.lost = False
        elif op == "inputs" and model is not None:
            model.digital_inputs = int(req["value"]) & 0xFFFF_FFFF
        elif op == "inputs" and isinstance(objects, TerminalObjects):
            objects.inputs = int(req["value"]) & 0xFFFF_FFFF
        elif op == "encoder" and isinstance(objects, TerminalObjects):
            objects.counter = (objects.counter + int(req["add"])) & 0xFFFF
        else:
            raise ConfigurationError(f"unknown control op {op!r}")
        return {"ok": True}


def control(path: str, op: str, timeout_s: float = 2.0, **kwargs: Any) -> dict[str, Any]:
    """Send one control request to a running emulator and return its reply."""
    with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as s:
        s.settimeout(timeout_s)
        s.connect(path)
        s.sendall(json.dumps({"op": op, **kwargs}).encode() + b"\n")
        raw = b""
        while not raw.endswith(b"\n"):
            chunk = s.recv(65536)
            if not chunk:
                break
            raw += chunk
    reply: dict[str, Any] = json.loads(raw.decode())
    if not reply.get("ok"):
        raise ConfigurationError(f"emulator control {op!r} failed: {reply.get('error')}")
    return reply


def run(ifname: str, n_drives: int, control_path: str | None = None, realtime: bool = False,
        counts_per_unit: float = 10_000.0, quiet: bool = False, variant: str = "standard",
        terminals: Sequence[str] = ()) -> int:
    """Entry point of `cnc-ethercat emulate`: serve until SIGINT/SIGTERM."""
    from ..drive_model import DriveParams

    if n_drives < 1:
        raise ConfigurationError(f"--drives must be >= 1, got {n_drives}")
    from .variants import VARIANTS

    if variant not in VARIANTS:
        raise ConfigurationError(f"--variant must be one of {', '.join(VARIANTS)}, got {variant!r}")
    from ..terminals import terminal_type

    segment = Segment.of_drives(n_drives, DriveParams.for_axis(counts_per_unit), VARIANTS[variant],
                                terminals=[terminal_type(t) for t in terminals])
    server = EmulatorServer(segment, ifname, control_path)
    if realtime:
        try:
            os.sched_setscheduler(0, os.SCHED_FIFO, os.sched_param(20))
        except (PermissionError, OSError, AttributeError):
            pass
    for sig in (signal.SIGTERM, signal.SIGINT):
        signal.signal(sig, lambda *_: server.stop())
    # no reference cycles are made per frame: keep the collector out of the answer path
    gc.collect()
    gc.freeze()
    gc.disable()
    if not quiet:
        more = f" and {', '.join(terminals)}" if terminals else ""
        print(f"emulating {n_drives} CiA 402 drive(s){more} on {ifname} (pid {os.getpid()}, "
              f"variant {variant})", flush=True)
    server.serve_forever()
    return 0
