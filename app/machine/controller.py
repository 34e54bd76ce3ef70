"""MachineController: what a CNC control does between the operator's buttons and the drives.

The one public face of ``app.machine`` (the panel builds against ``app.machine.api.MachineApi``;
QtCore only, no widgets: it runs headless). It builds the parts, hands each only the narrow
interfaces it uses (``app.machine.ports``), relays what they tell the panel to its Qt signals,
and declares its commands and read-only properties as its parts' own (``infra.forward``).

Threads. The controller lives in the GUI thread. A feeder thread (no Qt) turns the plan into
set-points and keeps the worker's buffer filled ``lead_s`` ahead; a 30 Hz QTimer reads the
worker's snapshot and tells the panel (never per control cycle).

Commands never raise for an operator-level refusal: they return a ``CommandResult`` (truthy
when accepted, ``reason`` otherwise) and emit ``commandRefused(action, reason)``.

States (``MachineState``) and the legal transitions (``TRANSITIONS``)::

    DISCONNECTED -> IDLE (connect_bus) | ESTOP
    IDLE    -> RUNNING (cycle_start, mdi, jog, run_from_line) | HOMING | ALARM | ESTOP | DISCONNECTED
    HOMING  -> IDLE | ALARM | ESTOP
    RUNNING -> HOLD (feed_hold, single block, M00/M01) | IDLE (end, stop) | ALARM | ESTOP
    HOLD    -> RUNNING (resume / cycle_start) | IDLE (stop, reset) | ALARM | ESTOP
    ALARM   -> IDLE (reset, alarms acknowledged) | ESTOP
    ESTOP   -> IDLE (estop_release) | DISCONNECTED

How motion is made. Every motion (program, MDI block, jog, approach move) is parsed, checked
against the soft limits on its whole path (arcs by their exact extremes) and planned with the
override budget (``app.machine.motion.timescale``: acceleration and jerk limits reduced to 85 %
and 70 %); a ``TimeScaledExecutor`` then runs the plan at a time scale sigma that carries feed
override (0-200 %), rapid override (0-100 %) and feed hold without leaving the path or
exceeding a limit; a hold or stop while moving is the time-optimal jerk-limited stop along the
path (``planner.motion.stopping``) when it keeps every limit, else sigma's own ramp. Continuous jog
is a move planned to the soft limit (a lost release stops there); a release is a hold followed
by abandoning the move. Faults keep the point to resume from (``resume_line``; ``resume()`` in
IDLE moves there safely and continues).

Coordinates: machine = drive position - home offset (set by homing); what a program reads
(the work position) is the machine position read in the frame in force
(``planner.core.frames.Frame``: G5x with its XY rotation, G92/G52). Persisted in the state folder.

Units: positions mm / degrees (rotary), speeds mm/s, times s, overrides in percent.

The parts, by folder (each owns its state; a field has one writer; the parts learn of E-stop,
faults, alarms, reset, a new configuration and shutdown from ``MachineEvents``)::

    state/    states     StateMachine    state, reason, activity; TRANSITIONS, refusals, E-stop, reset
              alarm_log  AlarmLog        alarm list, the worker's alarms
              status     StatusBoard     the status snapshot, published on change
    program/  loader     ProgramLoader   load (parse, soft limits, plan) in a worker thread, re-checks
              run        ProgramRunner   cycle start, hold, resume, stop, run from line, overrides
    motion/   stream     Streamer        jobs, set-point streaming, pause points, the resume point
              positions  Positions       drive positions, home offsets, homed flags
              homing     Homing          machine zero (to the switches, by the drive, or set here)
              coordinates Coordinates    work offsets, G-code parameters, the frame in force
              manual     ManualMotion    jog, MDI
    devices/  spindle_ctl SpindleControl the spindle (its restart after the door, at-speed)
              outputs    DigitalOutputs  the drives' and terminals' outputs (M62-M65, coolant, signals)
              signals    MachineSignals  what the machine's signals read now, the refusals they call for
              io         MachineIo       buttons, door, air, lube, the program's coolant
              handwheel_ctl HandwheelControl the handwheel's axis, step and when it is live
              compensation Compensation  the leadscrew compensation, on while an axis is homed
              tools      ToolControl     tool table, tool in the spindle
              setter     ToolSetter      measuring a tool on the setter
              prober     Prober          G38.x;  waiter  InputWaiter  M66
              probing    Probing         the probing wizards (a part set up by touch)
    infra/    conn       Connection      the worker's life cycle, persistence, simulated time
              poller     StatusPoller    the poll;  drives  DriveLink  the worker's handle
              settings   MachineSettings the configuration in force
"""

from __future__ import annotations

import os
from collections.abc import Callable
from pathlib import Path
from typing import Any

from PySide6.QtCore import QObject, Signal

from app.machine.config import MachineConfig
from app.machine.devices.compensation import Compensation
from app.machine.devices.handwheel import HandwheelControl
from app.machine.devices.inputs import InputWaiter
from app.machine.devices.machine_io import MachineIo
from app.machine.devices.outputs import DigitalOutputs
from app.machine.devices.probe import Prober
from app.machine.devices.probing import Probing
from app.machine.devices.reads import ReadAgain
from app.machine.devices.setter import ToolSetter
from app.machine.devices.signals import MachineSignals
from app.machine.devices.spindle import SpindleControl
from app.machine.devices.tools import ToolControl
from app.machine.infra.drives import DriveLink
from app.machine.infra.events import MachineEvents, PanelChannels
from app.machine.infra.forward import forward, reads
from app.machine.infra.persist import StateStore
from app.machine.infra.settings import MachineSettings
from app.machine.model import (
    Activity,
    Alarm,
    BusStatus,
    HandwheelStatus,
    HoldKind,
    MachineState,
    ProbingResult,
    ProgramInfo,
    Prompt,
    RunSummary,
    Severity,
    SpindleState,
    TrackingReport,
)
from app.machine.motion.coordinates import Coordinates
from app.machine.motion.homing import Homing
from app.machine.motion.manual import JOG_INCREMENTS, ManualMotion
from app.machine.motion.pauses import PauseHandlers
from app.machine.motion.positions import Positions
from app.machine.motion.streamer import Streamer
from app.machine.program.joblog import JobLog
from app.machine.program.loader import ProgramLoader
from app.machine.program.runner import ProgramRunner
from app.machine.program.switches import RunSwitches
from app.machine.session.connection import RAMP_DOWN_TIMEOUT_S, Connection
from app.machine.session.monitoring import RemoteMonitoring
from app.machine.session.poller import StatusPoller
from app.machine.state.alarms import AlarmLog
from app.machine.state.overrides import Overrides
from app.machine.state.states import TRANSITIONS, StateMachine
from app.machine.state.status import StatusBoard
from app.paths import DEFAULT_STATE_DIR
from ethercat.worker import CyclicWorker, WorkerConfig
from opcua_server.server import ServerStatus
from opcua_server.settings import OpcUaOverride, OpcUaSettings
from planner.core.program import Program
from planner.core.tools import ToolTable
from planner.motion.plan import Plan

__all__ = [
    "DEFAULT_STATE_DIR",
    "JOG_INCREMENTS",
    "RAMP_DOWN_TIMEOUT_S",
    "TRANSITIONS",
    "MachineController",
]


def _part(name: str) -> Callable[[Any], Any]:
    """The part ``name`` of a controller (for the declarations below)."""
    return lambda c: getattr(c, name)


_states, _settings, _positions, _coordinates = _part("states"), _part("settings"), _part("positions"), \
    _part("coordinates")
_stream, _loader, _run, _manual, _homing = _part("stream"), _part("loader"), _part("run"), _part("manual"), \
    _part("homing")
_spindle, _tools, _setter, _alarms, _conn = _part("spindle_ctl"), _part("tools"), _part("setter"), \
    _part("alarm_log"), _part("conn")
_poller, _drives, _status, _remote = _part("poller"), _part("drives"), _part("status"), _part("remote")
_job_log, _probing, _prober, _switches = _part("jobs_log"), _part("probing"), _part("prober"), \
    _part("switches")
_io, _signals, _wheel = _part("io"), _part("signals"), _part("handwheel_ctl")


class MachineController(QObject):
    """The machine: program run, hold/override, jog, MDI, homing, offsets, limits, alarms.

    Construct with a configuration (``MachineConfig``, a TOML path, or None for the state
    dir's saved ``machine.toml`` / the shipped XYZ mill) and a state directory for persisted
    positions, offsets, homed flags and alarms. Call ``connect_bus()`` to start the worker
    (simulated drives when the configuration's bus kind is "sim"), ``shutdown()`` at exit.
    """

    # --- signals (all emitted in the controller's thread; ``MachineApi`` says what each carries)
    stateChanged = Signal(object, str)
    activityChanged = Signal(object)
    positionChanged = Signal(object, object)
    trackingSample = Signal(float, object, object)
    programLoaded = Signal(object)
    programReadAgain = Signal(object)
    programErrors = Signal(object)
    loadingChanged = Signal(bool, str)
    programFinished = Signal(object)
    lineChanged = Signal(int)
    progressChanged = Signal(float, float)
    speedChanged = Signal(float)
    overridesChanged = Signal(float, float)
    feedOverrideNote = Signal(str)
    modesChanged = Signal(bool, bool, bool)
    alarmsChanged = Signal(object)
    homedChanged = Signal(object)
    offsetsChanged = Signal(object, str)
    spindleChanged = Signal(object)
    toolsChanged = Signal(object, int)
    busStateChanged = Signal(object)
    trackingUpdated = Signal(object)
    configChanged = Signal(object)
    commandRefused = Signal(str, str)
    message = Signal(str)
    probingFinished = Signal(object)
    handwheelChanged = Signal(object)
    spindleSample = Signal(float, float, float)
    statusChanged = Signal(object)   # ControllerSnapshot, at most once an event-loop turn

    def __init__(
        self,
        config: MachineConfig | str | os.PathLike[str] | None = None,
        *,
        state_dir: str | os.PathLike[str] | None = None,
        worker_factory: Callable[[WorkerConfig], CyclicWorker] | None = None,
        parent: QObject | None = None,
        worker_mode: str = "process",
        poll_hz: float = 30.0,
        opcua: OpcUaSettings | OpcUaOverride | None = None,
    ) -> None:
        """``worker_mode``: "process" (default, the real-time worker in its own process),
        "thread", or "manual" (no clock: tests and tools drive time with ``advance``).
        ``opcua``: the OPC UA server's settings instead of the configuration's ``[opcua]``, or
        the command line's ``--opcua-port`` / ``--opcua-insecure`` over it."""
        super().__init__(parent)
        out, events, pauses = PanelChannels(), MachineEvents(), PauseHandlers()
        store = StateStore(state_dir if state_dir is not None else DEFAULT_STATE_DIR, exclusive=True)
        try:
            self.settings = settings = MachineSettings(config, store)
        except BaseException:
            store.release()
            raise
        self.drives = drives = DriveLink(worker_mode)
        self.alarm_log = alarms = AlarmLog(store, out, events)
        self.positions = positions = Positions(settings, out, events, drives)
        self.signals = signals = MachineSignals(settings, drives)
        self.handwheel_ctl = wheel = HandwheelControl(settings, drives, positions, signals, events, out)
        self.compensation = Compensation(settings, drives, positions, out, events)
        self.states = states = StateMachine(settings, out, events, drives, positions, alarms, signals, wheel)
        self.coordinates = coords = Coordinates(settings, states, positions, store, alarms, out, events,
                                                pauses)
        self.outputs = outputs = DigitalOutputs(settings, drives, alarms, events, pauses)
        self.overrides = overrides = Overrides()
        self.spindle_ctl = spindle = SpindleControl(settings, states, drives, outputs, alarms, out, events,
                                                    signals, overrides)
        self.tools = tools = ToolControl(settings, states, positions, coords, store, alarms, out, pauses)
        self.switches = switches = RunSwitches(out, events, overrides)
        self.stream = stream = Streamer(settings, states, drives, positions, coords, spindle, tools, switches,
                                        alarms, pauses, str(store.path("last_run.npz")), out, events)
        jobs = stream.jobs
        self.loader = loader = ProgramLoader(settings, states, positions, coords, tools, spindle, stream,
                                             jobs, switches, out, events, self)
        self.jobs_log = job_log = JobLog(store.dir, alarms, loader, out, events)
        self.run = run = ProgramRunner(settings, states, positions, tools, loader, stream, jobs, switches,
                                       alarms, out, events, job_log.refusal)
        read_again = ReadAgain(states, positions, stream, alarms, out)
        self.prober = prober = Prober(settings, drives, positions, stream, read_again, pauses, tools)
        self.waiter = InputWaiter(settings, coords, stream, read_again, pauses)
        self.manual = manual = ManualMotion(settings, states, positions, coords, tools, spindle, outputs,
                                            switches, stream, jobs, signals)
        self.setter = ToolSetter(settings, states, tools, positions, coords, manual, alarms)
        self.homing = homing = Homing(settings, states, drives, positions, alarms, events, manual)
        self.probing = Probing(settings, states, tools, positions, coords, manual, out.probingFinished.emit)
        self.poller = poller = StatusPoller(settings, drives, positions, coords, alarms, stream, out, events)
        self.io = io = MachineIo(settings, states, signals, drives, spindle, outputs, alarms, stream, events,
                                 run)
        poller.on_poll(io.poll)
        poller.on_poll(wheel.poll)
        poller.on_poll(spindle.poll)
        poller.on_poll(homing.poll)
        poller.on_poll(prober.place_simulated_surface)
        poller.on_poll(prober.place_simulated_part)
        self.conn = conn = Connection(settings, store, states, drives, positions, coords, alarms, stream,
                                      poller, out, events, worker_factory, poll_hz, self)
        self.status = StatusBoard(settings, states, positions, coords, stream, switches, run, loader, spindle,
                                  tools, alarms, poller, out, self)
        self.status.published.connect(self.statusChanged.emit)
        self.remote = remote = RemoteMonitoring(settings, store.dir, alarms, events, opcua)
        self.status.published.connect(remote.publish)
        poller.on_poll(remote.poll)
        # the panel hears each fact after the parts have (the run log has the run that ended
        # when programFinished reaches the pages)
        for name in PanelChannels.names():
            getattr(out, name).connect(getattr(self, name).emit)
        conn.restore_persisted()
        for text in store.problems:
            alarms.raise_alarm("persistence", text, Severity.WARNING, "state_file")
        if settings.notice:
            alarms.raise_alarm("config", settings.notice, Severity.WARNING, "config_recovered")
        remote.start(self.status.current())

    # ------------------------------------------------------------------ read-only
    # (``MachineApi`` documents each; the part's attribute of that name, or as named)
    state: reads[MachineState] = reads(_states, "state")
    prompt: reads[Prompt | None] = reads(_states, "prompt")
    hold_kind: reads[HoldKind] = reads(_states, "hold_kind")
    state_reason: reads[str] = reads(_states, "state_reason")
    activity: reads[Activity] = reads(_states, "activity")
    config: reads[MachineConfig] = reads(_settings, "config")
    axes: reads[tuple[str, ...]] = reads(_settings, "axes")
    machine_position: reads[tuple[float, ...]] = reads(_positions, "machine_position")
    reference_position: reads[tuple[float, ...]] = reads(_positions, "reference_position")
    homed: reads[tuple[bool, ...]] = reads(_positions, "homed")
    work_position: reads[tuple[float, ...]] = reads(_coordinates, "work_position")
    work_offsets: reads[dict[str, tuple[float, ...]]] = reads(_coordinates, "work_offsets")
    active_offset: reads[str] = reads(_coordinates, "active_offset")
    g92_offset: reads[tuple[float, ...] | None] = reads(_coordinates, "g92_in_force")
    xy_rotation_deg: reads[float] = reads(_coordinates, "xy_rotation_deg")
    program_info: reads[ProgramInfo | None] = reads(_loader, "program_info")
    program: reads[Program | None] = reads(_loader, "program")
    plan: reads[Plan | None] = reads(_loader, "plan")
    loading: reads[bool] = reads(_loader, "loading")
    loading_name: reads[str] = reads(_loader, "loading_name")
    loading_progress: reads[float] = reads(_loader, "loading_progress")
    current_line: reads[int] = reads(_stream, "line")
    distance_to_go: reads[tuple[float, ...]] = reads(_stream, "distance_to_go")
    progress: reads[tuple[float, float]] = reads(_stream, "progress")
    tracking: reads[TrackingReport] = reads(_stream, "tracking")
    last_run: reads[RunSummary | None] = reads(_stream, "last_summary")
    last_probing: reads[ProbingResult | None] = reads(_probing, "last")
    feed_override_pct: reads[float] = reads(_switches, "feed_pct")
    rapid_override_pct: reads[float] = reads(_switches, "rapid_pct")
    single_block: reads[bool] = reads(_switches, "single_block")
    optional_stop: reads[bool] = reads(_switches, "optional_stop")
    block_delete: reads[bool] = reads(_switches, "block_delete")
    resume_line: reads[int] = reads(_run, "resume_line")
    run_first_move: reads[int] = reads(_run, "first_move")
    spindle: reads[SpindleState] = reads(_spindle, "spindle")
    tool_table: reads[ToolTable] = reads(_tools, "table")
    tool_in_spindle: reads[int] = reads(_tools, "in_spindle")
    alarms: reads[tuple[Alarm, ...]] = reads(_alarms, "all")
    active_alarms: reads[tuple[Alarm, ...]] = reads(_alarms, "active")
    bus_status: reads[BusStatus] = reads(_poller, "bus_status")
    config_path: reads[Path] = reads(_conn, "config_path")
    interrupted: reads[tuple[str, int] | None] = reads(_run, "interrupted")
    worker: reads[CyclicWorker | None] = reads(_drives, "worker")
    opcua_status: reads[ServerStatus | None] = reads(_remote, "status")
    part_count: reads[int] = reads(_job_log, "count")
    part_target: reads[int] = reads(_job_log, "target")
    opcua_settings: reads[OpcUaSettings] = reads(_remote, "settings")
    coolant: reads[tuple[bool, bool]] = reads(_io, "coolant")
    handwheel: reads[HandwheelStatus] = reads(_wheel, "status")

    # ------------------------------------------------------------------ commands
    snapshot = forward(_status, StatusBoard.current)
    refusal = forward(_run, ProgramRunner.refusal)
    reset = forward(_run, ProgramRunner.reset)
    estop = forward(_states, StateMachine.estop)
    estop_release = forward(_states, StateMachine.estop_release)
    update_config = forward(_conn, Connection.update_config)
    connect_bus = forward(_conn, Connection.connect_bus)
    disconnect_bus = forward(_conn, Connection.disconnect_bus)
    shutdown = forward(_conn, Connection.shutdown)
    advance = forward(_conn, Connection.advance)
    run_until = forward(_conn, Connection.run_until)
    machine_time_s = forward(_conn, Connection.machine_time_s)
    load_program = forward(_loader, ProgramLoader.load_program)
    wait_loaded = forward(_loader, ProgramLoader.wait_loaded)
    wait_run_plan = forward(_loader, ProgramLoader.wait_run_plan)
    cycle_start = forward(_run, ProgramRunner.cycle_start)
    feed_hold = forward(_run, ProgramRunner.feed_hold)
    resume = forward(_run, ProgramRunner.resume)
    stop = forward(_run, ProgramRunner.stop)
    set_single_block = forward(_run, ProgramRunner.set_single_block)
    set_optional_stop = forward(_run, ProgramRunner.set_optional_stop)
    set_block_delete = forward(_run, ProgramRunner.set_block_delete)
    restart_preview = forward(_run, ProgramRunner.restart_preview)
    run_from_line = forward(_run, ProgramRunner.run_from_line)
    set_feed_override = forward(_run, ProgramRunner.set_feed_override)
    set_rapid_override = forward(_run, ProgramRunner.set_rapid_override)
    jog_start = forward(_manual, ManualMotion.jog_start)
    jog_stop = forward(_manual, ManualMotion.jog_stop)
    jog_increment = forward(_manual, ManualMotion.jog_increment)
    mdi = forward(_manual, ManualMotion.mdi)
    home_axis = forward(_homing, Homing.home_axis)
    home_all = forward(_homing, Homing.home_all)
    set_machine_zero_here = forward(_homing, Homing.set_machine_zero_here)
    set_work_offset = forward(_coordinates, Coordinates.set_work_offset)
    select_work_offset = forward(_coordinates, Coordinates.select_work_offset)
    set_work_rotation = forward(_coordinates, Coordinates.set_work_rotation)
    work_rotation = forward(_coordinates, Coordinates.rotation_of)
    touch_off = forward(_coordinates, Coordinates.touch_off)
    clear_g92 = forward(_coordinates, Coordinates.clear_g92)
    spindle_on = forward(_spindle, SpindleControl.spindle_on)
    spindle_off = forward(_spindle, SpindleControl.spindle_off)
    spindle_speed = forward(_spindle, SpindleControl.spindle_speed)
    set_spindle_override = forward(_spindle, SpindleControl.set_override)
    set_tool = forward(_tools, ToolControl.set_tool)
    remove_tool = forward(_tools, ToolControl.remove_tool)
    set_tool_in_spindle = forward(_tools, ToolControl.set_tool_in_spindle)
    touch_off_tool = forward(_tools, ToolControl.touch_off_tool)
    import_tool_table = forward(_tools, ToolControl.import_table)
    measure_tool = forward(_setter, ToolSetter.measure_tool)
    probe_routine = forward(_probing, Probing.routine)
    preview_probing = forward(_probing, Probing.preview_probing)
    run_probing = forward(_probing, Probing.run_probing)
    simulate_part = forward(_prober, Prober.simulate_part)
    acknowledge_alarm = forward(_alarms, AlarmLog.acknowledge_alarm)
    set_part_target = forward(_job_log, JobLog.set_target)
    reset_part_count = forward(_job_log, JobLog.reset_count)
    runs = forward(_job_log, JobLog.runs)
    export_runs = forward(_job_log, JobLog.export)
    add_trace_sink = forward(_stream, Streamer.add_trace_sink)
    override_limits = forward(_io, MachineIo.override_limits)
    set_coolant = forward(_io, MachineIo.set_coolant)
    set_work_light = forward(_io, MachineIo.set_work_light)
    simulate_input = forward(_io, MachineIo.simulate_input)
    signal_readings = forward(_signals, MachineSignals.readings)
    select_handwheel = forward(_wheel, HandwheelControl.select_handwheel)
    set_handwheel_step = forward(_wheel, HandwheelControl.set_handwheel_step)
    turn_handwheel = forward(_wheel, HandwheelControl.turn_handwheel)
    simulate_spindle_load = forward(_spindle, SpindleControl.simulate_spindle_load)
