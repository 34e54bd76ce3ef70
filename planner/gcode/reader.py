"""Reading and checking one block, as LinuxCNC's ``interp_read.cc`` and ``interp_check.cc`` do:
the lexed words become a ``Block`` (its G and M codes by modal group, its values by letter, its
axis words, the motion it makes) or a ``BlockError`` naming the word at fault. Nothing here
changes the interpreter's state; ``planner.gcode.execute`` runs the block.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from planner.core.errors import BlockError
from planner.gcode.codes import (
    AXIS_USERS,
    CYCLE_NEEDS_Q,
    CYCLE_TAKES_P,
    CYCLES,
    G_GROUP,
    G_UNSUPPORTED,
    LATHE_CYCLES,
    M_GROUP,
    M_UNSUPPORTED,
    SYNCHRONISED,
    G,
    Group,
    M,
    MGroup,
    gname,
)
from planner.gcode.state import FEED_LIMIT, VALUE_LIMIT, Setup

__all__ = ["Block", "read_block", "WORD_LETTERS", "AXIS_LETTERS"]

WORD_LETTERS = frozenset("FSTPQRIJKDHL")
AXIS_LETTERS = "XYZABC"
_CENTRE_LETTERS = ("I", "J", "K", "R")


@dataclass(slots=True)
class Block:
    """One block read and checked: ``groups`` the G codes by modal group, ``mgroups`` the M
    codes, ``vals`` the other words' values (program units; G7 halves X and polar words become
    X and Y as it runs), ``axis_words`` the axis letters that make a motion target, and
    ``offset_words`` those that are a G43.1/G43.2 offset instead; ``motion`` the motion this
    block makes (the modal one when it has axis words but no motion code), ``axis_data``
    whether a G10/G28/G30/G52/G92 takes the axis words as data."""

    line: int
    groups: dict[int, int]
    mgroups: dict[int, int]
    vals: dict[str, float]
    axis_words: list[str]
    offset_words: list[str]
    axis_data: bool
    motion: int | None
    polar: bool
    assigns: Sequence[tuple[object, float]]

    @property
    def non_modal(self) -> int | None:
        return self.groups.get(Group.NON_MODAL)

    @property
    def motion_code(self) -> int | None:
        """The motion group's code written in this block (G80 included)."""
        return self.groups.get(Group.MOTION)


def _split_words(words: list) -> tuple[list[int], list[int], dict[str, float]] | None:
    """G codes (times ten), M codes, and the other words' values; None for a Fanuc program
    number line (O0001), which is nothing to run."""
    gcodes: list[int] = []
    mcodes: list[int] = []
    vals: dict[str, float] = {}
    first = True
    for letter, t in words:
        v = float(t)
        if not -VALUE_LIMIT < v < VALUE_LIMIT and not (letter == "F" and abs(v) < FEED_LIMIT):
            limit = "1e12" if letter == "F" else "1e9"
            raise BlockError(f"{letter} value {v:g} out of range (|value| < {limit})", letter)
        if letter == "G":
            c = round(v * 10.0)
            if abs(v * 10.0 - c) > 1e-6:
                raise BlockError(f"unknown G code G{v:g}", "G")
            gcodes.append(c)
        elif letter == "M":
            c = round(v)
            if abs(v - c) > 1e-9:
                raise BlockError(f"unknown M code M{v:g}", "M")
            mcodes.append(c)
        elif letter == "N":
            if not first:
                raise BlockError("N word (line number) must begin the block", "N")
        elif letter == "O":
            if len(words) != 1:
                raise BlockError("O-word program numbers must be alone on their line", "O")
            return None
        elif letter in vals:
            raise BlockError(f"two {letter} words in one block", letter)
        else:
            vals[letter] = v
        first = False
    return gcodes, mcodes, vals


def _g_groups(gcodes: list[int]) -> dict[int, int]:
    groups: dict[int, int] = {}
    for c in gcodes:
        g = G_GROUP.get(c)
        if g is None:
            what = G_UNSUPPORTED.get(c)
            if what:
                raise BlockError(f"{gname(c)} is not supported ({what})", gname(c))
            raise BlockError(f"unknown G code {gname(c)}", gname(c))
        if g is Group.MOTION and g in groups and G.G80 in (c, groups[g]):
            # LinuxCNC reads G80 beside another motion code as nothing: the other one counts
            groups[g] = groups[g] if c == G.G80 else c
            continue
        if g in groups:
            raise BlockError(f"{gname(groups[g])} and {gname(c)} are in the same modal group (one per block)",
                             gname(c))
        groups[g] = c
    return groups


def _m_groups(mcodes: list[int], setup: Setup) -> dict[int, int]:
    mgroups: dict[int, int] = {}
    for c in mcodes:
        g = M_GROUP.get(c)
        if g is None:
            why = M_UNSUPPORTED.get(c)
            raise BlockError(f"M{c} is not supported" + (f" ({why})" if why else ""), f"M{c}")
        if g is MGroup.USER and c not in setup.mcodes:
            raise BlockError(f"M{c} is a user M-code this machine does not define (add it to "
                             "[[mcodes]] in the machine configuration: a pause with a message, an "
                             "output or nothing)", f"M{c}")
        if g in mgroups:          # M7 M8 too: LinuxCNC 2.9 refuses them in one block
            raise BlockError(f"M{mgroups[g]} and M{c} are in the same modal group (one per block)", f"M{c}")
        mgroups[g] = c
    return mgroups


def _axis_words(vals: dict[str, float], polar: bool, setup: Setup) -> list[str]:
    axis_words = []
    if polar:                         # X and Y come from them once the block's modes are set
        which = "@" if "@" in vals else "^"
        if "X" in vals or "Y" in vals:
            raise BlockError("cannot use polar coordinates (@ ^) with X or Y words", which)
        if "X" not in setup.axis_index or "Y" not in setup.axis_index:
            raise BlockError("polar coordinates (@ ^) need X and Y axes", which)
        axis_words = ["X", "Y"]
    for letter in vals:
        if letter in "@^":
            continue
        if letter in AXIS_LETTERS:
            if letter not in setup.axis_index:
                raise BlockError(f"axis {letter} is not on this machine (axes: {' '.join(setup.axes)})",
                                 letter)
            axis_words.append(letter)
        elif letter not in WORD_LETTERS:
            if letter == "E":
                continue                  # its use is known once the motion is
            if letter in "UVW":
                raise BlockError(f"axis {letter} is not on this machine (axes: {' '.join(setup.axes)})",
                                 letter)
            raise BlockError(f"word {letter} is not supported", letter)
    return axis_words


def read_block(words: list, assigns: Sequence[tuple[object, float]], line_no: int, setup: Setup,
               motion_mode: int | None) -> Block | None:
    """The block of lexed ``words`` read and checked against the machine (``setup``) and the
    motion mode in force; None for a line that is only a Fanuc program number."""
    split = _split_words(words)
    if split is None:
        return None
    gcodes, mcodes, vals = split
    groups = _g_groups(gcodes)
    mgroups = _m_groups(mcodes, setup)
    polar = "@" in vals or "^" in vals
    axis_words = _axis_words(vals, polar, setup)

    g0 = groups.get(Group.NON_MODAL)
    g1 = groups.get(Group.MOTION)
    tool_length = groups.get(Group.TOOL_LENGTH)
    offset_words: list[str] = []
    if tool_length in (G.G43_1, G.G43_2) and axis_words:
        # the axis words are the offset: no motion in this block
        if g1 is not None and g1 != G.G80 or g0 == G.G28:
            raise BlockError("cannot use two G codes that both use axis values "
                             f"({gname(tool_length)} and a motion code)", gname(tool_length))
        offset_words, axis_words = axis_words, []
    axis_data = g0 in AXIS_USERS       # G10, G28, G30, G52, G92: the axis words are data
    if g0 is not None and axis_data and g1 is not None and g1 != G.G80 and axis_words:
        raise BlockError(f"cannot use two G codes that both use axis values ({gname(g0)} and a motion code)",
                         gname(g0))
    if g1 == G.G80 and axis_words and not axis_data:
        raise BlockError("cannot use axis values with G80", axis_words[0])
    motion: int | None
    if g1 is not None:
        motion = g1
    elif not axis_data and (axis_words or (motion_mode in (G.G2, G.G3)
                                           and any(c in vals for c in _CENTRE_LETTERS))):
        motion = motion_mode  # LinuxCNC 2.9: centre words alone repeat a modal G02/G03
    else:
        motion = None
    if motion == G.G80:
        motion = None
    if polar and (motion is None or axis_data or offset_words):
        # LinuxCNC: G10, G28, G30, G52, G92 and G43.1/G43.2 take no polar words either
        raise BlockError("polar coordinates (@ ^) can only be used for motion", "@" if "@" in vals else "^")
    if axis_words and motion is None and not axis_data:
        raise BlockError("axis words without a motion mode: program G00/G01/G02/G03 first", axis_words[0])
    _check_words(vals, groups, mgroups, motion, axis_words, setup)
    return Block(line_no, groups, mgroups, vals, axis_words, offset_words, axis_data, motion, polar, assigns)


def _check_words(vals: dict[str, float], groups: dict[int, int], mgroups: dict[int, int], motion: int | None,
                 axis_words: list[str], setup: Setup) -> None:
    """Every word has a code in the block that uses it, and the codes have the words they need
    (LinuxCNC 2.9's checks and messages' sense)."""
    g0 = groups.get(Group.NON_MODAL)
    g1 = groups.get(Group.MOTION)
    io = mgroups.get(MGroup.IO)
    path = groups.get(Group.PATH_CONTROL)
    comp = groups.get(Group.CUTTER_COMP)
    # G76: the taper; G33, G33.1 ignore it; M67, M68: the analog output
    if "E" in vals and motion not in SYNCHRONISED and io not in (M.M67, M.M68) and motion != G.G70:
        if io == M.M66:
            raise BlockError("M66 E (an analog input): this machine has no analog inputs", "E")
        raise BlockError("E word with no G33, G33.1, G76, M67 or M68 to use it", "E")
    is_arc = motion in (G.G2, G.G3)
    is_cycle = motion in CYCLES
    if g1 in (G.G5, G.G5_1) and not axis_words:
        raise BlockError(f"{gname(g1)} needs X or Y (all axes missing with a motion code)", gname(g1))
    if g0 in (G.G52, G.G92) and not axis_words:        # LinuxCNC: all axes missing with g52 or g92
        raise BlockError(f"{gname(g0)} needs an axis word (all axes missing with G52 or G92)", gname(g0))
    if motion in (G.G33, G.G33_1):
        name = gname(motion)
        if "K" not in vals:
            raise BlockError(f"{name} needs a K word (the thread pitch, length per turn)",
                             name if g1 == motion else "K")
        if "F" in vals:
            raise BlockError(f"F word with {name}: the feed is the pitch K times the spindle speed", "F")
    if motion == G.G76:
        where = "G76" if g1 == G.G76 else axis_words[0] if axis_words else "G"
        if "P" not in vals:
            raise BlockError("G76 needs a P word (the thread pitch, length per turn)", where)
        missing = [letter for letter in "IJK" if letter not in vals]
        if missing:
            raise BlockError(f"G76 needs I, J and K words (the thread's offset, first cut and depth): "
                             f"{' '.join(missing)} missing", where)
    for letter in _CENTRE_LETTERS:
        if (motion == G.G33_1 and letter in "IK" or motion == G.G33 and letter == "K"
                or motion == G.G76):
            continue
        if motion in LATHE_CYCLES and motion != G.G70 and letter in "IR":   # the depth of cut, the retract
            continue
        if letter in "IJ" and motion in (G.G5, G.G5_1):
            continue
        if letter in vals and not is_arc and not (letter == "R" and (is_cycle or g0 == G.G10)):
            users = ("G02/G03 or canned cycle" if letter == "R"
                     else "G02/G03, G05 or G05.1" if letter in "IJ" else "G02/G03")
            raise BlockError(f"{letter} word with no {users} to use it", letter)
    if "P" in vals and not (g0 in (G.G4, G.G10) or is_arc or path == G.G64 or MGroup.OVERRIDES in mgroups
                            or motion in CYCLE_TAKES_P or MGroup.IO in mgroups
                            or motion in (G.G5, G.G5_2, G.G76, G.G70)):
        raise BlockError("P word with no G code that uses it (G04, G02/G03, G05, G05.2, G64, G82, G84, "
                         "G86, G89)", "P")
    if ("Q" in vals and path != G.G64 and mgroups.get(MGroup.TOOL_CHANGE) != M.M61
            and motion not in CYCLE_NEEDS_Q and io not in (M.M66, M.M67, M.M68)
            and motion not in (G.G5, G.G76) and motion not in LATHE_CYCLES):
        raise BlockError("Q word with no code that uses it (G05, G64, M61, G73, G76, G83, M66, M67, "
                         "M68)", "Q")
    if ("D" in vals and comp not in (G.G41, G.G42, G.G41_1, G.G42_1)
            and groups.get(Group.SPINDLE_MODE) != G.G96 and motion not in LATHE_CYCLES):
        raise BlockError("D word with no G41, G41.1, G42, G42.1 or G96 to use it", "D")
    if groups.get(Group.SPINDLE_MODE) == G.G96 and "S" not in vals:
        raise BlockError("G96 needs an S word (the surface speed)", "G96")
    if ("L" in vals and not is_cycle and g0 != G.G10 and comp not in (G.G41_1, G.G42_1)
            and io != M.M66 and motion not in (G.G5_2, G.G76)):
        raise BlockError("L word with no canned cycle, G05.2, G10, G76 or M66 to use it", "L")
    if is_cycle:
        for letter in axis_words:
            if setup.rotary[setup.axis_index[letter]]:
                raise BlockError(f"cannot put an {letter} word in a canned cycle", letter)
    if "H" in vals and groups.get(Group.TOOL_LENGTH) not in (G.G43, G.G43_2) and motion != G.G76:
        raise BlockError("H word with no G43, G43.2 or G76 to use it", "H")
