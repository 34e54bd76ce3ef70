"""An emulated EtherCAT link on this machine: a network namespace, a veth pair and the
emulator answering on its far end (needs root and `ip netns`).

    with EmulatedLink(n_drives=3) as link:
        bus = make_bus("soem", drives, adapter=link.master_ifname)
        link.control("fault", slave=1, code=0x2310)

Names are unique per process (`cncec<pid>x<k>`); `close()` stops the emulator by its pid
and deletes the link and the namespace by name, also after a failed start.
"""

from __future__ import annotations

import itertools
import os
import select
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from types import TracebackType
from typing import Any

from ..errors import ConfigurationError, EtherCATTimeoutError
from .server import control

_counter = itertools.count()
_REPO_ROOT = Path(__file__).resolve().parents[2]


def link_unavailable_reason() -> str:
    """Why an emulated link cannot be made here ('' if it can)."""
    if os.geteuid() != 0:
        return "needs root (network namespaces and raw sockets)"
    if shutil.which("ip") is None:
        return "the `ip` command (iproute2) is not installed"
    probe = subprocess.run(["ip", "netns", "list"], capture_output=True, text=True)
    if probe.returncode != 0:
        return f"`ip netns` does not work here: {probe.stderr.strip()}"
    return ""


def _ip(*args: str, check: bool = True) -> subprocess.CompletedProcess[str]:
    res = subprocess.run(["ip", *args], capture_output=True, text=True)
    if check and res.returncode != 0:
        raise ConfigurationError(f"ip {' '.join(args)} failed: {res.stderr.strip()}")
    return res


class EmulatedLink:
    """Namespace + veth pair + `python -m ethercat emulate s0 --drives N` on the far end."""

    def __init__(self, n_drives: int = 3, realtime: bool = False, start_timeout_s: float = 15.0,
                 variant: str = "standard", terminals: tuple[str, ...] = ()) -> None:
        k = next(_counter)
        pid = os.getpid()
        self.netns = f"cncec{pid}x{k}"
        self.master_ifname = f"cem{pid}x{k}"[:15]
        self.slave_ifname = "s0"
        self.n_drives = n_drives
        self.variant = variant
        self.terminals = terminals
        self.realtime = realtime
        self.start_timeout_s = start_timeout_s
        self.control_path = os.path.join(tempfile.gettempdir(), f"{self.netns}.sock")
        self.process: subprocess.Popen[str] | None = None
        self._log: Any = None
        self.log_path = ""
        self._ns_created = False

    # ------------------------------------------------------------------ life cycle
    def start(self) -> EmulatedLink:
        reason = link_unavailable_reason()
        if reason:
            raise ConfigurationError(f"cannot create an emulated link: {reason}")
        try:
            _ip("netns", "add", self.netns)
            self._ns_created = True
            _ip("link", "add", self.master_ifname, "type", "veth", "peer", "name", self.slave_ifname,
                "netns", self.netns)
            _ip("link", "set", self.master_ifname, "up")
            _ip("netns", "exec", self.netns, "ip", "link", "set", self.slave_ifname, "up")
            self._start_emulator()
        except BaseException:
            self.close()
            raise
        return self

    def _start_emulator(self) -> None:
        cmd = ["ip", "netns", "exec", self.netns, sys.executable, "-m", "ethercat", "emulate",
               self.slave_ifname, "--drives", str(self.n_drives), "--control", self.control_path]
        if self.realtime:
            cmd.append("--realtime")
        cmd += ["--variant", self.variant]
        if self.terminals:
            cmd += ["--terminals", ",".join(self.terminals)]
        self._log = tempfile.NamedTemporaryFile(prefix=f"{self.netns}-", suffix=".log", delete=False)
        self.log_path = self._log.name
        env = dict(os.environ)
        env["PYTHONPATH"] = str(_REPO_ROOT) + os.pathsep + env.get("PYTHONPATH", "")
        self.process = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=self._log, text=True, env=env,
                                        cwd=str(_REPO_ROOT))
        assert self.process.stdout is not None
        deadline = time.monotonic() + self.start_timeout_s
        while time.monotonic() < deadline:
            ready, _, _ = select.select([self.process.stdout], [], [], 0.1)
            if ready:
                line = self.process.stdout.readline()
                if line.startswith("emulating"):
                    break
            if self.process.poll() is not None:
                raise ConfigurationError(f"emulator exited with {self.process.returncode}: {self.log()}")
        else:
            raise EtherCATTimeoutError(
                f"emulator did not start within {self.start_timeout_s} s: {self.log()}")
        while not os.path.exists(self.control_path) and time.monotonic() < deadline:
            time.sleep(0.01)

    def log(self) -> str:
        if not self.log_path:
            return ""
        try:
            return Path(self.log_path).read_text()[-2000:]
        except OSError:
            return ""

    @property
    def pid(self) -> int:
        return self.process.pid if self.process is not None else -1

    def stop_emulator(self) -> None:
        """Stop the emulator process (by its pid); the link stays."""
        proc = self.process
        if proc is None:
            return
        self.process = None
        if proc.poll() is None:
            proc.terminate()
            try:
                proc.wait(5.0)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait(5.0)
        if proc.stdout is not None:
            proc.stdout.close()

    def close(self) -> None:
        """Stop the emulator, delete the veth pair and the namespace (idempotent)."""
        try:
            self.stop_emulator()
        finally:
            _ip("link", "del", self.master_ifname, check=False)
            if self._ns_created:
                _ip("netns", "del", self.netns, check=False)
                self._ns_created = False
            if os.path.exists(self.control_path):
                os.unlink(self.control_path)
            if self._log is not None:
                self._log.close()
                self._log = None

    def remove_log(self) -> None:
        if self.log_path and os.path.exists(self.log_path):
            os.unlink(self.log_path)

    def __enter__(self) -> EmulatedLink:
        return self.start()

    def __exit__(self, exc_type: type[BaseException] | None, exc: BaseException | None,
                 tb: TracebackType | None) -> None:
        self.close()
        if exc_type is None:
            self.remove_log()

    # ------------------------------------------------------------------ control
    def control(self, op: str, **kwargs: Any) -> dict[str, Any]:
        """Send a control request to the emulator (see ethercat.emulator.server)."""
        return control(self.control_path, op, **kwargs)
