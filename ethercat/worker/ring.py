"""The set-point ring's one operation beside push and take: replacing the queued set-points."""

from __future__ import annotations

import numpy as np

from .messages import Result
from .shared import SharedBlock

__all__ = ["replace_queued"]


def replace_queued(block: SharedBlock, cap: int, from_serial: int, n: int) -> Result:
    """Applied between two cycles: the queued set-points with serial >= `from_serial` are
    dropped and the `n` staged ones take their place. Serial k = the k-th set-point taken
    since start (``live.consumed`` is the serial taken next; it sits at ring index ``tail``).
    Refused (nothing changed) when that serial was already taken or lies past the queue's
    end. At most two block copies of the staging area into the ring."""
    ctl = block.ctl
    consumed = int(block.live.consumed)
    tail = int(ctl.tail)
    head = int(ctl.head)
    if from_serial < consumed:
        return Result.TOO_LATE
    start = tail + (from_serial - consumed)
    if start > head:
        return Result.BEYOND_END
    n = max(0, min(n, cap - (start - tail)))
    i0 = start % cap
    first = min(n, cap - i0)
    stage, ring = block.stage, block.ring
    if first > 0:
        np.copyto(ring[i0:i0 + first], stage[:first])
    if n > first:
        np.copyto(ring[:n - first], stage[first:n])
    ctl.head[...] = start + n          # the producer waits for our ack before touching head
    return Result.OK
