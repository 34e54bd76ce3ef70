"""The plain CAM line read fast: one regex match per line (``fast_line``), the lexed words
without the general checks (``fast_block``), and runs of plain lines at once
(``bulk_lines``, ``planner.gcode.bulk``). Each takes a line only when ``plain_motion_allowed``
and hands any other to the general path.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from planner.core.heap import trim_heap
from planner.gcode.bulk import newline_offsets, scan_plain
from planner.gcode.codes import (
    G,
)
from planner.gcode.motion import MotionCodes
from planner.gcode.state import (
    VALUE_LIMIT,
    ZERO_LEN,
    short_way,
)

TRIM_BYTES = 32 << 20   # program bytes read in bulk between two trims of the heap
#: passes that drop the zero-length moves of a run (each may make the next line's move short);
#: a run that still has one after them is cut there, and the line path reads on
_DROP_PASSES = 4
#: G00-G03 as the fast paths read them: their digit, by their text
FAST_G = {"0": "0", "00": "0", "1": "1", "01": "1", "2": "2", "02": "2", "3": "3", "03": "3"}


#: the codes each line is compared with, looked up once (an enum member's lookup costs
#: 60 ns in CPython 3.11, a module constant's 5 ns)
_G0, _G1, _G2, _G3, _G94 = G.G0, G.G1, G.G2, G.G3, G.G94


@dataclass
class BulkState:
    """What the bulk reader carries from one piece of the program to the next."""

    scanned: bool = False  # a block was scanned (the first is small)
    skip: int = 0          # blocks left to read line by line: the last scan found few long runs
    trimmed_at: int = 0    # where the heap was last trimmed


class FastPaths(MotionCodes):
    use_fast = True  # the fast paths (one regex per line; word fast path); tests compare both ways
    use_bulk = True  # plain coordinate lines read many at a time (planner.gcode.bulk); tests compare too
    BULK_LINES = 16_384  # lines scanned at once by the bulk reader (its arrays: ~40 MB)
    BULK_MIN_RUN = 24  # shorter runs of plain lines are read one by one (cheaper than the arrays)
    BULK_SKIP_BLOCKS = 4  # blocks read line by line after a scan that found few long runs
    BULK_PIECE = 16 << 20  # characters of the program indexed at a time by the bulk reader
    PROGRESS_LINES = 16_384  # the line reader reports its progress this often

    def plain_motion_allowed(self) -> bool:
        """Whether a plain line (G00-G03, axis words, I J K R F) reads as the fast paths read
        it: G94 feed, no XY rotation, no cutter compensation pending, no NURBS open, radius
        mode. Otherwise the general path reads it."""
        return not (self.modal.feed_mode != _G94 or self.offsets.rotation or self.comp.busy
                    or self.curve.nurbs is not None or self.modal.diameter)

    def fast_line(self, groups: tuple, line_no: int) -> bool:
        """A plain line: [N] [G00-G03] axis words [I J K R] [F], as ``Setup.fast_re`` matches it
        (``groups``: G's digit, the axes' values in machine order, I, J, K, R, F; text or
        numbers, None when not given), run as the general path runs it (``straight``,
        ``arc``), its target ``target``'s in the state this path runs in
        (``plain_motion_allowed``: no XY rotation, no compensation pending, not G53). False,
        having changed nothing, hands the line to the general path (which also diagnoses
        errors): a negative F, a G02 without axis words, a motion mode other than G00-G03."""
        modal = self.modal
        setup = self.setup
        n = setup.n
        gtxt = groups[0]
        axes = groups[1:n + 1]
        i_t, j_t, k_t, r_t, f_t = groups[n + 1:]
        f = None if f_t is None else float(f_t)
        if f is not None and f < 0.0:
            return False
        ctr = i_t is not None or j_t is not None or k_t is not None or r_t is not None
        if axes.count(None) == n:           # F alone (or N alone): the feed for what follows
            if gtxt is None and not ctr and modal.feed_mode == _G94:
                if f is not None:
                    modal.feed_mm_s = f * modal.scale / 60.0
                return True
            return False
        motion = int(gtxt) * 10 if gtxt is not None else self.motion
        if motion is None or motion > _G3 or (ctr and motion < _G2) or not self.plain_motion_allowed():
            return False
        scale = modal.scale
        if f is not None:
            modal.feed_mm_s = f * scale / 60.0
        if gtxt is not None:
            self.motion = motion
            self.cycle.il = None
        pos = self.pos
        target = pos.copy()
        base = self.offsets.total if modal.absolute else pos
        if setup.all_linear:
            for i, v in enumerate(axes):
                if v is not None:
                    target[i] = float(v) * scale + base[i]
        else:
            rot, wrapped = setup.rotary, setup.wrapped
            for i, v in enumerate(axes):
                if v is not None:
                    target[i] = (float(v) if rot[i] else float(v) * scale) + base[i]
                    if wrapped[i] and base is not pos:      # absolute on an axis without end
                        target[i] = short_way(pos[i], target[i])
        if motion < _G2:
            self.straight(target, motion == _G0, line_no)
        else:
            centre = {}
            for letter, v in (("I", i_t), ("J", j_t), ("K", k_t), ("R", r_t)):
                if v is not None:
                    centre[letter] = float(v)
            self.arc(target, centre, motion == _G2, scale, line_no)
        return True

    def fast_block(self, words: list, line_no: int) -> bool:
        """The lexed words of a plain line (optional N, one G00-G03, axis words, I/J/K/R, F, in
        any order), run by ``fast_line``. False hands the line to the general path."""
        vals: dict[str, float] = {}
        g = None
        fast_letters = self.setup.fast_letters
        for letter, t in words:
            if letter in fast_letters:
                if letter in vals:
                    return False
                v = float(t)
                if not -VALUE_LIMIT < v < VALUE_LIMIT:
                    return False
                vals[letter] = v
            elif letter == "G" and g is None and t in FAST_G:
                g = FAST_G[t]
            elif letter != "N" or vals or g is not None:
                return False
        get = vals.get
        return self.fast_line((g, *(get(a) for a in self.setup.axes), get("I"), get("J"), get("K"), get("R"),
                               get("F")), line_no)

    def bulk_lines(self, values: np.ndarray, words: np.ndarray, first_line: int, cols: list[int]) -> int:
        """Run plain lines (``planner.gcode.bulk``: values of the linear axes' words in ``cols``
        order, then F, G, N) as ``fast_line`` runs them one by one, from the first; stops before
        a line whose reading needs more (a state the fast path leaves to the general one, a zero
        feed, a move too short to keep) and returns how many lines it ran."""
        n_lines = values.shape[0]
        if not n_lines or not self.plain_motion_allowed():
            return 0
        n_ax = len(cols)
        ax = values[:, :n_ax]
        f_val, g_val = values[:, n_ax], values[:, n_ax + 1]
        has_axes = ~np.isnan(ax).all(axis=1)
        has_g = ~np.isnan(g_val)
        # where the line path must take over: a G without axis words, a negative F
        stop = (has_g & ~has_axes) | (f_val < 0.0)
        motion = self._ffill(g_val * 10.0, -1.0 if self.motion is None else float(self.motion))
        scale = self.modal.scale
        feed = self._ffill(f_val * scale / 60.0, self.modal.feed_mm_s)
        stop |= has_axes & ~((motion == _G0) | ((motion == _G1) & (feed > 0.0)))
        cut = int(np.argmax(stop)) if stop.any() else n_lines
        # targets: absent words keep the axis where the last line put it
        pos = self.pos
        lin = list(self.setup.linear_idx)
        if self.modal.absolute:
            # a move of zero length is dropped, the position left where it was (as ``straight``
            # does): its words are taken as never given, and the lines after it measured again
            # from there, until no move left is short (a few passes: repeated points)
            given = ax[:cut] * scale + np.array([self.offsets.total[i] for i in cols])
            dropped = np.zeros(cut, bool)
            for passes_left in range(_DROP_PASSES, -1, -1):
                targets, length = self._absolute_targets(given, cols, pos, lin)
                short = has_axes[:cut] & ~dropped & (length <= ZERO_LEN)
                if not short.any():
                    break
                if not passes_left:                   # still short after every pass: cut there
                    cut = int(np.argmax(short))
                    break
                dropped |= short
                given[short] = np.nan
        else:
            dropped = np.zeros(cut, bool)
            targets = np.empty((cut + 1, self.setup.n))
            targets[:] = pos
            for c, i in enumerate(cols):
                step = np.nan_to_num(ax[:cut, c] * scale, nan=0.0)
                targets[0, i] = pos[i]
                targets[1:, i] = step
                np.cumsum(targets[:, i], out=targets[:, i])
            delta = np.diff(targets[:, lin], axis=0)
            length = np.sqrt(np.einsum("ij,ij->i", delta, delta))
            short = has_axes[:cut] & (length <= ZERO_LEN)
            if short.any():     # incremental: a dropped step would move every later target
                cut = int(np.argmax(short))
        if cut == 0:
            return 0
        moving = np.flatnonzero(has_axes[:cut] & ~dropped[:cut])
        if words[:cut].any():
            self.started = True
        if has_g[:cut].any():
            self.cycle.il = None
        self.motion = None if motion[cut - 1] < 0.0 else int(motion[cut - 1])
        self.modal.feed_mm_s = float(feed[cut - 1])
        if moving.size:       # none of them short now: the recorder keeps them all
            self.straight_runs(targets[1:][moving], motion[moving] == 0.0, moving + first_line, feed[moving],
                               length[moving])
        return cut

    def run_bulk(self, text: str | None, utf8: bytes | None = None) -> bool:
        """Read the program, plain coordinate lines in runs (``planner.gcode.bulk``), every other
        line by ``line``; ``utf8`` (the text's bytes) when given, else ``text``. A piece of
        the program (cut after a newline) at a time: the line index of a whole program of
        10,000,000 lines was 240 MB, its encoded text 250 MB more."""
        source: str | bytes = utf8 if utf8 is not None else (text or "")
        total = len(source)
        state = BulkState()
        if isinstance(source, bytes):
            # read where they lie, in pieces 4 times as big: the bytes are held anyway (only a
            # piece's index is new), and a fresh process read a 2,000,000-line file 10 % slower
            # in 16 MB pieces (why was not found: the same blocks scan as fast alone)
            newline: Any = b"\n"
            whole = np.frombuffer(source, np.uint8)
            piece = 4 * self.BULK_PIECE
        else:
            newline, whole, piece = "\n", np.zeros(0, np.uint8), self.BULK_PIECE
        lo = 0
        first_line = 0     # lines of the program before this piece
        while True:
            hi = source.find(newline, lo + piece) if lo + piece < total else -1
            last = hi < 0
            hi = total if last else hi + 1
            if isinstance(source, bytes):
                data = whole[lo:hi]
            else:
                # "surrogatepass": a text with lone surrogates reads as it did when it was
                # split into lines whole (they stay in the lines read one by one)
                data = np.frombuffer(source[lo:hi].encode("utf-8", "surrogatepass"), np.uint8)
            nl = newline_offsets(data)
            starts = np.concatenate(([0], nl + 1))
            ends = np.concatenate((nl, [data.shape[0]]))
            if not last:    # the piece ends with its newline: no line starts after it
                starts, ends = starts[:-1], ends[:-1]
            if self._bulk_piece(data, starts, ends, first_line, lo, total, state, utf8 is None):
                return True
            if last:
                return True
            first_line += int(starts.shape[0])
            lo = hi

    def _bulk_piece(self, data: np.ndarray, starts: np.ndarray, ends: np.ndarray, first_line: int,
                    offset: int, total: int, state: BulkState, surrogates: bool) -> bool:
        """Read the lines of one piece (``data``, lines from ``starts`` to ``ends``, the first
        being line ``first_line + 1`` of the program, at ``offset`` of its ``total``): True
        when the program ends there."""
        n_lines = int(starts.shape[0])
        letters = "".join(a for a, rot in zip(self.setup.axes, self.setup.rotary) if not rot) + "FGN"
        cols = [self.setup.axis_index[a] for a in letters[:-3]]
        line = self.line
        min_run = self.BULK_MIN_RUN
        errors = "surrogatepass" if surrogates else "strict"

        def by_line(a: int, b: int) -> bool:
            """Lines a .. b - 1 by ``line`` (True when the program ends there)."""
            if a >= b:
                return False
            text = data[int(starts[a]):int(ends[b - 1])].tobytes().decode("utf-8", errors)
            for line_no, raw in enumerate(text.split("\n"), first_line + a + 1):
                if line(raw, line_no):
                    return True
            return False

        b1 = 0
        while b1 < n_lines:
            if offset + int(starts[b1]) - state.trimmed_at > TRIM_BYTES:
                # each block's scan makes and frees arrays of megabytes, which stay in the heap
                # between the moves kept (360 MB of 1.1 GB after 10,000,000 lines): handed back
                trim_heap()
                state.trimmed_at = offset + int(starts[b1])
            # a small first block tells cheaply whether the program is made of long runs
            b0 = b1
            b1 = min(n_lines, b1 + (self.BULK_LINES if state.scanned else self.BULK_LINES // 8))
            state.scanned = True
            if state.skip:
                state.skip -= 1
                if by_line(b0, b1):
                    return True
                if self.progress is not None:
                    self.progress(offset + int(ends[b1 - 1]), total)
                continue
            base = int(starts[b0])
            block = scan_plain(data[base:int(ends[b1 - 1])], starts[b0:b1] - base, ends[b0:b1] - base,
                               letters)
            # runs of plain lines long enough to pay for the arrays; the lines between them
            # are read one by one, as a text of their own
            edges = np.flatnonzero(np.diff(np.concatenate(([0], block.plain.view(np.int8), [0]))))
            runs = [(b0 + int(r0), b0 + int(r1)) for r0, r1 in zip(edges[::2], edges[1::2])
                    if r1 - r0 >= min_run]
            if sum(r1 - r0 for r0, r1 in runs) < 0.25 * (b1 - b0):
                # a program of short runs (arcs between few lines): scanning costs more than it
                # saves; look again every few blocks, where the program may change its kind
                state.skip = self.BULK_SKIP_BLOCKS
            cursor = b0
            for r0, r1 in runs:
                if by_line(cursor, r0):
                    return True
                i = r0
                while i < r1:
                    i += self.bulk_lines(block.values[i - b0:r1 - b0], block.words[i - b0:r1 - b0],
                                         first_line + i + 1, cols)
                    if i < r1:  # a line the run cannot take: the line reader's
                        if by_line(i, i + 1):
                            return True
                        i += 1
                cursor = r1
            if by_line(cursor, b1):
                return True
            if self.progress is not None:
                self.progress(offset + int(ends[b1 - 1]), total)
        return False

    def _absolute_targets(self, given: np.ndarray, cols: list[int], pos: list[float], lin: list[int]
                          ) -> tuple[np.ndarray, np.ndarray]:
        """Where each line of an absolute run goes (``given``: machine values of the words, NaN
        where absent) and each move's length over the linear axes."""
        targets = np.empty((given.shape[0] + 1, self.setup.n))
        targets[:] = pos
        for c, i in enumerate(cols):
            targets[1:, i] = self._ffill(given[:, c], pos[i])
        delta = np.diff(targets[:, lin], axis=0)
        return targets, np.sqrt(np.einsum("ij,ij->i", delta, delta))

    @staticmethod
    def _ffill(values: np.ndarray, before: float) -> np.ndarray:
        """``values`` with each NaN replaced by the last value before it (``before`` at first)."""
        given = ~np.isnan(values)
        idx = np.where(given, np.arange(values.shape[0]), -1)
        np.maximum.accumulate(idx, out=idx)
        out = np.where(idx >= 0, values[np.maximum(idx, 0)], before)
        return out
