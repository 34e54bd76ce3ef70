"""Tracking error per axis, the paper's Eq. 18: e = reference - actual, MSE = sum(e^2) / n,
RMSE = sqrt(MSE), over the whole run and over a sliding window of whole seconds; the per-cycle
(reference, actual) rows go to the trace ring. In place, no allocation per cycle."""

from __future__ import annotations

import math

import numpy as np

from .shared import ControlFields, LiveFields

__all__ = ["Tracker"]


class Tracker:
    def __init__(self, live: LiveFields, n: int, ts_s: float, window_s: float) -> None:
        self.lv = live
        self.block_cycles = max(1, int(round(1.0 / ts_s)))      # 1 s blocks for the window
        n_blocks = max(1, int(math.ceil(window_s / (self.block_cycles * ts_s))))
        self.blocks = np.zeros((n_blocks, n))
        self.blocks_n = np.zeros(n_blocks, dtype=np.int64)
        self.block_acc = np.zeros(n)
        self.block_acc_n = 0
        self.block_index = 0
        self.e2 = np.zeros(n)
        self.abs_e = np.zeros(n)

    def reset(self) -> None:
        lv = self.lv
        lv.sum_e2[:] = 0.0
        lv.win_e2[:] = 0.0
        lv.max_e[:] = 0.0
        self.blocks[:] = 0.0
        self.blocks_n[:] = 0
        self.block_acc[:] = 0.0
        self.block_acc_n = 0
        lv.track_n[...] = 0
        lv.window_n[...] = 0

    def add(self, e: np.ndarray) -> None:
        """One cycle's error e (= reference - actual, axis units)."""
        lv = self.lv
        np.abs(e, out=self.abs_e)
        np.maximum(lv.max_e, self.abs_e, out=lv.max_e)
        np.multiply(e, e, out=self.e2)
        np.add(lv.sum_e2, self.e2, out=lv.sum_e2)
        lv.track_n[...] = int(lv.track_n) + 1
        np.add(self.block_acc, self.e2, out=self.block_acc)
        self.block_acc_n += 1
        if self.block_acc_n >= self.block_cycles:
            k = self.block_index % len(self.blocks)
            self.blocks[k] = self.block_acc
            self.blocks_n[k] = self.block_acc_n
            self.block_index += 1
            self.block_acc[:] = 0.0
            self.block_acc_n = 0
            self.blocks.sum(axis=0, out=lv.win_e2)
            lv.window_n[...] = int(self.blocks_n.sum())

    def trace_row(self, ctl: ControlFields, trace: np.ndarray, cycle: int, ref: np.ndarray,
                  act: np.ndarray, serial: int) -> None:
        """One row of the trace ring: the cycle, the set-point its actual position answers, that
        position, the set-point's serial."""
        n = len(ref)
        h = int(ctl.trace_head)
        row = trace[h % len(trace)]
        row[0] = cycle
        row[1:1 + n] = ref
        row[1 + n:1 + 2 * n] = act
        row[-1] = serial
        ctl.trace_head[...] = h + 1
