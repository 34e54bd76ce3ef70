"""Shared-memory blocks of the worker, seen from outside the process that made them: the
signal tests start a panel or cnc-run, wait for its worker's block to appear, and check that
the block is gone after the process ended."""

from __future__ import annotations

import subprocess
import time
from pathlib import Path

import pytest

SHM = Path("/dev/shm")


def shm_before() -> set[Path]:
    """The blocks that exist now (skips the test where /dev/shm is not there)."""
    if not SHM.is_dir():
        pytest.skip("no /dev/shm on this system")
    return set(SHM.iterdir())


def _mapped_by(pid: int) -> set[Path]:
    """The worker blocks (``psm_*``) process ``pid`` has mapped (the one that makes a block maps it)."""
    try:
        maps = Path(f"/proc/{pid}/maps").read_text()
    except OSError:                     # the process ended meanwhile
        return set()
    found: set[Path] = set()
    for line in maps.splitlines():
        fields = line.split(maxsplit=5)         # address perms offset dev inode [path]
        path = fields[5] if len(fields) == 6 else ""
        if path.startswith(f"{SHM}/psm_"):
            found.add(Path(path.removesuffix(" (deleted)")))
    return found


def wait_for_new_blocks(before: set[Path], proc: subprocess.Popen, timeout_s: float = 60.0) -> set[Path]:
    """The worker blocks (``psm_*``) that appeared since ``before`` and that ``proc`` has mapped
    (other tests running at the same time make blocks of their own),
    waited for while ``proc`` runs; empty when none came within the time."""
    deadline = time.monotonic() + timeout_s
    mine: set[Path] = set()
    while not mine and time.monotonic() < deadline and proc.poll() is None:
        time.sleep(0.2)
        new = {p for p in set(SHM.iterdir()) - before if p.name.startswith("psm_")}
        mine = new & _mapped_by(proc.pid) if new else set()
    return mine
