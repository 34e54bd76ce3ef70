"""The machine configuration: one TOML file, read strictly, written atomically.

Full configuration = the planner's ``MachineSpec`` (axes, path limits, planner settings, work
offsets; read by ``planner.core.machine.machine_from_dict``) + ``[homing]`` + ``[bus]`` with
``[[bus.drives]]`` + ``[controller]`` (jog, streaming lead, override budget, spindle).

Writing: the new text goes to a temporary file in the same directory (flushed and fsync'ed),
the current file - if it is itself valid - is copied to ``<file>.bak`` (also by temp + rename),
then ``os.replace`` puts the new file in place. The file name therefore always names either
the old or the new complete file, never a partial one.

The writer ends the file with an end marker line: a file that starts with the writer's header
but lacks the marker was cut short (e.g. a copy or a non-atomic editor interrupted) and is
reported as damaged even when what is left happens to parse.

Reading: a missing, damaged (truncated, not TOML) or invalid file raises ``ConfigError`` with
a message naming the file, the key and the value, and the backup path when a valid backup
exists. Nothing ever falls back silently to defaults; ``recover_config`` restores the backup
explicitly (keeping the damaged file as ``<file>.damaged``).
"""

from __future__ import annotations

import math
import os
import tomllib
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import tomlkit
import tomlkit.exceptions
import tomlkit.items

from app.machine.compensation import compensation_of
from app.machine.errors import ConfigError
from app.machine.spindle_settings import SpindleDriveSettings, spindle_lines
from app.machine.wiring import (
    Direction,
    MachineWiring,
    analog_place,
    handwheel_lines,
    homing_lines,
    signal_lines,
    terminal_lines,
    wiring_from_valid,
    worker_drives,
)
from ethercat.drive_setup import drive_table_problem
from opcua_server.settings import IDENTIFICATION_KEYS, OpcUaSettings
from planner.core.errors import PlannerError
from planner.core.files import write_output, write_text
from planner.core.machine import WORK_OFFSET_NAMES, MachineSpec, io_place, machine_from_valid
from planner.core.reading import CONFIGURATION, parse_toml, read_text
from planner.core.rules import drive_tables
from planner.core.schema import END_MARK, HEADER, Locator, check_complete, validate
from resources import SUBROUTINES, shipped_machine

if TYPE_CHECKING:
    from ethercat.drive_setup import DriveSetup
    from ethercat.worker import CompSpec

__all__ = [
    "BusSettings",
    "ControllerSettings",
    "DriveIdentity",
    "HomingSettings",
    "MachineConfig",
    "ProbeSettings",
    "ToolChangeSettings",
    "probe_overtravel_mm",
    "tool_measure_call",
    "config_from_dict",
    "config_to_toml",
    "load_config",
    "recover_config",
    "save_config",
]



@dataclass(frozen=True, slots=True)
class HomingSettings:
    required: bool = True  # programs may not start before every axis is homed
    method: str = "set_here"  # "set_here" | "drive" (CiA 402 homing mode 6)
    drive_method: int = 35  # 0x6098 homing method for "drive"
    timeout_s: float = 60.0
    absolute_encoders: bool = False  # positions survive a power cut: homed flags are kept after one


@dataclass(frozen=True, slots=True)
class StartupSdoSetting:
    """One ``[[bus.drives.sdo]]``: written in PRE-OP before the process data is mapped."""

    index: int
    subindex: int
    value: int
    size: int


@dataclass(frozen=True, slots=True)
class DriveIdentity:
    """One ``[[bus.drives]]``: the identity a slave must have and how it is brought up
    (mapping policy and entries, complete access, distributed clocks, start-up SDOs)."""

    position: int
    vendor_id: int = 0
    product_code: int = 0
    mapping: str = "adapt"                 # "adapt" | "write" | "keep"
    rx_pdo: int = 0x1600
    rx: tuple[str, ...] = ()               # "0x6040:0:16" entries; empty: the default mapping
    tx_pdo: int = 0x1A00
    tx: tuple[str, ...] = ()
    complete_access: str = "auto"          # "auto" | "on" | "off"
    dc: bool = True
    sync0_shift_ns: int = 0
    sync_mode: int | None = None           # 0x1C32:1, written when set
    watchdog_ms: float | None = None       # SM watchdog (0x0420), written when set
    sdos: tuple[StartupSdoSetting, ...] = ()

    def setup(self) -> DriveSetup:
        """The ``ethercat`` package's start-up settings of this drive."""
        from ethercat.drive_setup import DriveSetup, MappingPolicy, StartupSdo
        from ethercat.pdo import PdoMapping, is_velocity, parse_entry

        mapping = None
        if self.rx or self.tx:
            rx = tuple(parse_entry(e) for e in self.rx)
            mapping = PdoMapping(rx, tuple(parse_entry(e) for e in self.tx), self.rx_pdo, self.tx_pdo,
                                 velocity=is_velocity(rx))
        ca = {"auto": None, "on": True, "off": False}[self.complete_access]
        return DriveSetup(mapping=mapping, policy=MappingPolicy(self.mapping),
                          startup_sdos=tuple(StartupSdo(x.index, x.subindex, x.value, x.size)
                                             for x in self.sdos),
                          dc=self.dc, sync0_shift_ns=self.sync0_shift_ns, sync_mode=self.sync_mode,
                          complete_access=ca, watchdog_ms=self.watchdog_ms)


@dataclass(frozen=True, slots=True)
class BusSettings:
    kind: str = "sim"  # "sim" | "soem"
    adapter: str = ""  # network interface for "soem"
    wkc_error_limit: int = 3
    drives: tuple[DriveIdentity, ...] = ()


DEFAULT_LEAD_S = 0.5


@dataclass(frozen=True, slots=True)
class ProbeSettings:
    """The probe input G38.2-G38.5 watch: bit ``bit`` of the digital inputs (0x60FD) of the
    drive of axis index ``drive`` (None: the machine has no probe, and programs that probe are
    refused), reading ``touching_level`` while the stylus touches. With simulated drives the
    stylus touches when axis ``sim_axis`` is at or below machine coordinate ``sim_surface_mm``
    (None: never)."""

    drive: int | None = None
    bit: int = 16
    touching_level: int = 1
    # G38.x faster than this is refused: past the contact the stylus travels on for the
    # reaction and the jerk-limited stop, v (10 ms + sqrt(v / J)) (1 mm at 1000 mm/min and
    # 10,000 mm/s^3), which it must allow
    max_feed_mm_min: float = 1000.0
    # a tool setter wired to the probe input (all three, or none): machine X, Y of its centre and
    # the machine Z at which the spindle's gauge line (a tool of length 0) would touch it
    setter_x_mm: float | None = None
    setter_y_mm: float | None = None
    setter_z_mm: float | None = None
    sim_axis: str = "Z"
    sim_surface_mm: float | None = None
    # the probing wizards' defaults (the probe's tool, search distance, clearance, feeds, the
    # back-off between the fast and the slow probe)
    tool: int | None = None
    search_mm: float = 10.0
    clearance_mm: float = 5.0
    fast_feed_mm_min: float = 300.0
    slow_feed_mm_min: float = 30.0
    retract_mm: float = 1.0

    @property
    def has_setter(self) -> bool:
        return self.drive is not None and None not in (self.setter_x_mm, self.setter_y_mm, self.setter_z_mm)

    def probe_refusal(self, tool_in_spindle: int) -> str:
        """Why a probing move (a wizard's, or G38.x typed in MDI) may not run with this tool in
        the spindle ("" when it is the probe): only the tool ``[probe] tool`` names is a probe; a
        cutter would feed into whatever is below it until the end of the search."""
        if self.tool is None:
            return ("no probe is named: set [probe] tool to the probe's number in the tool table "
                    "(only the probe may make probing moves)")
        if tool_in_spindle == 0:
            return (f"no tool is in the spindle, not the probe T{self.tool}: put the probe in and say so "
                    f"(In the spindle, or M61 Q{self.tool})")
        if tool_in_spindle != self.tool:
            return (f"T{tool_in_spindle} is in the spindle, not the probe T{self.tool}: a probing move "
                    "would feed it into the part; put the probe in and say so (In the spindle, or "
                    f"M61 Q{self.tool})")
        return ""


@dataclass(frozen=True, slots=True)
class ToolChangeSettings:
    """M6 with the new tool measured on the tool setter once the operator has put it in
    (``measure``); a length differing from the table's by more than ``broken_tolerance_mm``
    stops the program with an alarm, the table unchanged (0: no check)."""

    measure: bool = False
    broken_tolerance_mm: float = 0.0


def probe_overtravel_mm(feed_mm_min: float, jerk_mm_s3: float, reaction_s: float = 0.015) -> float:
    """How far the stylus travels past the contact at ``feed_mm_min``: the feed for the reaction
    (the feeder sees the latch, the stop is spliced a few cycles ahead of the drives), then the
    jerk-limited stop along the path, v sqrt(v / J)."""
    v = feed_mm_min / 60.0
    return v * (reaction_s + math.sqrt(v / jerk_mm_s3))


#: the shipped subroutine that measures a tool after M6 (resources/subroutines)
TOOL_MEASURE = "tool_measure"


def tool_measure_call(machine: MachineSpec, probe: ProbeSettings, controller: ControllerSettings,
                      toolchange: ToolChangeSettings) -> str:
    """The O-word call M6 runs after a tool change when ``toolchange.measure`` (else ""): the
    setter's place, the clearance height, the probe feed, the back-off between the two
    probes (past the first contact's overtravel), the tolerance and the lowest Z, as
    resources/subroutines/tool_measure.ngc takes them."""
    if not toolchange.measure or not probe.has_setter or "Z" not in machine.axis_names:
        return ""
    assert probe.setter_x_mm is not None and probe.setter_y_mm is not None and probe.setter_z_mm is not None
    z_axis = machine.axes[machine.axis_index("Z")]
    clear = z_axis.max_pos if controller.restart_clearance_mm is None else controller.restart_clearance_mm
    fast = probe.max_feed_mm_min
    back_off = max(2.0, 2.0 * probe_overtravel_mm(fast, machine.limits.j_max_mm_s3) + 1.0)
    bottom = max(probe.setter_z_mm - 1.0, z_axis.min_pos)
    args = (probe.setter_x_mm, probe.setter_y_mm, probe.setter_z_mm, clear, fast, back_off,
            toolchange.broken_tolerance_mm, bottom)
    return f"o<{TOOL_MEASURE}> call " + " ".join(f"[{v:.6g}]" for v in args)


@dataclass(frozen=True, slots=True)
class ControllerSettings:
    """Controller tuning. The override budget (see ``app.machine.timescale``): the program is
    planned with ``(1 - accel_reserve)`` of every acceleration limit and ``(1 - jerk_reserve)``
    of every jerk limit; the rest is kept for changing the time scale (override, hold)."""

    jog_speed_mm_s: float = 10.0  # continuous jog speed at 100 % (deg/s for rotary axes)
    # set-points queued in the worker ahead of time. A feed hold, stop or override change does
    # not wait for them: the controller replaces the queue from a few cycles ahead of the
    # drives (``app.machine.feeder``, ~5 ms in simulated time, ~10-13 ms in real time), so the
    # lead only buys safety against GUI stalls. The feeder thread shares the GIL (and a core)
    # with the GUI; measured with the panel (demo, --screenshot, 1280x800 and 1920x1080, 2 busy
    # cores): feeder wake-up gaps p99 6-20 ms, max 56-265 ms; lead 0.1 s underran in 3 of 4
    # runs, 0.25 s in 1 of 4, 0.3 s in 0 of 3 (least buffer left 95 ms); with splicing, 0.3 s
    # left 135-281 ms, 0.5 s 364-469 ms (0 underruns in 5 + 5 runs). Default 0.5 s.
    lead_s: float = DEFAULT_LEAD_S
    accel_reserve: float = 0.15
    jerk_reserve: float = 0.3
    spindle_max_rpm: float = 24000.0
    spindle_drive: int = 0  # index of the drive whose digital outputs switch the spindle
    position_tolerance: float = 0.01  # mm|deg: persisted vs reported position to keep homed
    # wait after the spindle starts, reverses or speeds up before the next move (the spindle
    # must cut at speed; the simulated and CSP drives report no at-speed signal)
    spindle_spinup_s: float = 2.0
    # machine Z a restart (run from line, resume after a stop) retracts to before it moves
    # sideways; None: the top of the Z travel
    restart_clearance_mm: float | None = None


@dataclass(frozen=True)
class MachineConfig:
    machine: MachineSpec
    homing: HomingSettings = field(default_factory=HomingSettings)
    bus: BusSettings = field(default_factory=BusSettings)
    controller: ControllerSettings = field(default_factory=ControllerSettings)
    probe: ProbeSettings = field(default_factory=ProbeSettings)
    opcua: OpcUaSettings = field(default_factory=OpcUaSettings)
    path: str = ""  # file it was read from ("" if built in memory)
    toolchange: ToolChangeSettings = field(default_factory=ToolChangeSettings)
    # terminals, named signals, homing to switches, interlocks (``app.machine.wiring``)
    wiring: MachineWiring = field(default_factory=MachineWiring)
    # the compensated axes' corrections, read with the file (``app.machine.compensation``)
    compensation: tuple[CompSpec, ...] = ()
    # the spindle on its own drive (``[spindle]``; its drive None: the output bits)
    spindle: SpindleDriveSettings = field(default_factory=SpindleDriveSettings)

    def __post_init__(self) -> None:
        # what the interpreter takes from the panel's settings: the shipped subroutines' folder
        # and the measuring call after M6, derived here so every configuration made (read,
        # edited, replaced) has them as its settings say
        machine = replace(self.machine, shipped_subroutine_dir=str(SUBROUTINES),
                          after_tool_change=tool_measure_call(self.machine, self.probe, self.controller,
                                                              self.toolchange))
        if machine != self.machine:
            object.__setattr__(self, "machine", machine)

    @property
    def axes(self) -> tuple[str, ...]:
        return self.machine.axis_names

    @property
    def drives(self) -> tuple[tuple[int, str], ...]:
        """The 1 ms loop's drives in its order, (slave position, name): the axes', then each
        gantry's second drive (``<axis>2``)."""
        return worker_drives(self.machine)

    @staticmethod
    def default() -> MachineConfig:
        """The shipped 3-axis XYZ mill (resources/machines/xyz_mill.toml)."""
        return load_config(shipped_machine("xyz_mill"))


# ------------------------------------------------------------------------------ reading
def config_from_dict(data: dict[str, Any], where: str = "<config>", text: str | None = None,
                     base: str | os.PathLike[str] | None = None) -> MachineConfig:
    """Validate a parsed configuration against the one schema (``planner.core.schema``, strict:
    unknown keys, wrong types and values out of range are errors naming the file, the line
    when ``text`` is given, the key and the value) and build it. ``base``: the folder relative
    file names (a ``comp_file``) are in; the folder of ``where`` when it is a file."""
    loc = Locator(where, text)
    if base is None and not where.startswith("<"):
        base = os.path.dirname(os.path.abspath(where))
    try:
        valid = validate(data, loc)
        machine = machine_from_valid(valid, loc, drive_tables(drive_table_problem))
        compensation = compensation_of(machine, loc, base)
    except PlannerError as exc:
        raise ConfigError(str(exc), where) from None
    h = valid["homing"]
    homing = HomingSettings(required=h["required"], method=h["method"], drive_method=h["drive_method"],
                            timeout_s=h["timeout_s"], absolute_encoders=h["absolute_encoders"])
    b, c = valid["bus"], valid["controller"]
    drives = tuple(_drive(d) for d in b["drives"])
    bus = BusSettings(kind=b["kind"], adapter=b["adapter"], wkc_error_limit=b["wkc_error_limit"],
                      drives=drives)
    controller, probe = ControllerSettings(**c), ProbeSettings(**valid["probe"])
    spindle = SpindleDriveSettings.from_valid(valid["spindle"])
    try:
        wiring = wiring_from_valid(valid, machine, loc, homing.method,
                                   _reserved_bits(machine, controller, probe))
        taken = {a.drive_position: "an axis' drive" for a in machine.axes}
        taken.update({a.gantry_drive: f"axis {a.name}'s second drive" for a in machine.axes
                      if a.gantry_drive is not None})
        taken.update({t.position: f"a {t.type}" for t in wiring.terminals})
        if spindle.drive in taken:
            raise loc.fail(("spindle", "drive"), f"slave {spindle.drive} is {taken[spindle.drive]}: the "
                           "spindle's drive needs a slave position of its own")
        if spindle.analog_out:
            if spindle.drive is not None:
                raise loc.fail(("spindle", "analog_out"), f"the spindle is on its own drive (slave "
                               f"{spindle.drive}), which takes its speed: an analog output is for a VFD "
                               "run by the output bits; one or the other")
            try:
                analog_place(wiring, spindle.analog_out)
            except ValueError as exc:
                raise loc.fail(("spindle", "analog_out"), str(exc)) from None
        gantry = next((i for i, a in enumerate(machine.axes) if a.gantry_drive is not None), None)
        if gantry is not None and homing.method == "drive":
            raise loc.fail(("axes", gantry, "gantry_drive"), "a gantry's two drives home together and square "
                           "on their own switches: homing.method \"switches\" (or \"set_here\"), not "
                           "\"drive\", which homes one drive at a time")
    except PlannerError as exc:
        raise ConfigError(str(exc), where) from None
    return MachineConfig(machine=machine, homing=homing, bus=bus, controller=controller, probe=probe,
                         toolchange=ToolChangeSettings(**valid["toolchange"]),
                         opcua=OpcUaSettings.from_valid(valid["opcua"]), path=where, wiring=wiring,
                         compensation=compensation, spindle=spindle)


def _reserved_bits(machine: MachineSpec, controller: ControllerSettings, probe: ProbeSettings
                   ) -> list[tuple[str, Direction, int, int]]:
    """The drives' bits the program's inputs and outputs, the probe and the spindle use (no
    signal may take them): (what, direction, slave position, bit)."""
    slave = [a.drive_position for a in machine.axes]
    out: list[tuple[str, Direction, int, int]] = []
    for table, direction, bits in (("outputs", Direction.OUT, machine.output_bits),
                                   ("inputs", Direction.IN, machine.input_bits)):
        for number, (drive, bit, _name) in bits.items():
            kind, where = io_place(drive)
            position = where if kind == "slave" else slave[where] if where < len(slave) else -1
            if position >= 0:
                out.append((f"[[{table}]] number {number}", direction, position, bit))
    if probe.drive is not None and 0 <= probe.drive < len(slave):
        out.append(("the probe ([probe] drive, bit)", Direction.IN, slave[probe.drive], probe.bit))
    if 0 <= controller.spindle_drive < len(slave):
        for bit in (0, 1):
            out.append(("the spindle's ([controller] spindle_drive)", Direction.OUT,
                        slave[controller.spindle_drive], bit))
    return out


def _parse(path: Path) -> MachineConfig:
    if not path.exists() and not path.is_symlink():
        raise ConfigError(f"{path}: machine configuration file not found", str(path))
    try:
        text = read_text(path, CONFIGURATION)
        check_complete(text, str(path))
        data = parse_toml(text, str(path))
    except PlannerError as exc:
        raise ConfigError(str(exc), str(path)) from None
    except tomllib.TOMLDecodeError as exc:
        raise ConfigError(f"{path}: damaged file, not valid TOML: {exc}", str(path)) from None
    return config_from_dict(data, str(path), text)


def backup_path(path: str | os.PathLike[str]) -> Path:
    p = Path(path)
    return p.with_name(p.name + ".bak")


def load_config(path: str | os.PathLike[str]) -> MachineConfig:
    """Read and validate; on failure ``ConfigError`` names the problem and a valid backup."""
    p = Path(path)
    try:
        return _parse(p)
    except ConfigError as exc:
        bak = backup_path(p)
        good_backup = None
        if bak.exists():
            try:
                _parse(bak)
                good_backup = str(bak)
            except ConfigError:
                good_backup = None
        raise ConfigError(str(exc), str(p), good_backup) from None


def recover_config(path: str | os.PathLike[str]) -> tuple[MachineConfig, str]:
    """Restore ``<file>.bak`` over a damaged ``<file>`` (kept as ``<file>.damaged``).

    Returns the configuration and a message saying what happened. Raises ``ConfigError``
    when there is no valid backup.
    """
    p = Path(path)
    bak = backup_path(p)
    try:
        cfg = _parse(bak)
    except ConfigError as exc:
        raise ConfigError(f"{p}: no valid backup to recover from ({exc})", str(p)) from None
    reason = ""
    try:
        _parse(p)
        return load_config(p), f"{p} is valid; nothing recovered"
    except ConfigError as exc:
        reason = str(exc)
    if p.exists():
        os.replace(p, p.with_name(p.name + ".damaged"))
    write_text(p, bak.read_text(encoding="utf-8"))
    cfg = replace(cfg, path=str(p))
    return cfg, f"{reason}; restored from {bak} (damaged file kept as {p.name}.damaged)"


# ------------------------------------------------------------------------------ writing
def _fmt(value: object) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, str):
        escaped = value.replace("\\", "\\\\").replace('"', '\\"')
        return f'"{escaped}"'
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_fmt(v) for v in value) + "]"
    raise TypeError(f"cannot write {value!r} to TOML")


def config_to_toml(config: MachineConfig) -> str:
    """The whole configuration as TOML text (round-trips through ``config_from_dict``)."""
    m = config.machine
    out = [HEADER,
           "[machine]", f"name = {_fmt(m.name)}", ""]
    for a in m.axes:
        out += ["[[axes]]", f"name = {_fmt(a.name)}", f"kind = {_fmt('rotary' if a.rotary else 'linear')}",
                f"drive_position = {a.drive_position}", f"counts_per_unit = {_fmt(float(a.counts_per_unit))}",
                f"direction = {a.direction}", f"min = {_fmt(float(a.min_pos))}",
                f"max = {_fmt(float(a.max_pos))}",
                f"v_max = {_fmt(float(a.v_max))}", f"a_max = {_fmt(float(a.a_max))}",
                f"j_max = {_fmt(float(a.j_max))}",
                f"following_error_window = {_fmt(float(a.following_error_window))}"]
        if a.backlash > 0.0:
            out.append(f"backlash = {_fmt(float(a.backlash))}")
        if a.comp_file:
            out += [f"comp_file = {_fmt(a.comp_file)}", f"comp_file_type = {a.comp_file_type}"]
        if a.compensated:
            out.append(f"comp_reserve = {_fmt(float(a.comp_reserve))}")
        if a.gantry_drive is not None:
            out += [f"gantry_drive = {a.gantry_drive}", f"gantry_direction = {a.gantry_direction}",
                    f"gantry_skew_window = {_fmt(float(a.gantry_skew_window))}"]
        out += ["wrapped = true", ""] if a.wrapped else [""]
    lim = m.limits
    out += ["[limits]", f"v_max_mm_s = {_fmt(float(lim.v_max_mm_s))}",
            f"a_max_mm_s2 = {_fmt(float(lim.a_max_mm_s2))}", f"j_max_mm_s3 = {_fmt(float(lim.j_max_mm_s3))}",
            f"rapid_mm_s = {_fmt(float(lim.rapid_mm_s))}"]
    angular = ("v_max_deg_s", "a_max_deg_s2", "j_max_deg_s3", "rapid_deg_s")
    out += [f"{key} = {_fmt(float(getattr(lim, key)))}" for key in angular
            if math.isfinite(getattr(lim, key))]
    out += ["",
            "[planner]", f"ts_s = {_fmt(float(m.planner.ts_s))}", f"mode = {_fmt(m.planner.mode)}",
            f"interpolation = {_fmt(m.planner.interpolation)}"]
    if m.planner.subroutine_dirs:
        out.append(f"subroutine_dirs = {_fmt(list(m.planner.subroutine_dirs))}")
    out.append(f"blend_tolerance_mm = {_fmt(float(m.planner.blend_tolerance_mm))}")
    if m.planner.max_program_mb != 1024.0:
        out.append(f"max_program_mb = {_fmt(float(m.planner.max_program_mb))}")
    if m.planner.corner_velocity_step_mm_s:
        out.append(f"corner_velocity_step_mm_s = {_fmt(float(m.planner.corner_velocity_step_mm_s))}")
    out += [""]
    for table, bits in (("outputs", m.output_bits), ("inputs", m.input_bits)):
        for number, (drive, bit, name) in sorted(bits.items()):
            kind, where = io_place(drive)
            out += [f"[[{table}]]", f"number = {number}", f"{kind} = {where}", f"bit = {bit}",
                    f"name = {_fmt(name)}", ""]
    for code, (action, message, output, on) in sorted(m.mcodes.items()):
        out += ["[[mcodes]]", f"code = {code}", f"action = {_fmt(action)}", f"message = {_fmt(message)}"]
        if output >= 0:
            out.append(f"output = {output}")
        out += [f"on = {_fmt(on)}", ""]
    out += ["[offsets]"]
    for name in [n for n in WORK_OFFSET_NAMES if n in m.work_offsets]:
        key = f'"{name}"' if "." in name else name         # TOML quotes a key with a dot
        out.append(f"{key} = {_fmt([float(v) for v in m.offset(name)])}")
    h = config.homing
    out += ["", "[homing]", f"required = {_fmt(h.required)}", f"method = {_fmt(h.method)}",
            f"drive_method = {h.drive_method}", f"timeout_s = {_fmt(float(h.timeout_s))}",
            f"absolute_encoders = {_fmt(h.absolute_encoders)}", ""]
    out += homing_lines(config.wiring)
    b = config.bus
    out += ["", "[bus]", f"kind = {_fmt(b.kind)}", f"adapter = {_fmt(b.adapter)}",
            f"wkc_error_limit = {b.wkc_error_limit}", ""]
    for d in b.drives:
        out += drive_lines(d)
    out += terminal_lines(config.wiring)
    out += [""] + signal_lines(config.wiring) + handwheel_lines(config.wiring)
    out += [""] + spindle_lines(config.spindle)
    c = config.controller
    out += ["", "[controller]", f"jog_speed_mm_s = {_fmt(float(c.jog_speed_mm_s))}",
            f"lead_s = {_fmt(float(c.lead_s))}", f"accel_reserve = {_fmt(float(c.accel_reserve))}",
            f"jerk_reserve = {_fmt(float(c.jerk_reserve))}",
            f"spindle_max_rpm = {_fmt(float(c.spindle_max_rpm))}", f"spindle_drive = {c.spindle_drive}",
            f"position_tolerance = {_fmt(float(c.position_tolerance))}",
            f"spindle_spinup_s = {_fmt(float(c.spindle_spinup_s))}"]
    if c.restart_clearance_mm is not None:
        out.append(f"restart_clearance_mm = {_fmt(float(c.restart_clearance_mm))}")
    p = config.probe
    out += ["", "[probe]"]
    if p.drive is not None:
        out.append(f"drive = {p.drive}")
    out += [f"bit = {p.bit}", f"touching_level = {p.touching_level}",
            f"max_feed_mm_min = {_fmt(float(p.max_feed_mm_min))}", f"sim_axis = {_fmt(p.sim_axis)}"]
    for key in ("setter_x_mm", "setter_y_mm", "setter_z_mm", "sim_surface_mm"):
        value = getattr(p, key)
        if value is not None:
            out.append(f"{key} = {_fmt(float(value))}")
    if p.tool is not None:
        out.append(f"tool = {p.tool}")
    out += [f"{key} = {_fmt(float(getattr(p, key)))}" for key in
            ("search_mm", "clearance_mm", "fast_feed_mm_min", "slow_feed_mm_min", "retract_mm")]
    t = config.toolchange
    out += ["", "[toolchange]", f"measure = {_fmt(t.measure)}",
            f"broken_tolerance_mm = {_fmt(float(t.broken_tolerance_mm))}"]
    u = config.opcua
    out += ["", "[opcua]", f"enabled = {_fmt(u.enabled)}", f"host = {_fmt(u.host)}", f"port = {u.port}",
            f"security = {_fmt([m.value for m in u.security])}", f"anonymous = {_fmt(u.anonymous)}",
            f"rate_hz = {_fmt(float(u.rate_hz))}"]
    for key in ("manufacturer", "model", "serial_number", "product_instance_uri", *IDENTIFICATION_KEYS,
                "application_uri"):
        if getattr(u, key):
            out.append(f"{key} = {_fmt(getattr(u, key))}")
    out += ["", END_MARK, ""]
    return "\n".join(out)


def render_config(config: MachineConfig, existing: str | None = None) -> str:
    """The configuration as TOML text. With the current file's text, only the values that
    changed are rewritten there: the integrator's comments, key order, number formats (hex
    identities, integers) and layout stay; keys the configuration no longer has go. A file
    that does not parse is replaced by the fresh text."""
    fresh = config_to_toml(config)
    if existing is None:
        return fresh
    try:
        doc = tomlkit.parse(existing)
    except tomlkit.exceptions.ParseError:
        return fresh
    _merge(doc, tomlkit.parse(fresh))
    text = tomlkit.dumps(doc)
    if not text.startswith(HEADER):      # written by the panel from now on: truncation is detectable
        text = HEADER + "\n" + text
    if END_MARK not in text[-200:]:
        text = text.rstrip("\n") + "\n\n" + END_MARK + "\n"
    return text


def _merge(dst: Any, src: Any) -> None:
    """Make tomlkit table `dst` hold the values of `src`, touching only what differs."""
    for key, new in src.items():
        if key not in dst:
            dst[key] = new
            continue
        old = dst[key]
        if isinstance(new, dict) and isinstance(old, dict):
            _merge(old, new)
        elif isinstance(new, tomlkit.items.AoT) and isinstance(old, tomlkit.items.AoT):
            for i, table in enumerate(new):
                if i < len(old):
                    _merge(old[i], table)
                else:
                    old.append(table)
            while len(old) > len(new):
                del old[len(old) - 1]
        elif _plain(old) != _plain(new):
            dst[key] = _plain(new)
    for key in [k for k in dst if k not in src]:
        del dst[key]


def _plain(value: Any) -> Any:
    return value.unwrap() if hasattr(value, "unwrap") else value


def _drive(d: dict[str, Any]) -> DriveIdentity:
    return DriveIdentity(
        d["position"], d["vendor_id"], d["product_code"], mapping=d["mapping"], rx_pdo=d["rx_pdo"],
        rx=tuple(d["rx"]), tx_pdo=d["tx_pdo"], tx=tuple(d["tx"]), complete_access=d["complete_access"],
        dc=d["dc"], sync0_shift_ns=d["sync0_shift_ns"], sync_mode=d["sync_mode"],
        watchdog_ms=d["watchdog_ms"],
        sdos=tuple(StartupSdoSetting(x["index"], x["subindex"], x["value"], x["size"]) for x in d["sdo"]))


def drive_lines(d: DriveIdentity) -> list[str]:
    """The ``[[bus.drives]]`` table of one drive (every key, so nothing is lost on a save)."""
    out = ["[[bus.drives]]", f"position = {d.position}", f"vendor_id = 0x{d.vendor_id:08X}",
           f"product_code = 0x{d.product_code:08X}", f"mapping = {_fmt(d.mapping)}"]
    if d.rx or d.tx:
        out += [f"rx_pdo = 0x{d.rx_pdo:04X}", "rx = [" + ", ".join(_fmt(e) for e in d.rx) + "]",
                f"tx_pdo = 0x{d.tx_pdo:04X}", "tx = [" + ", ".join(_fmt(e) for e in d.tx) + "]"]
    out += [f"complete_access = {_fmt(d.complete_access)}", f"dc = {_fmt(d.dc)}",
            f"sync0_shift_ns = {d.sync0_shift_ns}"]
    if d.sync_mode is not None:
        out.append(f"sync_mode = {d.sync_mode}")
    if d.watchdog_ms is not None:
        out.append(f"watchdog_ms = {_fmt(d.watchdog_ms)}")
    for x in d.sdos:
        out += ["[[bus.drives.sdo]]", f"index = 0x{x.index:04X}", f"subindex = {x.subindex}",
                f"value = {x.value}", f"size = {x.size}"]
    return out


def save_config(config: MachineConfig, path: str | os.PathLike[str] | None = None) -> MachineConfig:
    """Validate and write atomically; the previous valid file is kept as ``<file>.bak``.

    Returns the configuration as re-read from the written text (so what is applied is
    exactly what is on disk).
    """
    p = Path(path if path is not None else config.path)
    if not str(p):
        raise ConfigError("no file name to save the machine configuration to")
    try:
        existing: str | None = p.read_text(encoding="utf-8") if p.is_file() else None
    except (OSError, UnicodeDecodeError):
        existing = None
    text = render_config(config, existing)
    try:
        new = config_from_dict(tomllib.loads(text), str(p))
    except tomllib.TOMLDecodeError as exc:  # pragma: no cover - writer bug
        raise ConfigError(f"{p}: internal error, written TOML does not parse: {exc}") from None
    if p.exists():
        try:
            _parse(p)
            current_valid = True
        except ConfigError:
            current_valid = False
        if current_valid:
            current = p.read_bytes()
            write_output(backup_path(p), lambda fh: fh.write(current))
    write_text(p, text)
    return new
