"""The garbage-collector pause is counted: overlapping parses and loads (two threads) keep the
collector off until the last one ends, then restore it as it was before the first began."""

from __future__ import annotations

import gc

from planner.core.gcpause import gc_paused


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


class _Big:
    """Something a cycle holds (a loaded program)."""


def test_garbage_made_in_a_freezing_pause_is_collected_not_frozen() -> None:
    """A load pauses the collector and freezes what survives it: a cycle that became garbage
    meanwhile (a parse's interpreter holding a callback that holds the load and its program)
    was frozen with it and never collected, and every program loaded since was kept."""
    import weakref

    big = _Big()
    alive = weakref.ref(big)
    try:
        with gc_paused(freeze=True):
            cycle: list[object] = [big]
            cycle.append(cycle)
            del cycle, big
            assert alive() is not None      # no collection during the pause
        assert alive() is None
    finally:
        gc.unfreeze()
