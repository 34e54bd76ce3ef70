"""The lathe cycles G70, G71/G71.1/G71.2, G72/G72.1/G72.2 on a profile subroutine
(``planner.gcode.g7x``).
"""

from __future__ import annotations

import math
from typing import Any

from planner.core.errors import BlockError
from planner.gcode import g7x
from planner.gcode.codes import (
    G,
    gname,
)
from planner.gcode.flow import MAX_EXECUTED, FlowCodes
from planner.gcode.lexer import LexError, read_line
from planner.gcode.motion import MotionCodes
from planner.gcode.oword import Statement
from planner.gcode.state import VALUE_LIMIT


class LatheCodes(MotionCodes, FlowCodes):
    def lathe_cycle(self, motion: int, vals: dict[str, float], scale: float, line_no: int) -> None:
        """G70 (finishing), G71 (roughing along Z) and G72 (along X), with .1 (no pockets) and .2
        (the pockets only), as LinuxCNC 2.9 runs them (``planner.gcode.g7x``): a rapid to the block's
        X Z, then the profile of the numbered subroutine Q (G0-G3 blocks with X Z, U W
        incremental, I K or R, A a round and C a chamfer at its end) is cut from there: G71/G72
        in passes of depth I (default 1), retracting R (0.5), down to D from the profile moved by
        U W; G70 in P passes from D to E. In G18 only."""
        name = gname(motion)
        cycle, variant = motion // 10, motion % 10
        if "Q" not in vals:
            raise BlockError(f"{name} requires a Q word (the number of the subroutine with the profile)",
                             name)
        if self.comp.side != 0:
            raise BlockError(f"{name} cannot be used with cutter compensation enabled: program G40 first",
                             name)
        if self.modal.plane != G.G18:
            raise BlockError(f"{name} can only be used in the XZ plane (G18)", name)
        if "X" not in self.setup.axis_index or "Z" not in self.setup.axis_index:
            raise BlockError(f"{name} cuts in X and Z: this machine has no "
                             f"{'X' if 'X' not in self.setup.axis_index else 'Z'} axis", name)
        ix, iz = self.setup.axis_index["X"], self.setup.axis_index["Z"]
        here = self.program_position(self.pos)
        x, z = here[ix] / scale, here[iz] / scale           # program units, as LinuxCNC works
        incremental = not self.modal.absolute
        if incremental:
            x, z = x + vals.get("X", 0.0), z + vals.get("Z", 0.0)
        else:
            x, z = vals.get("X", x), vals.get("Z", z)
        arc_absolute, absolute = self.modal.arc_absolute, self.modal.absolute
        last_mode = [0]

        def target(p: complex) -> list[float]:
            return self.target({"X": p.imag, "Z": p.real}, ["X", "Z"], scale, False)

        def straight(p: complex, rapid: bool) -> None:
            self.straight(target(p), rapid, line_no)
            last_mode[0] = 0 if rapid else 10

        def arc(ccw: bool, center: complex, p: complex) -> None:
            now = self.program_position(self.pos)
            if abs(now[iz] / scale - p.real) >= 1e-4 or abs(now[ix] / scale - p.imag) >= 1e-4:
                self.arc(target(p), {"X": p.imag, "Z": p.real, "I": center.imag, "K": center.real}, not ccw,
                         scale, line_no)
                last_mode[0] = 30 if ccw else 20

        # LinuxCNC reads the cycle's own moves, and the block's X Z for the rapid, as absolute
        self.modal.absolute, self.modal.arc_absolute = True, True
        try:
            axes: list[str] = [a for a in ("X", "Z") if a in vals]
            self.straight(self.target(vals, list(axes), scale, False), True, line_no)
            segments = self.lathe_profile(vals["Q"], complex(z, x), incremental, arc_absolute, name)
            if len(segments) <= 1:
                return
            i = vals.get("I", 1.0)
            if i <= 0:
                raise BlockError(f"{name}: I (the depth of cut) must be greater than zero", "I")
            out = g7x.Motion(lambda p: straight(p, False), lambda p: straight(p, True), arc)
            profile = g7x.Profile(segments)
            if cycle == 70:
                profile.g70(out, x, z, vals.get("D", 0.0), vals.get("E", 0.0), vals.get("P", 1.0))
            else:
                profile.g71(out, variant, x, z, vals.get("U", 0.0), vals.get("W", 0.0), vals.get("D", 0.0), i,
                            vals.get("R", 0.5), rotate=cycle == 72)
        except g7x.G7xError as e:
            raise BlockError(f"{name}: {e}", name) from None
        except (ZeroDivisionError, ValueError, OverflowError):
            # LinuxCNC's arithmetic goes on with infinities here and draws nonsense
            raise BlockError(f"{name}: the profile cannot be offset or cut (a segment of no length, or "
                             "the cycle's start on the profile)", name) from None
        finally:
            self.modal.absolute, self.modal.arc_absolute = absolute, arc_absolute
        self.motion = last_mode[0]

    def lathe_profile(self, q: float, start: complex, incremental: bool, centre_absolute: bool,
                      name: str) -> list[Any]:
        """The profile of subroutine ``o<q>`` as LinuxCNC's G7x reads it (program units, points
        as z + 1j x): each block's G0-G3, X Z or U W, I K or R, A (round) and C (chamfer);
        other words are not the profile's. Parameters are set as the blocks are read."""
        if q != int(q) or q < 0:
            raise BlockError(f"{name} Q{q:g}: the profile's subroutine number is a whole number", "Q")
        frame = self.calls.frame
        label = str(int(q))
        found = None
        if frame is not None:
            found = self.find_sub(label, Statement(self.calls.pc, label, "CALL", ""), frame)
        if frame is None or found is None:
            raise BlockError(f"{name} Q{q:g}: no o{label} sub in this program (the profile)", "Q")
        segments: list[Any] = []
        mode = 0                                  # the rapid to the start was the last move
        scale = self.modal.scale
        saved_pos = self.pos
        k, steps = found[0] + 1, 0
        try:
            while k < found[1]:
                steps += 1
                if steps > MAX_EXECUTED:
                    raise BlockError(f"{name}: more than {MAX_EXECUTED:,} profile blocks read (an endless "
                                     "loop?)", "Q")
                where = f"line {k + 1}, in the profile"
                st = frame.structure.statements.get(k)
                if st is not None:                # loops and branches run as the profile is read
                    if st.keyword == "RETURN":
                        break
                    if st.keyword not in ("IF", "ELSEIF", "ELSE", "ENDIF", "WHILE", "ENDWHILE", "DO",
                                          "DOWHILE", "REPEAT", "ENDREPEAT", "BREAK", "CONTINUE"):
                        raise BlockError(f"{name}: o{st.label} {st.keyword.lower()} ({where}) is not "
                                         "supported: a profile's calls are written out", "Q")
                    try:
                        nxt = self.statement(st, frame, [])
                    except BlockError as e:
                        raise BlockError(f"{name}: {where}: {e.message}", "Q") from None
                    assert isinstance(nxt, int)
                    k = nxt
                    continue
                k += 1
                text = frame.lines[k - 1].strip()
                if not text or text.startswith("%") or (text.startswith("/") and self.setup.block_delete):
                    continue
                try:
                    words, assigns = read_line(text.lstrip("/"), self.params)
                except LexError as e:
                    raise BlockError(f"{name}: {where}: {e.message}", "Q") from None
                mode, start = self._profile_block(words, mode, start, incremental, centre_absolute, segments,
                                                  f"{name}: ", f" ({where})")
                # #<_x>, #<_z> read where the profile has got to, as in LinuxCNC
                self.pos = self.target({"X": start.imag, "Z": start.real}, ["X", "Z"], scale, False)
                self.assign(assigns)
        finally:
            self.pos = saved_pos
        return segments

    def _profile_block(self, words: list, mode: int, start: complex, incremental: bool, centre_absolute: bool,
                       segments: list[Any], head: str, where: str) -> tuple[int, complex]:
        """One block of a G7x profile: its segment (and round or chamfer) appended; the motion
        mode and the point it ends at returned."""
        w: dict[str, float] = {}
        for letter, value in words:
            v = float(value)
            if not -VALUE_LIMIT < v < VALUE_LIMIT:      # as every block's words (inf and nan too)
                raise BlockError(f"{head}{letter} value {v:g} out of range (|value| < 1e9){where}", "Q")
            if letter == "G" and v in (0.0, 1.0, 2.0, 3.0):
                mode = int(v) * 10
            else:
                w[letter] = v
        end = complex(0.0, 0.0) if incremental else start
        for word, axis in (("U", "X"), ("W", "Z")):
            if word in w:
                if incremental:
                    raise BlockError(f"{head}cannot use {word} in incremental mode (G91){where}", "Q")
                if axis in w:
                    raise BlockError(f"{head}cannot use {word} and {axis} in the same block{where}", "Q")
        if "U" in w:
            end += 1j * (w["U"] / 2 if self.modal.diameter else w["U"])
        elif "X" in w:
            end = complex(end.real, w["X"] / 2 if self.modal.diameter else w["X"])
        if "W" in w:
            end += w["W"]
        elif "Z" in w:
            end = complex(w["Z"], end.imag)
        center = complex(w.get("K", 0.0), w.get("I", 0.0))
        if incremental:
            end += start
        if end == start:
            return mode, start
        if mode in (G.G0, G.G1):
            segments.append(g7x.StraightSegment(start, end))
        elif "R" in w:
            if "I" in w or "K" in w:
                raise BlockError(f"{head}both R and I or K for an arc{where}", "Q")
            r, chord = w["R"], abs(end - start) ** 2
            if r * r < chord / 4:
                raise BlockError(f"{head}radius R{r:g} too small for the arc{where}", "Q")
            d = 1j * math.sqrt((r * r - chord / 4) / chord) * (end - start)
            segments.append(g7x.RoundSegment(mode == G.G3, start,
                                             (start + end) / 2 + (d if mode == G.G3 else -d),
                                             end))
        else:
            if "I" not in w and "K" not in w:
                raise BlockError(f"{head}either I or K must be present for an arc{where}", "Q")
            segments.append(g7x.RoundSegment(mode == G.G3, start,
                                             center if centre_absolute else center + start,
                                             end))
        if "A" in w and "C" in w:
            raise BlockError(f"{head}both A and C on a corner{where}", "Q")
        if "A" in w:
            segments.append(g7x.fillet(w["A"], end))
        if "C" in w:
            segments.append(g7x.chamfer(w["C"], end))
        return mode, end
