"""The memory a check frees between the arrays it keeps goes back to the system."""

from __future__ import annotations

import sys

import numpy as np
import pytest

from planner.core.heap import trim_heap


def _rss_mb() -> float:
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024
    raise AssertionError("no VmRSS in /proc/self/status")


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="glibc's heap (Linux) only")
def test_freed_arrays_between_kept_ones_are_given_back():
    # a freed block from its own mapping raises glibc's threshold: the arrays after it come
    # from the heap, as a program's planning temporaries do
    big = np.ones(1 << 20)  # 8 MB: below the largest threshold glibc raises to (32 MB)
    del big
    # kept and freed arrays of one size, in turn: a freed one lies between two kept ones, where
    # it can neither join a neighbour nor leave with the top of the heap
    kept, freed = [], []
    for _ in range(100):
        kept.append(np.ones(100_000))
        freed.append(np.ones(100_000))  # 800 kB each, 80 MB in all
    freed.clear()
    before = _rss_mb()
    assert trim_heap()
    after = _rss_mb()
    assert before - after > 50.0, (before, after)
    assert len(kept) == 100
