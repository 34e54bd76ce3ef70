"""Per-block maxima of a plan's normalised velocity, acceleration and jerk, measured ahead of
execution: what the time scaling (``app.machine.timescale``) may do with sigma near planned
time tau depends on them. Computed lazily from ``plan.iter_chunks`` (a whole plan, or one made
as the run reaches it), against the machine's true limits (not the reduced ones the plan was
made with)."""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np

from planner.core.machine import MachineSpec
from planner.core.program import FEED_OVERRIDE_OFF
from planner.motion.plan import Plan
from planner.motion.window import PlanWindow

__all__ = ["BLOCK", "BlockStats"]

BLOCK = 16  # samples per statistics block


class BlockStats:
    """Per-block maxima of the plan's normalised velocity/acceleration/jerk, computed lazily
    from ``plan.iter_chunks`` ahead of execution (true machine limits, not the reduced ones)."""

    def __init__(self, plan: Plan | PlanWindow, machine: MachineSpec) -> None:
        self.plan = plan
        ts = plan.ts_s
        self.ts = ts
        lin = np.array([not a.rotary for a in machine.axes])
        self.lin = lin
        self.v_ax = np.array([a.v_motion for a in machine.axes])
        self.a_ax = np.array([a.a_motion for a in machine.axes])
        self.j_ax = np.array([a.j_motion for a in machine.axes])
        lim = machine.limits
        self.v_feed, self.v_rapid = lim.v_max_mm_s, lim.rapid_mm_s
        self.a_path, self.j_path = lim.a_max_mm_s2, lim.j_max_mm_s3
        self.rapid_move = plan.program.rapid_moves
        # moves the program runs with the feed override off (tapping, M49, M50 P0): None if none
        locks = plan.program.override_locks
        self.fixed_move = None if locks is None else (locks & FEED_OVERRIDE_OFF).astype(bool)
        self._chunks: Iterator = plan.iter_chunks(chunk_samples=BLOCK * 256)
        self._tail_q: np.ndarray | None = None
        self._tail_m: np.ndarray | None = None
        self._pending_q: list[np.ndarray] = []
        self.n_blocks = 0
        cap = 1024
        self.cols = {k: np.zeros(cap) for k in ("rv", "ra", "rj", "alpha", "beta", "gamma", "rjraw", "raraw")}
        self.has_rapid = np.zeros(cap, bool)
        self.has_feed = np.zeros(cap, bool)
        self.has_fixed = np.zeros(cap, bool)   # a move of the block runs with the feed override off
        self.done = False
        self._carry_q = np.zeros((0, len(machine.axes)))
        self._carry_m = np.zeros(0, np.int64)

    def _grow(self, need: int) -> None:
        cap = len(self.has_rapid)
        if need <= cap:
            return
        new = max(need, 2 * cap)
        for k, v in self.cols.items():
            self.cols[k] = np.concatenate([v, np.zeros(new - cap)])
        self.has_rapid = np.concatenate([self.has_rapid, np.zeros(new - cap, bool)])
        self.has_feed = np.concatenate([self.has_feed, np.zeros(new - cap, bool)])
        self.has_fixed = np.concatenate([self.has_fixed, np.zeros(new - cap, bool)])

    def ensure(self, tau_s: float) -> None:
        """Compute blocks up to planned time tau_s (or the end)."""
        need = int(tau_s / (self.ts * BLOCK)) + 2
        while self.n_blocks < need and not self.done:
            try:
                ch = next(self._chunks)
            except StopIteration:
                self.done = True
                if len(self._carry_q):
                    self._process(self._carry_q, self._carry_m, final=True)
                return
            q = np.concatenate([self._carry_q, ch.q])
            m = np.concatenate([self._carry_m, ch.move_index.astype(np.int64)])
            self._carry_q, self._carry_m = self._process(q, m, final=False)

    def _process(self, q: np.ndarray, m: np.ndarray, final: bool) -> tuple[np.ndarray, np.ndarray]:
        """q holds samples starting at block self.n_blocks, with 3 samples of history before
        when n_blocks > 0 (kept in the carry). Returns the new carry."""
        hist = 3 if self.n_blocks > 0 else 0
        body = len(q) - hist
        nb = body // BLOCK if not final else -(-body // BLOCK)
        if nb <= 0:
            return q, m
        end = hist + nb * BLOCK
        qq = q[:min(end, len(q))]
        mm = m[:min(end, len(m))]
        ts = self.ts
        dq = np.diff(qq, axis=0) / ts
        aq = np.diff(qq, 2, axis=0) / ts**2
        jq = np.diff(qq, 3, axis=0) / ts**3
        lin = self.lin

        def path(x: np.ndarray) -> np.ndarray:
            return np.linalg.norm(x[:, lin], axis=1) if lin.any() else np.zeros(len(x))

        same4 = (mm[3:] == mm[:-3]) & (mm[1:-2] == mm[3:])
        rapid = self.rapid_move[np.clip(mm, 0, len(self.rapid_move) - 1)] if len(self.rapid_move) else \
            np.zeros(len(mm), bool)
        v_path_lim = np.where(rapid[1:], self.v_rapid, self.v_feed)
        # normalised per sample (FD value k belongs to the sample it ends at: index k+order)
        n = len(qq)
        rv = np.zeros(n)
        ra = np.zeros(n)
        rj = np.zeros(n)
        alpha = np.zeros(n)
        beta = np.zeros(n)
        gamma = np.zeros(n)
        vp = path(dq)
        rv[1:] = np.maximum(vp / v_path_lim, np.max(np.abs(dq) / self.v_ax, axis=1))
        alpha[1:] = np.maximum(vp / self.a_path, np.max(np.abs(dq) / self.a_ax, axis=1))
        gamma[1:] = np.maximum(vp / self.j_path, np.max(np.abs(dq) / self.j_ax, axis=1))
        ap = path(aq)
        ra[2:] = np.maximum(ap / self.a_path, np.max(np.abs(aq) / self.a_ax, axis=1))
        beta[2:] = np.maximum(ap / self.j_path, np.max(np.abs(aq) / self.j_ax, axis=1))
        jp = path(jq)
        rjs = np.maximum(jp / self.j_path, np.max(np.abs(jq) / self.j_ax, axis=1))
        rj[3:] = np.where(same4, rjs, 0.0)
        # FD spans the previous sample too: spread each value to both ends (max with neighbour)
        for arr in (rv, ra, rj, alpha, beta, gamma):
            arr[:-1] = np.maximum(arr[:-1], arr[1:])
        sl = slice(hist, hist + nb * BLOCK)

        def blocks(x: np.ndarray) -> np.ndarray:
            y = x[sl]
            pad = nb * BLOCK - len(y)
            if pad > 0:
                y = np.concatenate([y, np.zeros(pad)])
            return y.reshape(nb, BLOCK).max(axis=1)

        b0 = self.n_blocks
        self._grow(b0 + nb)
        for key, arr in (("rv", rv), ("ra", ra), ("rj", rj), ("alpha", alpha), ("beta", beta),
                         ("gamma", gamma)):
            self.cols[key][b0:b0 + nb] = blocks(arr)
        def per_block(x: np.ndarray) -> np.ndarray | None:
            """(nb, BLOCK) of a per-sample flag, the last sample's repeated to fill the last block."""
            y = x[sl]
            pad = nb * BLOCK - len(y)
            y = np.concatenate([y, np.repeat(y[-1:], pad)]) if pad > 0 and len(y) else y
            return y.reshape(nb, BLOCK) if len(y) == nb * BLOCK else None

        rr = per_block(rapid)
        if rr is not None:
            self.has_rapid[b0:b0 + nb] = rr.any(axis=1)
            self.has_feed[b0:b0 + nb] = (~rr).any(axis=1)
        if self.fixed_move is not None and len(mm):
            fx = per_block(self.fixed_move[np.clip(mm, 0, len(self.fixed_move) - 1)])
            if fx is not None:
                self.has_fixed[b0:b0 + nb] = fx.any(axis=1)
        self.n_blocks = b0 + nb
        keep = max(end - 3, 0)
        return q[keep:], m[keep:]

    def window(self, tau0_s: float, tau1_s: float) -> slice:
        bt = self.ts * BLOCK
        b0 = max(int(tau0_s / bt) - 1, 0)
        b1 = min(int(tau1_s / bt) + 2, self.n_blocks)
        return slice(b0, max(b1, min(b0 + 1, self.n_blocks)))
