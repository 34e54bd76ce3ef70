"""Whether this test process has the machine's real-time scheduling to itself.

A test of real-time priority or core placement (two workers never on one core at SCHED_FIFO)
measures what the kernel gives it, which another control's real-time workers on the same
machine change: such a test skips, saying so, while one runs."""

from __future__ import annotations

import os
from pathlib import Path

__all__ = ["other_realtime_processes"]

_PF_KTHREAD = 0x00200000           # the kernel's own threads (migration/N, watchdog/N) are real-time too
_REALTIME_POLICIES = {1, 2}        # SCHED_FIFO, SCHED_RR


def other_realtime_processes() -> list[str]:
    """'pid name' of each user process at real-time priority that is neither this process nor
    one of its descendants."""
    out: list[str] = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            stat = (entry / "stat").read_text()
        except OSError:
            continue                      # ended meanwhile
        name = stat[stat.index("(") + 1:stat.rindex(")")]
        fields = stat[stat.rindex(")") + 2:].split()
        # after the name: state, ppid, ... flags, ... policy (proc(5)'s fields 3, 4, 9 and 41)
        flags, policy = int(fields[6]), int(fields[38])
        if flags & _PF_KTHREAD or policy not in _REALTIME_POLICIES:
            continue
        if not _descends(int(entry.name), {os.getpid()}):
            out.append(f"{entry.name} {name}")
    return out


def _descends(pid: int, ancestors: set[int]) -> bool:
    """Whether ``pid`` is one of ``ancestors`` or below one of them (read through /proc)."""
    seen: set[int] = set()
    while pid > 1 and pid not in seen:
        if pid in ancestors:
            return True
        seen.add(pid)
        try:
            stat = Path(f"/proc/{pid}/stat").read_text()
        except OSError:
            return False
        pid = int(stat[stat.rindex(")") + 2:].split()[1])
    return False
