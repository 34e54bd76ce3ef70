"""The machine configuration file, declared once: every section, key, type, range and default.

The planner reads its sections from it (``planner.core.machine``) and the controller the rest
(``app.machine.config``); both go through ``validate``, so a file is accepted or refused the
same way by ``cnc-plan``, ``cnc-run`` and the panel. Strict: an unknown section or key is an
error (with the nearest known name), a value of the wrong type is an error (an integer key
takes no 1.5, a number no "fast"), and every number has a range. Every message names the
file, the line when the text is at hand, the key and the value.
"""

from __future__ import annotations

import difflib
import math
import re
from dataclasses import dataclass, field
from typing import Any

from planner.core.errors import PlannerError

__all__ = ["END_MARK", "HEADER", "MACHINE_FILE", "REQUIRED", "SIGNAL_NAMES", "Key", "Locator", "Table",
           "check_complete", "key_lines", "validate"]


class _Required:
    def __repr__(self) -> str:
        return "REQUIRED"


REQUIRED: Any = _Required()


@dataclass(frozen=True, slots=True)
class Key:
    """One key: its type ("float", "int", "bool", "str", "floats", "strs"), default (``REQUIRED`` when
    it must be given, None when derived by the reader), inclusive range or choices."""

    name: str
    kind: str
    default: Any = REQUIRED
    lo: float | None = None
    hi: float | None = None
    choices: tuple[Any, ...] = ()


@dataclass(frozen=True, slots=True)
class Table:
    """A table (``[name]``) or an array of tables (``[[name]]``) and its keys; ``pattern``
    admits further keys by name (work offsets G54..G59)."""

    name: str
    keys: tuple[Key, ...] = ()
    array: bool = False
    required: bool = False
    tables: tuple[Table, ...] = ()
    pattern: str = ""
    pattern_key: Key | None = None
    doc: str = field(default="", compare=False)


_LIN = 1e6        # mm: positions and travel
#: the machine's named signals (``[signals]``; ``app.machine.wiring`` says what each does)
SIGNAL_NAMES = (
    "estop_chain_ok", "cycle_start", "feed_hold", "stop", "door_closed", "air_ok", "lube_ok",
    "spindle_at_speed", "coolant_flood", "coolant_mist", "lube_pump", "work_light", "spindle_enable",
    "jog_scale_x10", "jog_scale_x100",
)
#: a digital output or input: its number in a program (M62-M66 P), where it is (the axis index of
#: the drive that carries it, bit ``bit`` of its 0x60FE:1 / 0x60FD; or ``slave``: the bus position
#: of a terminal, ``bit`` its channel), a name for the operator
_IO_KEYS = (
    Key("number", "int", REQUIRED, 0, 63),
    Key("drive", "int", None, 0, 63),
    Key("slave", "int", None, 0, 65535),
    Key("bit", "int", REQUIRED, 0, 31),
    Key("name", "str", ""),
)
MACHINE_FILE = Table("", tables=(
    Table("machine", (Key("name", "str", "machine"),)),
    Table("axes", (
        Key("name", "str", choices=("X", "Y", "Z", "A", "B", "C")),
        Key("kind", "str", None, choices=("linear", "rotary")),
        Key("drive_position", "int", None, 0, 65535),
        Key("counts_per_unit", "float", 10_000.0, 1e-3, 1e9),
        Key("direction", "int", 1, choices=(1, -1)),
        Key("min", "float", REQUIRED, -_LIN, _LIN),
        Key("max", "float", REQUIRED, -_LIN, _LIN),
        # lower bounds keep planning bounded: a jerk of 1e-300 makes every move take forever
        Key("v_max", "float", REQUIRED, 1e-3, 1e5),
        Key("a_max", "float", REQUIRED, 1e-3, 1e7),
        Key("j_max", "float", REQUIRED, 1e-3, 1e10),
        Key("following_error_window", "float", 1.0, 1e-6, 1e4),
        # a rotary axis that turns without end (LinuxCNC's WRAPPED_ROTARY): absolute moves the
        # short way, the position read modulo 360, no travel limits
        Key("wrapped", "bool", False),
        # leadscrew compensation (LinuxCNC's BACKLASH, COMP_FILE and COMP_FILE_TYPE), sent to the
        # drive once the axis is homed; motion plans with (1 - comp_reserve) of v_max, a_max and
        # j_max on a compensated axis, the rest is the compensation's
        Key("backlash", "float", 0.0, 0.0, 1.0),
        Key("comp_file", "str", ""),
        Key("comp_file_type", "int", 0, choices=(0, 1)),
        Key("comp_reserve", "float", 0.1, 0.02, 0.5),
        # a gantry: the axis' second drive (its slave position), that motor's direction, and
        # the largest skew of the two sides while they move (axis units) before both stop
        Key("gantry_drive", "int", None, 0, 65535),
        Key("gantry_direction", "int", 1, choices=(1, -1)),
        Key("gantry_skew_window", "float", 0.5, 1e-6, 1e3),
    ), array=True, required=True),
    Table("limits", (
        Key("v_max_mm_s", "float", 30.0, 1e-3, 1e5),
        Key("a_max_mm_s2", "float", 1000.0, 1e-3, 1e7),
        Key("j_max_mm_s3", "float", 10_000.0, 1e-3, 1e10),
        Key("rapid_mm_s", "float", 30.0, 1e-3, 1e5),
        # moves of rotary axes alone, along their rotary distance (deg): left out, the rotary
        # axes' own limits govern (LinuxCNC's MAX_ANGULAR_VELOCITY ...)
        Key("v_max_deg_s", "float", None, 1e-3, 1e6),
        Key("a_max_deg_s2", "float", None, 1e-3, 1e8),
        Key("j_max_deg_s3", "float", None, 1e-3, 1e11),
        Key("rapid_deg_s", "float", None, 1e-3, 1e6),
    )),
    Table("planner", (
        # the cyclic worker's range: 0.1 ms to 100 ms
        Key("ts_s", "float", 0.001, 1e-4, 0.1),
        Key("mode", "str", "lookahead", choices=("lookahead", "paper")),
        Key("interpolation", "str", "exact", choices=("exact", "taylor", "classic")),
        # folders where "o<name> call" finds <name>.ngc (relative: to this file's folder)
        Key("subroutine_dirs", "strs", []),
        # G64 without P: how far (mm) a corner blend may leave the programmed corner; 0 keeps
        # the programmed path (G64 P<tol> in a program sets its own)
        Key("blend_tolerance_mm", "float", 0.0, 0.0, 10.0),
        # the largest program read (MB): a longer file, or a device that goes on, is refused
        Key("max_program_mb", "float", 1024.0, 0.001, 65536.0),
        # at a joint that is not blended (a corner in G61.1, one the blends leave), how much an
        # axis' velocity may change in one sample (mm/s or deg/s) beyond what its jerk limit
        # allows; 0: none (such joints are crossed within every axis' jerk limit: a real corner
        # is all but a stop); like Klipper's square corner velocity, the axes' acceleration
        # bounds it too
        Key("corner_velocity_step_mm_s", "float", 0.0, 0.0, 1000.0),
    )),
    # G54 ... G59.3 (a name with a dot is quoted: "G59.1" = [...])
    Table("offsets", pattern=r"G5[4-8]|G59(?:\.[123])?",
          pattern_key=Key("", "floats", REQUIRED, -_LIN, _LIN)),
    # digital outputs a program switches (M62-M65 P<number>): a bit of a drive's 0x60FE:1
    # (bits 0 and 1 of the spindle drive switch the spindle)
    Table("outputs", _IO_KEYS, array=True),
    # digital inputs a program reads or waits for (M66 P<number>): a bit of a drive's 0x60FD
    Table("inputs", _IO_KEYS, array=True),
    # user M-codes M100-M199: what each does on this machine
    Table("mcodes", (
        Key("code", "int", REQUIRED, 100, 199),
        Key("action", "str", REQUIRED, choices=("pause", "output", "ignore")),
        Key("message", "str", ""),
        Key("output", "int", None, 0, 63),
        Key("on", "bool", True),
    ), array=True),
    Table("homing", (
        Key("required", "bool", True),
        # "switches": each axis homes to its home switch ([[homing.axes]], the signal home_<axis>);
        # "drive": the drive's own CiA 402 homing; "set_here": where the axes stand is machine
        # zero (a machine without reference switches: after a power loss the control cannot
        # know where the machine is)
        Key("method", "str", "set_here", choices=("set_here", "drive", "switches")),
        Key("drive_method", "int", 35, -128, 127),
        Key("timeout_s", "float", 60.0, 0.1, 3600.0),
        # drives that keep their position through a power cut stay homed after one
        Key("absolute_encoders", "bool", False),
    ), tables=(
        # homing to a switch, per axis, as LinuxCNC's HOME_* keys (units/s, the sign of the
        # search velocity the direction to the switch; the latch velocity's sign the same:
        # off the switch and back onto it slowly, opposite: latched as it leaves the switch);
        # offset: the switch's machine coordinate; home: where the axis goes after; sequence:
        # the order (equal values home together); max_travel: the longest search (default the
        # axis' travel and a fifth); use_index: latch at the encoder's index past the switch
        Table("axes", (
            Key("axis", "str", REQUIRED, choices=("X", "Y", "Z", "A", "B", "C")),
            Key("search_vel", "float", REQUIRED, -1e5, 1e5),
            Key("latch_vel", "float", REQUIRED, -1e5, 1e5),
            Key("final_vel", "float", 0.0, 0.0, 1e5),
            Key("offset", "float", 0.0, -_LIN, _LIN),
            Key("home", "float", 0.0, -_LIN, _LIN),
            Key("sequence", "int", 0, 0, 9),
            Key("ignore_limits", "bool", False),
            Key("max_travel", "float", None, 1e-3, _LIN),
            # HOME_USE_INDEX: past the switch edge on to the encoder's index pulse (latched by
            # the drive's touch probe 1, 0x60B8-0x60BA); offset is then the index' coordinate
            Key("use_index", "bool", False),
            # a gantry's second side: its own home switch's machine coordinate (LinuxCNC's
            # HOME_OFFSET of the second joint; left out, the same as offset)
            Key("gantry_offset", "float", None, -_LIN, _LIN),
        ), array=True),
    )),
    Table("bus", (
        Key("kind", "str", "sim", choices=("sim", "soem")),
        Key("adapter", "str", ""),
        Key("wkc_error_limit", "int", 3, 1, 1000),
    ), tables=(
        Table("drives", (
            Key("position", "int", None, 0, 65535),
            Key("vendor_id", "int", 0, 0, 0xFFFF_FFFF),
            Key("product_code", "int", 0, 0, 0xFFFF_FFFF),
            # how the drive is brought up (ethercat.drive_setup): PDO mapping policy and
            # entries ("0x6040:0:16"), complete access, distributed clocks, 0x1C32:1
            Key("mapping", "str", "adapt", choices=("adapt", "write", "keep")),
            Key("rx_pdo", "int", 0x1600, 0x1600, 0x17FF),
            Key("rx", "strs", []),
            Key("tx_pdo", "int", 0x1A00, 0x1A00, 0x1BFF),
            Key("tx", "strs", []),
            Key("complete_access", "str", "auto", choices=("auto", "on", "off")),
            Key("dc", "bool", True),
            Key("sync0_shift_ns", "int", 0, -999_999_999, 999_999_999),
            Key("sync_mode", "int", None, 0, 3),
            # the process data (SM) watchdog written to 0x0420; unset: the drive's own
            Key("watchdog_ms", "float", None, 1.0, 6553.5),
        ), array=True, tables=(
            Table("sdo", (
                Key("index", "int", REQUIRED, 0, 0xFFFF),
                Key("subindex", "int", 0, 0, 255),
                Key("value", "int", REQUIRED, -(1 << 63), (1 << 64) - 1),
                Key("size", "int", REQUIRED, choices=(1, 2, 4, 8)),
            ), array=True),
        )),
        # terminals beside the drives (ethercat.terminals): slave position, type ("EK1100",
        # "EL1008", "EL2008", "EL5101", ...), a name for the operator
        Table("terminals", (
            Key("position", "int", REQUIRED, 0, 65535),
            Key("type", "str", REQUIRED),
            Key("name", "str", ""),
        ), array=True),
    )),
    # the machine's signals, each wired to a bit: "<slave>:<bit>" (the slave's bus position;
    # a terminal's channel counted from 0, a drive's bit of 0x60FD in / 0x60FE:1 out), "!" in
    # front when the bit reads 0 while the signal is true (a normally closed contact); ""
    # not wired. limit_pos_<axis>, limit_neg_<axis> and home_<axis> default to bits 1, 0 and 2
    # of the axis' drive's 0x60FD (CiA 402); limit_pos2_, limit_neg2_ and home2_<axis> are a
    # gantry's second side's, by default those bits of its second drive
    Table("signals", tuple(Key(name, "str", "") for name in SIGNAL_NAMES),
          pattern=r"(?:limit_pos2?|limit_neg2?|home2?|jog_enable)_[XYZABC]",
          pattern_key=Key("", "str", None)),
    # the handwheel (MPG): the bus position of the encoder terminal it is wired to (an EL5101 of
    # [[bus.terminals]]; unset: no handwheel), the counts of one detent (a wheel read in
    # quadrature: 4), "position" (every detent moves its step; turned faster than the axis
    # follows, it catches up within the limits) or "velocity" (counts the axis cannot follow are
    # dropped: it stops soon after the wheel), the step of one detent at x1, x10 and x100 (mm or
    # deg), and the largest change of its counter in one cycle taken as a turn (more is a jump:
    # nothing moves, the wheel stops). Its axis and step come from the panel, or from the
    # signals jog_enable_<axis>, jog_scale_x10 and jog_scale_x100 when they are wired
    Table("handwheel", (
        Key("terminal", "int", None, 0, 65535),
        Key("counts_per_detent", "int", 4, 1, 10_000),
        Key("mode", "str", "position", choices=("position", "velocity")),
        Key("steps", "floats", [0.001, 0.01, 0.1], 1e-6, 100.0),
        Key("max_counts_per_cycle", "int", 256, 1, 32_767),
    )),
    # the spindle on its own CiA 402 drive (left out: the output bits of [controller]
    # spindle_drive): its slave position, velocity mode (9 cyclic synchronous, 3 profile), the
    # drive's velocity units per rpm, the ramp (rpm/s), at speed within at_speed_pct of the
    # speed commanded, and below that band for speed_loss_s while turning at speed: a hold
    Table("spindle", (
        Key("drive", "int", None, 0, 65535),
        Key("mode", "int", 9, choices=(9, 3)),
        Key("velocity_per_rpm", "float", 10_000.0 / 60.0, 1e-6, 1e8),
        Key("accel_rpm_s", "float", 2000.0, 1.0, 1e6),
        Key("at_speed_pct", "float", 5.0, 0.1, 50.0),
        Key("speed_loss_s", "float", 0.5, 0.01, 60.0),
        Key("vendor_id", "int", 0, 0, 0xFFFF_FFFF),
        Key("product_code", "int", 0, 0, 0xFFFF_FFFF),
        # a VFD instead of a drive: its speed from an analog output terminal's channel
        # ("<slave>:<channel>" of an EL4xxx, 0-10 V), 10 V at analog_rpm_at_10v (default
        # [controller] spindle_max_rpm); its run and direction from the spindle's output bits
        Key("analog_out", "str", ""),
        Key("analog_rpm_at_10v", "float", None, 1.0, 1e6),
    )),
    # what the machine's interlocks do: air or lube pressure lost ("stop": the motion stops
    # along its path, an alarm; "warning": an alarm only); the jog speed allowed with the
    # door open (mm/s; 0: no jog with the door open)
    Table("interlocks", (
        Key("air_lost", "str", "stop", choices=("stop", "warning")),
        Key("lube_lost", "str", "warning", choices=("stop", "warning")),
        Key("door_open_jog_mm_s", "float", 0.0, 0.0, 1e4),
    )),
    # the probe G38.2-G38.5 read: a bit of the digital inputs (0x60FD) of an axis' drive, and
    # its level while the stylus touches; with simulated drives, a surface it touches
    Table("probe", (
        Key("drive", "int", None, 0, 63),
        Key("bit", "int", 16, 0, 31),
        Key("touching_level", "int", 1, choices=(0, 1)),
        # the fastest probe move: the stylus travels on past the contact while the motion stops
        Key("max_feed_mm_min", "float", 1000.0, 1.0, 100_000.0),
        # a tool setter under the probe input: machine X and Y of its centre, and the machine
        # Z at which the spindle's gauge line (a tool of length 0) would touch it
        Key("setter_x_mm", "float", None, -_LIN, _LIN),
        Key("setter_y_mm", "float", None, -_LIN, _LIN),
        Key("setter_z_mm", "float", None, -_LIN, _LIN),
        Key("sim_axis", "str", "Z", choices=("X", "Y", "Z", "A", "B", "C")),
        Key("sim_surface_mm", "float", None, -_LIN, _LIN),
        # the probing wizards' defaults: the probe's tool number (its length and tip diameter
        # from the tool table), how far a probe move searches past where the surface should be,
        # the distance kept from the part when moving around it, the fast and slow probe feeds
        # and how far back the stylus goes between them
        Key("tool", "int", None, 1, 99999),
        Key("search_mm", "float", 10.0, 0.1, 1000.0),
        Key("clearance_mm", "float", 5.0, 0.1, 1000.0),
        Key("fast_feed_mm_min", "float", 300.0, 1.0, 100_000.0),
        Key("slow_feed_mm_min", "float", 30.0, 0.1, 100_000.0),
        Key("retract_mm", "float", 1.0, 0.01, 100.0),
    )),
    # M6 with the tool measured on the setter ([probe] setter_*) after the operator's change;
    # a length that differs from the table's by more than broken_tolerance_mm stops the program
    # (0: no check)
    Table("toolchange", (
        Key("measure", "bool", False),
        Key("broken_tolerance_mm", "float", 0.0, 0.0, 1000.0),
    )),
    Table("controller", (
        Key("jog_speed_mm_s", "float", 10.0, 1e-3, 1e4),
        Key("lead_s", "float", 0.5, 0.01, 1.0),
        Key("accel_reserve", "float", 0.15, 0.01, 0.5),
        Key("jerk_reserve", "float", 0.3, 0.01, 0.7),
        Key("spindle_max_rpm", "float", 24000.0, 1.0, 1e6),
        Key("spindle_drive", "int", 0, 0, 63),
        Key("position_tolerance", "float", 0.01, 0.0, 100.0),
        Key("spindle_spinup_s", "float", 2.0, 0.0, 120.0),
        Key("restart_clearance_mm", "float", None, -1e6, 1e6),
    )),
    # the OPC UA server (OPC 40501 Machine Tools): read-only monitoring for a shop's clients.
    # Security "None" is only what the file asks for by name; identification fills the
    # MachineTool's Identification ("" takes the machine name and the host; a year or month of
    # construction of 0 is not given); application_uri "" is made from the host and the
    # installation (its state folder)
    Table("opcua", (
        Key("enabled", "bool", False),
        Key("host", "str", "0.0.0.0"),
        Key("port", "int", 4840, 1, 65535),
        Key("security", "strs", ("Basic256Sha256_SignAndEncrypt",),
            choices=("Basic256Sha256_SignAndEncrypt", "Basic256Sha256_Sign", "None")),
        Key("anonymous", "bool", False),
        Key("rate_hz", "float", 10.0, 0.1, 50.0),
        Key("manufacturer", "str", ""),
        Key("model", "str", ""),
        Key("serial_number", "str", ""),
        Key("product_instance_uri", "str", ""),
        Key("product_code", "str", ""),
        Key("year_of_construction", "int", 0, 0, 9999),
        Key("month_of_construction", "int", 0, 0, 12),
        Key("location", "str", ""),
        Key("manufacturer_uri", "str", ""),
        Key("hardware_revision", "str", ""),
        Key("device_class", "str", ""),
        Key("asset_id", "str", ""),
        Key("application_uri", "str", ""),
    )),
))

#: first and last line of a file the panel wrote: a file that starts with the header but has
#: no end mark was cut short (a copy or a non-atomic editor interrupted) even if what is left
#: parses, and every reader refuses it
HEADER = "# Machine configuration (written by the CNC panel). Units: mm or deg, s."
END_MARK = "# end of machine configuration"


def table_keys(name: str) -> tuple[Key, ...]:
    """The keys of the machine file's table ``name`` (its ranges, for the command line's
    overrides of the same values)."""
    return next(t.keys for t in MACHINE_FILE.tables if t.name == name)


def check_complete(text: str, where: str) -> None:
    """Refuse a panel-written file whose end mark is missing (truncated)."""
    if text.startswith(HEADER) and END_MARK not in text[-200:]:
        raise PlannerError(f"{where}: damaged file, truncated (the end mark is missing)")


_HEADER_RE = re.compile(r"^\s*(\[\[?)\s*([A-Za-z0-9_.-]+)\s*\]\]?")
# "a = 1", a dotted key's first part, or a quoted key ("G59.1" = ...)
_KEY_RE = re.compile(r'^\s*(?:"([A-Za-z0-9_.-]+)"|([A-Za-z0-9_-]+))\s*[=.]')


def key_lines(text: str) -> dict[tuple[str | int, ...], int]:
    """Line numbers (1-based) of the tables and keys of a TOML text, by path: ("limits",),
    ("limits", "v_max_mm_s"), ("axes", 1, "v_max"), ("bus", "drives", 0, "position").
    Plain headers and ``key = value`` lines only; anything else has no line."""
    lines: dict[tuple[str | int, ...], int] = {}
    counters: dict[str, int] = {}
    current: tuple[str | int, ...] = ()
    for number, line in enumerate(text.splitlines(), start=1):
        m = _HEADER_RE.match(line)
        if m:
            parts = m.group(2).split(".")
            path: list[str | int] = []
            for depth, part in enumerate(parts):
                path.append(part)
                dotted = ".".join(parts[:depth + 1])
                last = depth == len(parts) - 1
                if m.group(1) == "[[" and last:
                    counters[dotted] = counters.get(dotted, -1) + 1
                    path.append(counters[dotted])
                    for inner in [k for k in counters if k.startswith(dotted + ".")]:
                        del counters[inner]        # a new element starts its own sub-arrays
                elif dotted in counters:         # inside the latest element of an array
                    path.append(counters[dotted])
            current = tuple(path)
            lines.setdefault(current, number)
            if m.group(1) == "[[":
                lines.setdefault(current[:-1], number)    # the array itself: its first element
            continue
        k = _KEY_RE.match(line)
        if k:
            lines.setdefault((*current, k.group(1) or k.group(2)), number)
    return lines


class Locator:
    """Turns a key's path into ``file:line: key.path: message`` errors."""

    def __init__(self, where: str, text: str | None) -> None:
        self.where = where
        self.lines = key_lines(text) if text else {}

    def fail(self, path: tuple[str | int, ...], message: str) -> PlannerError:
        line = 0
        for n in range(len(path), 0, -1):        # the key's line, else its table's
            line = self.lines.get(path[:n], 0)
            if line:
                break
        loc = f"{self.where}:{line}" if line else self.where
        return PlannerError(f"{loc}: {_dotted(path)}: {message}")


def _dotted(path: tuple[str | int, ...]) -> str:
    out = ""
    for p in path:
        out += f"[{p}]" if isinstance(p, int) else (f".{p}" if out else p)
    return out or "(top level)"


def _suggest(name: str, known: list[str]) -> str:
    close = difflib.get_close_matches(name, known, n=1, cutoff=0.6)
    return f" (did you mean '{close[0]}'?)" if close else f" (known: {', '.join(known)})"


def _check_value(ctx: Locator, path: tuple[str | int, ...], key: Key, value: Any) -> Any:
    kind = key.kind
    if kind == "bool":
        if not isinstance(value, bool):
            raise ctx.fail(path, f"must be true or false, got {value!r}")
        return value
    if kind == "str":
        if not isinstance(value, str):
            raise ctx.fail(path, f"must be a string, got {value!r}")
        if key.choices and value not in key.choices:
            raise ctx.fail(path, f"must be one of {', '.join(map(repr, key.choices))}, got {value!r}")
        return value
    if kind == "strs":
        if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
            raise ctx.fail(path, f"must be a list of strings, got {value!r}")
        for i, item in enumerate(value):
            if key.choices and item not in key.choices:
                raise ctx.fail((*path, i),
                               f"must be one of {', '.join(map(repr, key.choices))}, got {item!r}")
        if key.choices and not value:
            raise ctx.fail(path, f"needs at least one of {', '.join(map(repr, key.choices))}")
        return list(value)
    if kind == "floats":
        if not isinstance(value, list):
            raise ctx.fail(path, f"must be a list of numbers, got {value!r}")
        return [_number(ctx, (*path, i), key, v, float) for i, v in enumerate(value)]
    return _number(ctx, path, key, value, int if kind == "int" else float)


def _number(ctx: Locator, path: tuple[str | int, ...], key: Key, value: Any, kind: type) -> Any:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        what = "a whole number" if kind is int else "a number"
        raise ctx.fail(path, f"must be {what}, got {value!r}")
    if kind is int and not isinstance(value, int):
        raise ctx.fail(path, f"must be a whole number, got {value!r}")
    if not math.isfinite(value):
        raise ctx.fail(path, f"must be a finite number, got {value!r}")
    if key.choices and value not in key.choices:
        raise ctx.fail(path, f"must be one of {', '.join(map(str, key.choices))}, got {value!r}")
    if key.lo is not None and value < key.lo or key.hi is not None and value > key.hi:
        raise ctx.fail(path, f"must be within [{key.lo:g}, {key.hi:g}], got {value!r}")
    return kind(value)


def _table(ctx: Locator, spec: Table, data: Any, path: tuple[str | int, ...]) -> dict[str, Any]:
    if not isinstance(data, dict):
        raise ctx.fail(path, f"must be a table ([{_dotted(path)}]), got {data!r}")
    keys = {k.name: k for k in spec.keys}
    subs = {t.name: t for t in spec.tables}
    out: dict[str, Any] = {}
    for name, value in data.items():
        if name in keys:
            out[name] = _check_value(ctx, (*path, name), keys[name], value)
        elif name in subs:
            out[name] = _section(ctx, subs[name], value, (*path, name))
        elif spec.pattern and spec.pattern_key is not None and re.fullmatch(spec.pattern, name):
            out[name] = _check_value(ctx, (*path, name), spec.pattern_key, value)
        else:
            known = sorted([*keys, *subs])
            what = "section" if path == () else "key"
            if spec.pattern:
                raise ctx.fail((*path, name), f"unknown {what} (allowed: {spec.pattern})")
            raise ctx.fail((*path, name), f"unknown {what}{_suggest(name, known)}")
    for name, key in keys.items():
        if name not in out:
            if key.default is REQUIRED:
                raise ctx.fail(path, f"missing '{name}'")
            out[name] = key.default
    for name, sub in subs.items():
        if name not in out:
            if sub.required:
                raise ctx.fail(path, f"at least one [[{_dotted((*path, name))}]] table is required")
            out[name] = [] if sub.array else _table(ctx, sub, {}, (*path, name))
    return out


def _section(ctx: Locator, spec: Table, value: Any, path: tuple[str | int, ...]) -> Any:
    if spec.array:
        if not isinstance(value, list) or not all(isinstance(v, dict) for v in value):
            raise ctx.fail(path, f"must be [[{_dotted(path)}]] tables, got {value!r}")
        if spec.required and not value:
            raise ctx.fail(path, f"at least one [[{_dotted(path)}]] table is required")
        return [_table(ctx, spec, v, (*path, i)) for i, v in enumerate(value)]
    return _table(ctx, spec, value, path)


def validate(data: dict[str, Any], where: str | Locator = "<config>", text: str | None = None,
             schema: Table = MACHINE_FILE) -> dict[str, Any]:
    """The configuration checked against the schema, with defaults filled in (derived keys
    stay None). ``text``: the file's text, for line numbers in the messages."""
    loc = where if isinstance(where, Locator) else Locator(where, text)
    return _table(loc, schema, data, ())
