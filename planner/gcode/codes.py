"""The G and M codes this interpreter reads, their modal groups, and what it refuses, by name.

A G code's value is its number times ten (``G.G38_2 == 382``), as LinuxCNC's interpreter keeps
them (``interp_internal.hh``), so that G38.2 and G3 are integers apart; ``str(G.G38_2)`` is
``"G38.2"``. M codes are their numbers. Modal groups follow RS274/NGC table 4 with LinuxCNC's
additions (group 16: G92.1-G92.3 after the non-modal codes; M groups 9-11).
"""

from __future__ import annotations

from enum import IntEnum

from planner.core.program import EventKind

__all__ = [
    "G", "M", "Group", "MGroup", "G_GROUP", "M_GROUP", "G_UNSUPPORTED", "M_UNSUPPORTED", "CYCLES", "PROBES",
    "LATHE_CYCLES", "SYNCHRONISED", "CYCLE_NEEDS_P", "CYCLE_NEEDS_Q", "CYCLE_TAKES_P", "AXIS_USERS",
    "SHOWN_GROUPS", "SYSTEMS", "PLANES", "PLANE_NAMES", "STOP_EVENTS", "USER_MCODES", "gname",
]


def gname(code10: int) -> str:
    """``G38.2`` for 382, ``G1`` for 10."""
    return f"G{code10 // 10}" if code10 % 10 == 0 else f"G{code10 // 10}.{code10 % 10}"


class G(IntEnum):
    """The G codes read (value: the code times ten)."""

    G0 = 0
    G1 = 10
    G2 = 20
    G3 = 30
    G4 = 40
    G5 = 50
    G5_1 = 51
    G5_2 = 52
    G5_3 = 53
    G7 = 70
    G8 = 80
    G10 = 100
    G17 = 170
    G18 = 180
    G19 = 190
    G20 = 200
    G21 = 210
    G28 = 280
    G28_1 = 281
    G30 = 300
    G30_1 = 301
    G33 = 330
    G33_1 = 331
    G38_2 = 382
    G38_3 = 383
    G38_4 = 384
    G38_5 = 385
    G40 = 400
    G41 = 410
    G41_1 = 411
    G42 = 420
    G42_1 = 421
    G43 = 430
    G43_1 = 431
    G43_2 = 432
    G49 = 490
    G52 = 520
    G53 = 530
    G54 = 540
    G55 = 550
    G56 = 560
    G57 = 570
    G58 = 580
    G59 = 590
    G59_1 = 591
    G59_2 = 592
    G59_3 = 593
    G61 = 610
    G61_1 = 611
    G64 = 640
    G70 = 700
    G71 = 710
    G71_1 = 711
    G71_2 = 712
    G72 = 720
    G72_1 = 721
    G72_2 = 722
    G73 = 730
    G74 = 740
    G76 = 760
    G80 = 800
    G81 = 810
    G82 = 820
    G83 = 830
    G84 = 840
    G85 = 850
    G86 = 860
    G89 = 890
    G90 = 900
    G90_1 = 901
    G91 = 910
    G91_1 = 911
    G92 = 920
    G92_1 = 921
    G92_2 = 922
    G92_3 = 923
    G93 = 930
    G94 = 940
    G95 = 950
    G96 = 960
    G97 = 970
    G98 = 980
    G99 = 990

    def __str__(self) -> str:
        return gname(self.value)


class M(IntEnum):
    """The M codes read (user M-codes M100-M199 aside: ``USER_MCODES``)."""

    M0 = 0
    M1 = 1
    M2 = 2
    M3 = 3
    M4 = 4
    M5 = 5
    M6 = 6
    M7 = 7
    M8 = 8
    M9 = 9
    M30 = 30
    M48 = 48
    M49 = 49
    M50 = 50
    M51 = 51
    M52 = 52
    M53 = 53
    M61 = 61
    M62 = 62
    M63 = 63
    M64 = 64
    M65 = 65
    M66 = 66
    M67 = 67
    M68 = 68
    M70 = 70
    M71 = 71
    M72 = 72
    M73 = 73

    def __str__(self) -> str:
        return f"M{self.value}"


class Group(IntEnum):
    """Modal groups of the G codes (RS274/NGC table 4; 16 is LinuxCNC 2.9's own)."""

    NON_MODAL = 0        # G4 G10 G28 G30 G52 G53 G92 ...
    MOTION = 1           # G0-G3 G5 G33 G38.x G7x G73-G89 G80
    PLANE = 2            # G17 G18 G19
    DISTANCE = 3         # G90 G91
    ARC_DISTANCE = 4     # G90.1 G91.1
    FEED_MODE = 5        # G93 G94 G95
    UNITS = 6            # G20 G21
    CUTTER_COMP = 7      # G40 G41 G42 G41.1 G42.1
    TOOL_LENGTH = 8      # G43 G43.1 G43.2 G49
    RETURN_MODE = 10     # G98 G99
    COORD_SYSTEM = 12    # G54-G59.3
    PATH_CONTROL = 13    # G61 G61.1 G64
    SPINDLE_MODE = 14    # G96 G97
    LATHE_MODE = 15      # G7 G8
    AXIS_OFFSETS = 16    # G92.1 G92.2 G92.3


class MGroup(IntEnum):
    """Modal groups of the M codes."""

    STOPPING = 4         # M0 M1 M2 M30
    IO = 5               # M62-M68
    TOOL_CHANGE = 6      # M6 M61
    SPINDLE = 7          # M3 M4 M5
    COOLANT = 8          # M7 M8 M9
    OVERRIDES = 9        # M48-M53
    USER = 10            # M100-M199
    MODAL_STATE = 11     # M70-M73


USER_MCODES = range(100, 200)

G_GROUP: dict[int, Group] = {
    **dict.fromkeys((G.G4, G.G28, G.G53, G.G10, G.G28_1, G.G30, G.G30_1, G.G52, G.G92), Group.NON_MODAL),
    **dict.fromkeys((G.G92_1, G.G92_2, G.G92_3), Group.AXIS_OFFSETS),
    **dict.fromkeys((G.G0, G.G1, G.G2, G.G3, G.G80, G.G38_2, G.G38_3, G.G38_4, G.G38_5, G.G33_1, G.G33,
                     G.G76, G.G70, G.G71, G.G71_1, G.G71_2, G.G72, G.G72_1, G.G72_2, G.G5, G.G5_1, G.G5_2,
                     G.G73, G.G74, G.G81, G.G82, G.G83, G.G84, G.G85, G.G86, G.G89), Group.MOTION),
    G.G5_3: Group.NON_MODAL,
    **dict.fromkeys((G.G17, G.G18, G.G19), Group.PLANE),
    **dict.fromkeys((G.G90, G.G91), Group.DISTANCE),
    **dict.fromkeys((G.G90_1, G.G91_1), Group.ARC_DISTANCE),
    **dict.fromkeys((G.G93, G.G94, G.G95), Group.FEED_MODE),
    **dict.fromkeys((G.G96, G.G97), Group.SPINDLE_MODE),
    **dict.fromkeys((G.G20, G.G21), Group.UNITS),
    **dict.fromkeys((G.G40, G.G41, G.G42, G.G41_1, G.G42_1), Group.CUTTER_COMP),
    **dict.fromkeys((G.G43, G.G43_1, G.G43_2, G.G49), Group.TOOL_LENGTH),
    **dict.fromkeys((G.G54, G.G55, G.G56, G.G57, G.G58, G.G59, G.G59_1, G.G59_2, G.G59_3),
                    Group.COORD_SYSTEM),
    **dict.fromkeys((G.G61, G.G61_1, G.G64), Group.PATH_CONTROL),
    **dict.fromkeys((G.G98, G.G99), Group.RETURN_MODE),
    **dict.fromkeys((G.G7, G.G8), Group.LATHE_MODE),
}
M_GROUP: dict[int, MGroup] = {
    **dict.fromkeys((M.M0, M.M1, M.M2, M.M30), MGroup.STOPPING),
    **dict.fromkeys((M.M6, M.M61), MGroup.TOOL_CHANGE),
    **dict.fromkeys((M.M3, M.M4, M.M5), MGroup.SPINDLE),
    **dict.fromkeys((M.M7, M.M8, M.M9), MGroup.COOLANT),
    **dict.fromkeys((M.M62, M.M63, M.M64, M.M65, M.M66, M.M67, M.M68), MGroup.IO),
    **dict.fromkeys((M.M70, M.M71, M.M72, M.M73), MGroup.MODAL_STATE),
    **dict.fromkeys((M.M48, M.M49, M.M50, M.M51, M.M52, M.M53), MGroup.OVERRIDES),
    **dict.fromkeys(USER_MCODES, MGroup.USER),
}
M_UNSUPPORTED = {19: "M19 orients the spindle, which this machine's spindle cannot",
                 60: "M60 exchanges pallets and pauses; this machine has no pallet shuttle"}
G_UNSUPPORTED = {
    870: "G87 back boring: it needs an oriented spindle stop (M19), which this machine's spindle "
         "does not have",
    880: "G88 boring with a manual retract: the operator would jog the spindle out during a "
         "program stop; use G86 or G89",
    150: "G15 polar coordinates",
    160: "G16 polar coordinates",
    680: "G68 coordinate rotation", 690: "G69 coordinate rotation",
    171: "G17.1 selects the UV plane, of U and V axes this machine does not have",
    181: "G18.1 selects the WU plane, of U and W axes this machine does not have",
    191: "G19.1 selects the VW plane, of V and W axes this machine does not have",
}

#: canned cycles (motion group 1), as LinuxCNC 2.9 runs them (interp_cycles.cc)
CYCLES = frozenset({G.G73, G.G74, G.G81, G.G82, G.G83, G.G84, G.G85, G.G86, G.G89})
#: G38.2-G38.5, straight probe moves (motion group 1, modal as in LinuxCNC)
PROBES = frozenset({G.G38_2, G.G38_3, G.G38_4, G.G38_5})
#: the lathe cycles G70 (finishing), G71/G72 (roughing; .1 no pockets, .2 pockets only)
LATHE_CYCLES = frozenset({G.G70, G.G71, G.G71_1, G.G71_2, G.G72, G.G72_1, G.G72_2})
#: G33, G33.1, G76: feed moves at the pitch (K, P) times the spindle speed; F is not theirs
SYNCHRONISED = frozenset({G.G33, G.G33_1, G.G76})
CYCLE_NEEDS_P = frozenset({G.G82, G.G86, G.G89})
CYCLE_NEEDS_Q = frozenset({G.G73, G.G83})
CYCLE_TAKES_P = CYCLE_NEEDS_P | {G.G74, G.G84}
#: non-modal codes whose axis words are data, not a motion target
AXIS_USERS = frozenset({G.G10, G.G28, G.G30, G.G52, G.G92})
#: the modal groups the panel shows
SHOWN_GROUPS = frozenset({Group.PLANE, Group.DISTANCE, Group.UNITS, Group.CUTTER_COMP, Group.TOOL_LENGTH,
                          Group.COORD_SYSTEM, Group.PATH_CONTROL, Group.LATHE_MODE})
#: coordinate systems 1-9
SYSTEMS = (G.G54, G.G55, G.G56, G.G57, G.G58, G.G59, G.G59_1, G.G59_2, G.G59_3)
#: plane code -> (name, first, second, normal, centre letter of first, of second, letter not allowed)
PLANES: dict[int, tuple[str, str, str, str, str, str, str]] = {
    G.G17: ("XY", "X", "Y", "Z", "I", "J", "K"),
    G.G18: ("ZX", "Z", "X", "Y", "K", "I", "J"),
    G.G19: ("YZ", "Y", "Z", "X", "J", "K", "I"),
}
PLANE_NAMES: dict[int, str] = {G.G17: "G17", G.G18: "G18", G.G19: "G19"}
STOP_EVENTS: dict[int, EventKind] = {M.M0: EventKind.PAUSE, M.M1: EventKind.OPTIONAL_PAUSE,
                                     M.M2: EventKind.END, M.M30: EventKind.END}
