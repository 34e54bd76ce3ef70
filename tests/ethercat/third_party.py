"""Slaves written by others on a link of this machine: KickCAT's CiA 402 drive simulation
(``../shared/thirdparty/kickcat``), run on the far end of a veth pair in a namespace, as the
project's own emulator is (same names, same clean-up by pid and by name)."""

from __future__ import annotations

import os
import subprocess
import tempfile
import time
from pathlib import Path

from ethercat.emulator.link import EmulatedLink, link_unavailable_reason
from ethercat.errors import ConfigurationError, EtherCATTimeoutError

KICKCAT_DIR = Path(os.environ.get("CNC_KICKCAT_DIR",
                                  Path(__file__).resolve().parents[3] / "shared" / "thirdparty" / "kickcat"))
KICKCAT_BIN = KICKCAT_DIR / "network_simulator"
KICKCAT_CONFIG = KICKCAT_DIR / "ecat402-drive.json"
KICKCAT_ESI = KICKCAT_DIR / "ecat402-drive.xml"


def kickcat_unavailable_reason() -> str:
    """Why KickCAT's drives cannot run here ('' if they can)."""
    reason = link_unavailable_reason()
    if reason:
        return reason
    if not KICKCAT_BIN.is_file():
        return f"KickCAT's network_simulator is not at {KICKCAT_BIN} (set CNC_KICKCAT_DIR)"
    ldd = subprocess.run(["ldd", str(KICKCAT_BIN)], capture_output=True, text=True)
    missing = [line.split()[0] for line in ldd.stdout.splitlines() if "not found" in line]
    if missing:
        return (f"KickCAT needs {', '.join(missing)}: apt-get install -y libtinyxml2-9 "
                "(make test installs it as root)")
    return ""


class KickcatLink(EmulatedLink):
    """`n_drives` KickCAT CiA 402 drives on the slave end of the link."""

    def _start_emulator(self) -> None:
        # its statistics go on for as long as it runs: into the log file, not a pipe that fills
        cmd = ["ip", "netns", "exec", self.netns, "stdbuf", "-oL", str(KICKCAT_BIN), "-i", self.slave_ifname,
               "-s", *([str(KICKCAT_CONFIG)] * self.n_drives)]
        self._log = tempfile.NamedTemporaryFile(prefix=f"{self.netns}-kickcat-", suffix=".log", delete=False)
        self.log_path = self._log.name
        self.process = subprocess.Popen(cmd, stdout=self._log, stderr=subprocess.STDOUT, text=True,
                                        cwd=str(KICKCAT_DIR))
        deadline = time.monotonic() + self.start_timeout_s
        while "Opening nominal interface" not in self.log():
            if self.process.poll() is not None:
                raise ConfigurationError(f"KickCAT exited with {self.process.returncode}: {self.log()}")
            if time.monotonic() > deadline:
                raise EtherCATTimeoutError(f"KickCAT did not start within {self.start_timeout_s} s: "
                                           f"{self.log()}")
            time.sleep(0.05)
        time.sleep(0.3)                       # its frame loop starts after the interface opens

    def control(self, op: str, timeout_s: float = 2.0, **kwargs: object) -> dict[str, object]:
        raise ConfigurationError("KickCAT's drives have no control socket")
