"""The machine around the drives as its configuration wires it: terminals, the named signals,
homing to switches and the interlocks; checked as one, and turned into what the 1 ms loop
watches.

Signals (``[signals]``) are LinuxCNC's HAL signals of the same meaning, each wired to one bit:
``"<slave>:<bit>"``, the slave's bus position (a drive's or a terminal's, as ``[[bus.drives]]``
and ``[[bus.terminals]]`` count them) and its bit (a terminal's channel from 0; a drive's bit of
0x60FD for an input, of 0x60FE:1 for an output), with ``!`` in front when the bit reads 0
while the signal is true (a normally closed contact: a broken wire then reads as the safe
state). The limit and home switches of an axis default to the bits CiA 402 gives them in the
axis' drive's 0x60FD (negative limit 0, positive limit 1, home 2); a gantry's second side has
its own (``limit_neg2_<axis>``, ``limit_pos2_<axis>``, ``home2_<axis>``), by default on its
second drive's bits.

The 1 ms loop numbers its drives as the machine's axes, then each gantry's second drive (named
``<axis>2``, ``worker_drives``); its input words are those drives' 0x60FD, then the terminals'.

The one check (``wiring_from_valid``) refuses, naming the key and its line: a slave that is not
on the bus, a terminal channel that does not exist or points the wrong way (an input on an
output terminal), a signal for an axis the machine does not have, one bit used by two signals
(or by a signal and an ``[[inputs]]``/``[[outputs]]`` entry, the probe or the spindle's bits),
and homing to switches without a home switch or search settings for every axis. An axis'
home switch may share the bit of one of its limit switches when that axis homes with its
limits ignored (LinuxCNC's shared home and limit switch).
"""

from __future__ import annotations

import enum
import math
import re
from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import Any

from ethercat.errors import ConfigurationError as BusConfigurationError
from ethercat.sim_io import SimSwitch
from ethercat.terminals import TerminalKind, TerminalSpec, TerminalType, terminal_type
from ethercat.worker import GantrySpec, HandwheelSpec, InputWatch, SwitchHoming, WatchAction
from planner.core.machine import MachineSpec
from planner.core.schema import Locator

__all__ = [
    "AXIS_SIGNALS", "SIGNALS", "AxisHoming", "HandwheelSettings", "InterlockSettings", "MachineWiring",
    "SignalDef", "SignalWire", "TerminalSetting", "WheelMode", "Wire", "WorkerIo", "analog_place", "axis_at",
    "worker_drives",
    "wiring_from_valid", "worker_io",
]


class Direction(enum.Enum):
    IN = "in"
    OUT = "out"


@dataclass(frozen=True, slots=True)
class SignalDef:
    """One signal: its direction, the value a healthy machine at rest shows (inputs), what
    LinuxCNC calls it ("" where LinuxCNC has no such signal), and what it does here."""

    name: str
    direction: Direction
    healthy: bool
    hal: str
    meaning: str


#: every signal (per axis: ``<name>_<axis>``), in the order the Diagnostics page lists them
SIGNALS: tuple[SignalDef, ...] = (
    SignalDef("estop_chain_ok", Direction.IN, True, "iocontrol.0.emc-enable-in",
              "the E-stop chain (safety relay) is closed; open: E-stop, no reset until closed"),
    SignalDef("door_closed", Direction.IN, True, "",
              "the guard door is closed; open: a program holds and the spindle stops"),
    SignalDef("air_ok", Direction.IN, True, "", "air pressure present"),
    SignalDef("lube_ok", Direction.IN, True, "iocontrol.0.lube_level", "lubricant level or pressure present"),
    SignalDef("cycle_start", Direction.IN, False, "halui.program.run", "the machine's Cycle start button"),
    SignalDef("feed_hold", Direction.IN, False, "halui.program.pause", "the machine's Feed hold button"),
    SignalDef("stop", Direction.IN, False, "halui.program.stop", "the machine's Stop button"),
    SignalDef("spindle_at_speed", Direction.IN, False, "spindle.0.at-speed",
              "the spindle drive reports the commanded speed"),
    SignalDef("limit_pos", Direction.IN, False, "joint.N.pos-lim-sw-in", "the positive limit switch"),
    SignalDef("limit_neg", Direction.IN, False, "joint.N.neg-lim-sw-in", "the negative limit switch"),
    SignalDef("home", Direction.IN, False, "joint.N.home-sw-in", "the home switch"),
    SignalDef("limit_pos2", Direction.IN, False, "joint.N.pos-lim-sw-in",
              "a gantry's second side: its positive limit switch"),
    SignalDef("limit_neg2", Direction.IN, False, "joint.N.neg-lim-sw-in",
              "a gantry's second side: its negative limit switch"),
    SignalDef("home2", Direction.IN, False, "joint.N.home-sw-in", "a gantry's second side: its home switch"),
    SignalDef("coolant_flood", Direction.OUT, False, "iocontrol.0.coolant-flood", "flood coolant (M8)"),
    SignalDef("coolant_mist", Direction.OUT, False, "iocontrol.0.coolant-mist", "mist coolant (M7)"),
    SignalDef("lube_pump", Direction.OUT, False, "iocontrol.0.lube",
              "the lube pump, on while the drives are on"),
    SignalDef("work_light", Direction.OUT, False, "", "the work light"),
    SignalDef("spindle_enable", Direction.OUT, False, "spindle.0.on", "on while the spindle turns"),
    SignalDef("jog_enable", Direction.IN, False, "axis.L.jog-enable",
              "the handwheel's axis selector stands on this axis"),
    SignalDef("jog_scale_x10", Direction.IN, False, "", "the handwheel's step selector stands on x10"),
    SignalDef("jog_scale_x100", Direction.IN, False, "", "the handwheel's step selector stands on x100"),
)
_BY_NAME = {s.name: s for s in SIGNALS}
AXIS_SIGNALS = ("limit_pos", "limit_neg", "home", "jog_enable", "limit_pos2", "limit_neg2", "home2")
#: CiA 402's bits of 0x60FD for an axis' switches (and a gantry's second drive's)
DRIVE_SWITCH_BITS = {"limit_neg": 0, "limit_pos": 1, "home": 2}
SECOND_SWITCH_BITS = {"limit_neg2": 0, "limit_pos2": 1, "home2": 2}
_WIRE = re.compile(r"\s*(!?)\s*(\d+)\s*:\s*(\d+)\s*")


@dataclass(frozen=True, slots=True)
class Wire:
    """A bit on the bus: slave position, bit, read inverted (a normally closed contact)."""

    slave: int
    bit: int
    inverted: bool = False

    @staticmethod
    def parse(text: str) -> Wire:
        m = _WIRE.fullmatch(text)
        if m is None:
            raise ValueError(f"{text!r} is not a wire: write \"<slave>:<bit>\", \"!\" in front for a "
                             "normally closed contact (e.g. \"4:0\", \"!4:3\")")
        return Wire(int(m.group(2)), int(m.group(3)), m.group(1) == "!")

    def text(self) -> str:
        return f"{'!' if self.inverted else ''}{self.slave}:{self.bit}"


@dataclass(frozen=True, slots=True)
class SignalWire:
    """One wired signal: its key (``limit_pos_X``), definition, axis ("" for the machine's),
    where it is wired, and whether that is CiA 402's default (not written to the file)."""

    key: str
    signal: SignalDef
    axis: str
    wire: Wire
    by_default: bool = False


@dataclass(frozen=True, slots=True)
class TerminalSetting:
    """One ``[[bus.terminals]]``."""

    position: int
    type: str
    name: str = ""

    @property
    def terminal_type(self) -> TerminalType:
        return terminal_type(self.type)

    def spec(self) -> TerminalSpec:
        return TerminalSpec(self.position, self.type, self.name)


@dataclass(frozen=True, slots=True)
class AxisHoming:
    """One ``[[homing.axes]]`` (LinuxCNC's HOME_SEARCH_VEL, HOME_LATCH_VEL, HOME_FINAL_VEL,
    HOME_OFFSET, HOME, HOME_SEQUENCE, HOME_IGNORE_LIMITS, HOME_USE_INDEX)."""

    axis: str
    search_vel: float
    latch_vel: float
    final_vel: float = 0.0
    offset: float = 0.0
    home: float = 0.0
    sequence: int = 0
    ignore_limits: bool = False
    max_travel: float | None = None
    use_index: bool = False
    gantry_offset: float | None = None

    @property
    def second_offset(self) -> float:
        """A gantry's second side: its home switch's machine coordinate."""
        return self.offset if self.gantry_offset is None else self.gantry_offset


@dataclass(frozen=True, slots=True)
class InterlockSettings:
    air_lost: str = "stop"
    lube_lost: str = "warning"
    door_open_jog_mm_s: float = 0.0


class WheelMode(enum.Enum):
    POSITION = "position"     # every detent moves its step (LinuxCNC's jog-vel-mode false)
    VELOCITY = "velocity"     # counts the axis cannot follow are dropped (jog-vel-mode true)


@dataclass(frozen=True, slots=True)
class HandwheelSettings:
    """``[handwheel]``: the encoder terminal (bus position; None: no handwheel), counts per
    detent, the mode, the step of one detent at x1, x10, x100, the largest count change of one
    cycle that is a turn."""

    terminal: int | None = None
    counts_per_detent: int = 4
    mode: WheelMode = WheelMode.POSITION
    steps: tuple[float, float, float] = (0.001, 0.01, 0.1)
    max_counts_per_cycle: int = 256


@dataclass(frozen=True, slots=True)
class MachineWiring:
    """Terminals, wired signals (by key), homing to switches, interlocks and the handwheel."""

    terminals: tuple[TerminalSetting, ...] = ()
    signals: tuple[SignalWire, ...] = ()
    homing: tuple[AxisHoming, ...] = ()
    interlocks: InterlockSettings = InterlockSettings()
    handwheel: HandwheelSettings = HandwheelSettings()

    def get(self, key: str) -> SignalWire | None:
        for s in self.signals:
            if s.key == key:
                return s
        return None

    def homing_of(self, axis: str) -> AxisHoming | None:
        for h in self.homing:
            if h.axis == axis:
                return h
        return None

    def terminal_index(self, position: int) -> int:
        for k, t in enumerate(self.terminals):
            if t.position == position:
                return k
        return -1

    def has(self, key: str) -> bool:
        return self.get(key) is not None

    def homing_groups(self, axes: Sequence[str]) -> list[list[int]]:
        """The axes (indices) homing together, in their sequence order."""
        by_seq: dict[int, list[int]] = {}
        for h in self.homing:
            by_seq.setdefault(h.sequence, []).append(axes.index(h.axis))
        return [sorted(by_seq[k]) for k in sorted(by_seq)]


# ------------------------------------------------------------------------------ reading
def wiring_from_valid(valid: dict[str, Any], machine: MachineSpec, loc: Locator, homing_method: str,
                      reserved: Sequence[tuple[str, Direction, int, int]] = ()) -> MachineWiring:
    """The wiring of a validated configuration, checked as one (the module docstring).
    ``reserved``: bits others use, as (what, direction, slave position, bit)."""
    drive_slave = {a.name: a.drive_position for a in machine.axes}
    drives_at = dict(worker_drives(machine))
    terminals: list[TerminalSetting] = []
    for k, t in enumerate(valid["bus"]["terminals"]):
        path: tuple[str | int, ...] = ("bus", "terminals", k)
        try:
            setting = TerminalSetting(t["position"], t["type"].upper(), t["name"])
            terminal_type(setting.type)
        except BusConfigurationError as exc:
            raise loc.fail((*path, "type"), str(exc)) from None
        if setting.position in drives_at:
            raise loc.fail((*path, "position"), f"slave {setting.position} is the drive "
                                                f"{drives_at[setting.position]}")
        if any(o.position == setting.position for o in terminals):
            raise loc.fail((*path, "position"), f"slave {setting.position} is given twice")
        terminals.append(setting)
    by_position = {t.position: t for t in terminals}
    for table, kind in (("outputs", TerminalKind.DIGITAL_OUT), ("inputs", TerminalKind.DIGITAL_IN)):
        for i, o in enumerate(valid[table]):
            if o["slave"] is None:
                continue
            term = by_position.get(o["slave"])
            if term is None or term.terminal_type.kind is not kind:
                what = "outputs" if kind is TerminalKind.DIGITAL_OUT else "inputs"
                found = f"a {term.terminal_type.name}" if term is not None else "no terminal"
                raise loc.fail((table, i, "slave"), f"slave {o['slave']} is {found}, not a terminal with "
                                                    f"digital {what} ([[bus.terminals]])")
            if not 0 <= o["bit"] < term.terminal_type.channels:
                raise loc.fail((table, i, "bit"), f"a {term.terminal_type.name} has channels "
                                                  f"0..{term.terminal_type.channels - 1}, not {o['bit']}")
    interlocks = InterlockSettings(**valid["interlocks"])
    homing = tuple(AxisHoming(**h) for h in valid["homing"]["axes"])

    signals: list[SignalWire] = []
    raw: dict[str, str | None] = dict(valid["signals"])
    axes = [a.name for a in machine.axes]
    for key, text in raw.items():
        if key in _BY_NAME:
            base, axis = key, ""
        else:
            base, _, axis = key.rpartition("_")
            if axis not in axes:
                raise loc.fail(("signals", key), f"this machine has no axis {axis} (axes: {' '.join(axes)})")
            if base in SECOND_SWITCH_BITS and machine.axes[axes.index(axis)].gantry_drive is None:
                raise loc.fail(("signals", key), f"axis {axis} has one drive: {base} is a gantry's second "
                                                 "side's switch ([[axes]] gantry_drive)")
        if not text:
            continue
        try:
            wire = Wire.parse(text)
        except ValueError as exc:
            raise loc.fail(("signals", key), str(exc)) from None
        signals.append(SignalWire(key, _BY_NAME[base], axis, wire))
    for axis in axes:                           # CiA 402's switches of the axis' drive by default
        for base, bit in DRIVE_SWITCH_BITS.items():
            key = f"{base}_{axis}"
            if key not in raw:
                signals.append(SignalWire(key, _BY_NAME[base], axis, Wire(drive_slave[axis], bit), True))
        second = machine.axes[axes.index(axis)].gantry_drive
        for base, bit in SECOND_SWITCH_BITS.items():
            key = f"{base}_{axis}"
            if key not in raw and second is not None:
                signals.append(SignalWire(key, _BY_NAME[base], axis, Wire(second, bit), True))

    used: dict[tuple[Direction, int, int], str] = {}
    for what, direction, slave, bit in reserved:
        used[(direction, slave, bit)] = what
    for s in signals:
        path = ("signals", s.key)
        w, direction = s.wire, s.signal.direction
        term = by_position.get(w.slave)
        if term is not None:
            tt = term.terminal_type
            wanted = TerminalKind.DIGITAL_IN if direction is Direction.IN else TerminalKind.DIGITAL_OUT
            if tt.kind is not wanted:
                raise loc.fail(path, f"slave {w.slave} is a {tt.name} ({tt.description}), not a terminal "
                                     f"with digital {'inputs' if direction is Direction.IN else 'outputs'}")
            if not 0 <= w.bit < tt.channels:
                raise loc.fail(path, f"a {tt.name} has channels 0..{tt.channels - 1}, not {w.bit}")
        elif w.slave in drives_at:
            if not 0 <= w.bit < 32:
                raise loc.fail(path, f"a drive's {'0x60FD' if direction is Direction.IN else '0x60FE:1'} has "
                                     f"bits 0..31, not {w.bit}")
        else:
            known = sorted([*drives_at, *by_position])
            raise loc.fail(path, f"no slave at bus position {w.slave} (drives and terminals at "
                                 f"{', '.join(map(str, known))})")
        spot = (direction, w.slave, w.bit)
        other = used.get(spot)
        if other is not None and not _may_share(s, other, homing):
            if s.by_default:
                continue                          # a default gives way to what the file says
            raise loc.fail(path, f"bit {w.bit} of slave {w.slave} is already {other}")
        used.setdefault(spot, f"signal {s.key}")
    signals = [s for s in signals if not (s.by_default and _taken(s, signals, used))]

    if homing_method == "switches":
        for i, h in enumerate(homing):
            if h.axis not in axes:
                raise loc.fail(("homing", "axes", i, "axis"), f"this machine has no axis {h.axis}")
            if h.search_vel == 0.0 or h.latch_vel == 0.0:
                raise loc.fail(("homing", "axes", i), "search_vel and latch_vel must not be 0 (their signs "
                                                      "say the directions)")
        seen = [h.axis for h in homing]
        twice = sorted({a for a in seen if seen.count(a) > 1})
        if twice:
            raise loc.fail(("homing", "axes"), f"an axis has two [[homing.axes]] tables: {' '.join(twice)}")
        missing = [a for a in axes if not any(h.axis == a for h in homing)]
        if missing:
            raise loc.fail(("homing", "method"), "homing to switches needs a [[homing.axes]] table for every "
                                                 f"axis; missing: {' '.join(missing)}")
    return MachineWiring(tuple(terminals), tuple(signals), homing, interlocks,
                         _handwheel(valid["handwheel"], by_position, loc))


def _handwheel(h: dict[str, Any], by_position: dict[int, TerminalSetting], loc: Locator) -> HandwheelSettings:
    """``[handwheel]``, its terminal an encoder terminal of ``[[bus.terminals]]``."""
    steps = tuple(float(x) for x in h["steps"])
    if len(steps) != 3:
        raise loc.fail(("handwheel", "steps"), f"three steps (x1, x10, x100), not {len(steps)}")
    term = by_position.get(h["terminal"]) if h["terminal"] is not None else None
    if h["terminal"] is not None and (term is None or term.terminal_type.kind is not TerminalKind.ENCODER):
        found = f"a {term.terminal_type.name}" if term is not None else "no terminal"
        raise loc.fail(("handwheel", "terminal"), f"slave {h['terminal']} is {found}, not an encoder "
                                                  "terminal (an EL5101 in [[bus.terminals]])")
    return HandwheelSettings(h["terminal"], h["counts_per_detent"], WheelMode(h["mode"]),
                             (steps[0], steps[1], steps[2]), h["max_counts_per_cycle"])


def analog_place(wiring: MachineWiring, text: str) -> tuple[int, int]:
    """Where ``"<slave>:<channel>"`` is: (the index of its analog output terminal in
    ``wiring.terminals``, the channel); ValueError saying why it is not one."""
    wire = Wire.parse(text)
    if wire.inverted:
        raise ValueError(f"{text!r}: an analog output has no normally closed contact (no \"!\")")
    k = wiring.terminal_index(wire.slave)
    kind = wiring.terminals[k].terminal_type if k >= 0 else None
    if kind is None or kind.kind is not TerminalKind.ANALOG_OUT:
        found = f"a {kind.name}" if kind is not None else "no terminal"
        raise ValueError(f"slave {wire.slave} is {found}, not an analog output terminal (an EL4xxx in "
                         "[[bus.terminals]])")
    if not 0 <= wire.bit < kind.channels:
        raise ValueError(f"a {kind.name} has channels 0..{kind.channels - 1}, not {wire.bit}")
    return k, wire.bit


def _may_share(s: SignalWire, other: str, homing: tuple[AxisHoming, ...]) -> bool:
    """An axis' home switch on one of its limit switches, when that axis ignores its limits while
    homing."""
    if not other.startswith("signal "):
        return False
    other_key = other[len("signal "):]
    keys = {s.key, other_key}
    for h in homing:
        if h.ignore_limits and (keys == {f"home_{h.axis}", f"limit_pos_{h.axis}"}
                                or keys == {f"home_{h.axis}", f"limit_neg_{h.axis}"}):
            return True
    return False


def _taken(s: SignalWire, signals: Sequence[SignalWire], used: dict[tuple[Direction, int, int], str]) -> bool:
    """A default wiring whose bit the file gives to something else."""
    return used.get((s.signal.direction, s.wire.slave, s.wire.bit)) != f"signal {s.key}"


def signal_lines(wiring: MachineWiring) -> list[str]:
    """``[signals]``, ``[interlocks]`` and ``[[bus.terminals]]`` as the file writes them (the
    defaults of CiA 402 left out)."""
    out = ["[signals]"]
    out += [f'{s.key} = "{s.wire.text()}"' for s in wiring.signals if not s.by_default]
    i = wiring.interlocks
    out += ["", "[interlocks]", f'air_lost = "{i.air_lost}"', f'lube_lost = "{i.lube_lost}"',
            f"door_open_jog_mm_s = {float(i.door_open_jog_mm_s)!r}", ""]
    return out


def terminal_lines(wiring: MachineWiring) -> list[str]:
    out: list[str] = []
    for t in wiring.terminals:
        out += ["[[bus.terminals]]", f"position = {t.position}", f'type = "{t.type}"']
        if t.name:
            out.append(f'name = "{t.name}"')
    return out


def handwheel_lines(wiring: MachineWiring) -> list[str]:
    h = wiring.handwheel
    out = ["[handwheel]"]
    if h.terminal is not None:
        out.append(f"terminal = {h.terminal}")
    return out + [f"counts_per_detent = {h.counts_per_detent}", f'mode = "{h.mode.value}"',
                  f"steps = [{', '.join(repr(float(x)) for x in h.steps)}]",
                  f"max_counts_per_cycle = {h.max_counts_per_cycle}"]


def homing_lines(wiring: MachineWiring) -> list[str]:
    out: list[str] = []
    for h in wiring.homing:
        out += ["[[homing.axes]]", f'axis = "{h.axis}"', f"search_vel = {float(h.search_vel)!r}",
                f"latch_vel = {float(h.latch_vel)!r}", f"final_vel = {float(h.final_vel)!r}",
                f"offset = {float(h.offset)!r}", f"home = {float(h.home)!r}", f"sequence = {h.sequence}",
                f"ignore_limits = {'true' if h.ignore_limits else 'false'}"]
        if h.max_travel is not None:
            out.append(f"max_travel = {float(h.max_travel)!r}")
        if h.use_index:
            out.append("use_index = true")
        if h.gantry_offset is not None:
            out.append(f"gantry_offset = {float(h.gantry_offset)!r}")
    return out


# ------------------------------------------------------------------------------ the loop's part
@dataclass(frozen=True, slots=True)
class WorkerIo:
    """What the worker is given: its terminals, the inputs it watches (with the keys of the
    signals they are), homing to switches, and for a simulated bus its switches and rest words."""

    terminals: tuple[TerminalSpec, ...]
    watches: tuple[InputWatch, ...]
    switch_homing: tuple[SwitchHoming, ...]
    sim_switches: tuple[SimSwitch, ...]
    input_rest: tuple[int, ...]
    sim_index_pitch: tuple[float, ...] = ()
    handwheel: HandwheelSpec | None = None
    gantry: tuple[GantrySpec, ...] = ()


#: how far beyond its soft limit a simulated axis' limit switch closes (mm or deg)
SIM_LIMIT_MARGIN = 2.0
#: the simulated encoders' index pulse: one per this much travel (a 5 mm screw's turn, or 5°)
SIM_INDEX_PITCH = 5.0
_FAR = 1e9


def worker_drives(machine: MachineSpec) -> tuple[tuple[int, str], ...]:
    """The 1 ms loop's drives in its order, (slave position, name): the axes', then each
    gantry's second drive (``<axis>2``)."""
    return (*((a.drive_position, a.name) for a in machine.axes),
            *((a.gantry_drive, f"{a.name}2") for a in machine.axes if a.gantry_drive is not None))


def axis_at(machine: MachineSpec, position: int) -> int:
    """The loop's index of the drive that is the slave at bus ``position`` (an axis', or after
    them a gantry's second drive); -1 when none is."""
    return next((i for i, (p, _name) in enumerate(worker_drives(machine)) if p == position), -1)


def input_word(wiring: MachineWiring, machine: MachineSpec, s: SignalWire) -> tuple[int, int, bool]:
    """Where the worker reads a wired input: (word, bit, level read while the signal is true);
    words 0..n-1 the drives' 0x60FD (``worker_drives``), n.. the terminals'."""
    k = wiring.terminal_index(s.wire.slave)
    if k >= 0:
        word = len(worker_drives(machine)) + k
    else:
        word = axis_at(machine, s.wire.slave)
    return word, s.wire.bit, not s.wire.inverted


def worker_io(wiring: MachineWiring, machine: MachineSpec, homing_method: str, simulated: bool) -> WorkerIo:
    """The worker's share of the wiring (see ``WorkerIo``). A gantry's second side is the
    loop's drive ``followers[axis]``: its limits, its homing (with its leader's velocities) and
    its simulated switches are its own."""
    axes = [a.name for a in machine.axes]
    followers = {name[:-1]: i for i, (_p, name) in enumerate(worker_drives(machine)) if i >= len(axes)}
    watches: list[InputWatch] = []
    chain = wiring.get("estop_chain_ok")
    if chain is not None:
        word, bit, level = input_word(wiring, machine, chain)
        watches.append(InputWatch(WatchAction.ESTOP_CHAIN, word, bit, not level, name=chain.key))
    for i, a in enumerate(axes):
        second = followers.get(a, -1)
        for base, side, drive in (("limit_pos", 1, i), ("limit_neg", -1, i),
                                  ("limit_pos2", 1, second), ("limit_neg2", -1, second)):
            s = wiring.get(f"{base}_{a}")
            if s is not None and drive >= 0:
                word, bit, level = input_word(wiring, machine, s)
                watches.append(InputWatch(WatchAction.LIMIT, word, bit, level, axis=drive, side=side,
                                          name=s.key))
    homing: list[SwitchHoming] = []
    if homing_method == "switches":
        for h in wiring.homing:
            i = axes.index(h.axis)
            ax = machine.axes[i]
            switch = wiring.get(f"home_{h.axis}")
            if switch is None:
                continue
            word, bit, level = input_word(wiring, machine, switch)
            travel = h.max_travel if h.max_travel is not None else 1.2 * (ax.max_pos - ax.min_pos)
            if not math.isfinite(travel) or travel <= 0.0:
                travel = 720.0                    # a rotary axis without end: two turns
            first = SwitchHoming(i, word, bit, level, h.search_vel, h.latch_vel, travel,
                                 float(ax.a_motion), float(ax.j_motion), h.ignore_limits, h.use_index)
            homing.append(first)
            switch2 = wiring.get(f"home2_{h.axis}")
            if h.axis in followers and switch2 is not None:   # the second side: its own switch
                word, bit, level = input_word(wiring, machine, switch2)
                homing.append(replace(first, axis=followers[h.axis], word=word, bit=bit, level=level))
    gantry = tuple(GantrySpec(axes.index(a), f, machine.axes[axes.index(a)].gantry_skew_window,
                              _switch_offset(wiring.homing_of(a), homing_method))
                   for a, f in followers.items())
    switches: list[SimSwitch] = []
    rest = [0] * len(wiring.terminals)
    if simulated:
        for s in wiring.signals:
            if s.signal.direction is not Direction.IN:
                continue
            k = wiring.terminal_index(s.wire.slave)
            raw_healthy = s.signal.healthy != s.wire.inverted
            if k >= 0 and raw_healthy:
                rest[k] |= 1 << s.wire.bit
            if not s.axis:
                continue
            i = axes.index(s.axis)
            ax = machine.axes[i]
            name, homing_s = s.signal.name, wiring.homing_of(s.axis)
            if name.endswith("2"):            # a gantry's second side: its drive, its switch's place
                i, name = followers[s.axis], name[:-1]
                if homing_s is not None:
                    homing_s = replace(homing_s, offset=homing_s.second_offset)
            lo, hi = _sim_range(name, float(ax.min_pos), float(ax.max_pos), homing_s)
            if lo is None or hi is None:
                continue
            place = {"terminal": k} if k >= 0 else {"drive": axis_at(machine, s.wire.slave)}
            switches.append(SimSwitch(i, s.wire.bit, lo, hi, not s.wire.inverted, **place))
    pitch = tuple(SIM_INDEX_PITCH if simulated and any(h.axis == i and h.use_index for h in homing) else 0.0
                  for i in range(len(worker_drives(machine))))
    wheel = wiring.handwheel
    spec = None if wheel.terminal is None else HandwheelSpec(wiring.terminal_index(wheel.terminal),
                                                             max_counts_per_cycle=wheel.max_counts_per_cycle)
    return WorkerIo(tuple(t.spec() for t in wiring.terminals), tuple(watches), tuple(homing), tuple(switches),
                    tuple(rest), pitch if any(pitch) else (), spec, gantry)


def _switch_offset(h: AxisHoming | None, homing_method: str) -> float:
    """How much further along the axis a gantry's second home switch is than its first."""
    return h.second_offset - h.offset if h is not None and homing_method == "switches" else 0.0


def _sim_range(name: str, lo: float, hi: float,
               homing: AxisHoming | None) -> tuple[float | None, float | None]:
    """Where a simulated switch is closed, in the drive's own frame (the simulated machine's
    true machine coordinates): limits just beyond the soft limits, the home switch from its
    offset on in the search direction."""
    if not (math.isfinite(lo) and math.isfinite(hi)):
        return None, None
    if name == "limit_pos":
        return hi + SIM_LIMIT_MARGIN, _FAR
    if name == "limit_neg":
        return -_FAR, lo - SIM_LIMIT_MARGIN
    if name == "home" and homing is not None:
        if homing.search_vel > 0:
            return homing.offset, _FAR
        return -_FAR, homing.offset
    return None, None
