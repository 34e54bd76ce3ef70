"""The garbage-collector pause is counted: overlapping parses and loads (two threads) keep the
collector off until the last one ends, then restore it as it was before the first began."""

from __future__ import annotations

import gc

from planner.gcpause import gc_paused


def test_overlapping_pauses_end_with_the_last() -> None:
    assert gc.isenabled()
    outer = gc_paused(freeze=True)
    inner = gc_paused()
    outer.__enter__()
    inner.__enter__()
    outer.__exit__(None, None, None)   # the first one ends while the other still runs
    assert not gc.isenabled()
    inner.__exit__(None, None, None)
    assert gc.isenabled()
    gc.unfreeze()


def test_a_disabled_collector_stays_disabled() -> None:
    gc.disable()
    try:
        with gc_paused():
            pass
        assert not gc.isenabled()
    finally:
        gc.enable()
