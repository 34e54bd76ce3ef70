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


def wait_for_new_blocks(before: set[Path], proc: subprocess.Popen, timeout_s: float = 60.0) -> set[Path]:
    """The worker blocks (``psm_*``) that appeared since ``before``, waited for while ``proc``
    runs; empty when none came within the time."""
    deadline = time.monotonic() + timeout_s
    mine: set[Path] = set()
    while not mine and time.monotonic() < deadline and proc.poll() is None:
        time.sleep(0.2)
        mine = {p for p in set(SHM.iterdir()) - before if p.name.startswith("psm_")}
    return mine
