"""The bus connection: the worker's life cycle, the feeder thread, the state saved for a power
cut, a new configuration, and simulated time.

connect_bus starts the worker (WorkerConfig defaults for core, priority and spin) and the
feeder thread; disconnect_bus/shutdown first stop any motion along its path, then stop the
worker (drives disabled) and only then the feeder. ``advance``/``run_until`` drive simulated
time in worker mode "manual".
"""

from __future__ import annotations

import math
import os
import sys
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from PySide6.QtCore import QObject, QTimer

from app.machine.config import MachineConfig
from app.machine.errors import ConfigError
from app.machine.infra.drives import DriveLink
from app.machine.infra.events import MachineEvents, PanelChannels
from app.machine.infra.persist import StateStore
from app.machine.infra.settings import MachineSettings
from app.machine.model import Activity, BusStatus, CommandResult, MachineState, Severity
from app.machine.motion.coordinates import Coordinates
from app.machine.motion.positions import Positions
from app.machine.motion.streamer import Streamer
from app.machine.motion.timescale import ramp_bound_s
from app.machine.ports import AlarmSink
from app.machine.session.poller import StatusPoller
from app.machine.state.gate import Action, guarded
from app.machine.state.states import StateMachine
from app.machine.wiring import worker_io
from ethercat.worker import CyclicWorker, DriveSpec, WorkerConfig, WorkerSnapshot
from planner.core.machine import WORK_OFFSET_NAMES, AxisSpec

__all__ = ["Connection", "PERSIST_EVERY_S", "RAMP_DOWN_TIMEOUT_S"]

RAMP_DOWN_TIMEOUT_S = 3.0  # disconnect/shutdown mid-run: longest wait for the stop along the path
PERSIST_EVERY_S = 1.0  # position and homed flags saved this often while the axes may move
_MOVING = frozenset({MachineState.RUNNING, MachineState.HOLD, MachineState.HOMING})
_SAVED_ON = frozenset({MachineState.IDLE, MachineState.DISCONNECTED, MachineState.ALARM, MachineState.ESTOP})


#: the worker's ring holds this long of set-points at the least (2000 at 1 ms), and twice the
#: lead the feeder keeps plus the longest braking tail behind it, whatever the cycle
RING_S = 2.0


def ring_capacity(ts_s: float, lead_s: float, stop_s: float = 0.0) -> int:
    """Set-points the worker's ring holds for a cycle of ``ts_s``, a lead of ``lead_s`` and a
    braking tail of at most ``stop_s`` (``app.machine.motion.timescale.ramp_bound_s``)."""
    return int(math.ceil(max(RING_S, 2.0 * lead_s + 1.2 * stop_s) / ts_s))


#: what a machine homed by "set here" is after a power loss or a kill
NO_REFERENCE = ("this machine has no reference switches ([homing] method = \"set_here\"): where its axes "
                "stand after the cut is not known, so machine zero set now would not be the old one; "
                "the part zero must be touched off again")


class Connection:
    """Worker and feeder life cycle, persistence of the machine state, simulated time
    (``controller.conn``)."""

    def __init__(self, settings: MachineSettings, store: StateStore, states: StateMachine, drives: DriveLink,
                 positions: Positions, coordinates: Coordinates, alarms: AlarmSink, motion: Streamer,
                 poller: StatusPoller, out: PanelChannels, events: MachineEvents,
                 worker_factory: Callable[[WorkerConfig], CyclicWorker] | None, poll_hz: float,
                 qt_parent: QObject) -> None:
        self._settings = settings
        self.store = store
        self._states = states
        self._drives = drives
        self._positions = positions
        self._coordinates = coordinates
        self._alarms = alarms
        self._motion = motion
        self._poller = poller
        self._out = out
        self._events = events
        self._worker_factory = worker_factory
        self.unclean_shutdown = False   # the state folder says the last run did not end cleanly
        # the program (path, or name for a text) and line running when it did: (program, line)
        self.persisted_at = 0.0         # time.monotonic() of the last save of the machine state
        self._feeder: threading.Thread | None = None
        self._feeder_stop = threading.Event()
        self.timer = QTimer(qt_parent)     # never fires after the controller is gone
        self.timer.setInterval(max(int(1000.0 / poll_hz), 5))
        self.timer.timeout.connect(self.tick)
        self._shutdown = False
        self._feeder_error = ""  # set by the feeder thread, reported by the next tick
        self._feeder_error_lock = threading.Lock()
        events.transition.connect(self._transition)
        events.coordinates_changed.connect(self.persist_state)

    @property
    def worker_mode(self) -> str:
        return self._drives.worker_mode

    @property
    def config_path(self) -> Path:
        """The machine configuration file that ``update_config`` writes."""
        return self._settings.path

    # ------------------------------------------------------------------ persistence
    def restore_persisted(self) -> None:
        """The positions, homed flags, offsets and parameters the state folder kept; after an
        unclean end (power cut, kill) the axes are not homed any more, with an alarm saying why."""
        cfg = self._settings.config
        axes = cfg.axes
        st = self.store.load_state(axes)
        active = None
        if st is not None:
            self._positions.restore(st["raw_position"], st["home_offset"], st["homed"])
            self.unclean_shutdown = st["running"]
            if st["running"]:
                # the last run ended without a shutdown (power loss, kill): the drives may have
                # moved or lost their count since the position was saved
                no_reference = cfg.homing.method == "set_here"
                if not cfg.homing.absolute_encoders and any(self._positions.homed):
                    self._positions.unhome_all()
                    why = "axes are not homed any more: home them before running a program"
                else:
                    why = "the drives have absolute encoders: homed flags kept"
                if no_reference:
                    why = NO_REFERENCE
                when = time.strftime("%Y-%m-%d %H:%M:%S", time.localtime(st["saved"])) if st["saved"] else "?"
                cause = (f"the control did not shut down cleanly (power loss or killed; position last "
                         f"saved {when}): {why}")
                cut = st["program"] and st["line"] > 0
                if cut and no_reference:
                    cause += (f"; {os.path.basename(st['program'])} was running at line {st['line']}: "
                              "touch off the part zero again and run it from its start")
                elif cut:
                    cause += (f"; {os.path.basename(st['program'])} was running at line {st['line']}: "
                              f"load it and run from line {st['line']} once homed")
                self._alarms.raise_alarm("controller", cause, Severity.WARNING, "unclean_shutdown")
                if cut and not no_reference:
                    self._events.run_interrupted.emit(st["program"], int(st["line"]), float(st["saved"]))
            active = st["active_offset"] if st["active_offset"] in WORK_OFFSET_NAMES else None
        self._coordinates.restore(self.store.load_offsets(len(axes)), self.store.load_parameters(), active)

    def persist_state(self) -> None:
        """Save the position, home offsets, homed flags and active offset, with a flag saying
        whether a control has the drives (an unclean end leaves it set)."""
        self.persisted_at = time.monotonic()
        pos = self._positions
        job = self._motion.job
        program, line = "", 0
        if job is not None and job.kind is Activity.PROGRAM and self._motion.line > 0:
            program, line = job.source or job.name, int(self._motion.line)
        try:
            self.store.save_state(
                self._settings.config.axes,
                [float(x) for x in pos.raw_pos],
                [float(x) for x in pos.home_offset],
                list(pos.homed),
                self._coordinates.active_offset,
                running=self._drives.attached and not self._shutdown,
                program=program, line=line,
            )
        except OSError as exc:
            self._alarms.raise_alarm("persistence", f"cannot save machine state: {exc}", Severity.WARNING,
                                     "state_file")

    def _transition(self, _old: MachineState, new: MachineState) -> None:
        if new in _SAVED_ON:
            self.persist_state()

    # ------------------------------------------------------------------ configuration
    @guarded(Action.UPDATE_CONFIG)
    def update_config(self, config: MachineConfig, *, wait: bool = False) -> CommandResult:
        """Validate, write atomically (temp + os.replace, old file kept as .bak) and apply.
        Refused while moving; bus and drive changes take effect at the next connect; the loaded
        program is checked again against the new limits: in a worker thread like a load (cycle
        start refused until it is done; ``loadingChanged``), or before returning with ``wait``
        (headless; the outcome is the same).
        """
        action = Action.UPDATE_CONFIG
        try:
            saved = self._settings.write(config)
        except ConfigError as exc:
            return self._states.refuse(action, str(exc))
        except OSError as exc:
            return self._states.refuse(action, f"cannot write {self._settings.path}: {exc}")
        axes_changed = saved.axes != self._settings.config.axes
        self._settings.apply(saved)
        self._events.config_changed.emit(saved, axes_changed)
        self.persist_state()
        self._out.configChanged.emit(saved)
        self._events.config_applied.emit(wait)
        if axes_changed and self._drives.attached:
            self._out.message.emit("axes changed: reconnect the bus to apply")
        return self._states.ok(action)

    @property
    def gate(self) -> StateMachine:
        return self._states

    # ------------------------------------------------------------------ the worker
    def _worker_config(self) -> WorkerConfig:
        from ethercat.worker.shared import ordered_stores

        cfg = self._settings.config
        ids = {d.position: d for d in cfg.bus.drives}

        def drive(a: AxisSpec, position: int, name: str, direction: int) -> DriveSpec:
            ident = ids.get(position)
            return DriveSpec(position=position, axis_name=name, counts_per_unit=a.counts_per_unit,
                             direction=direction, following_error_window=a.following_error_window,
                             vendor_id=ident.vendor_id if ident is not None else 0,
                             product_code=ident.product_code if ident is not None else 0)

        axes = cfg.machine.axes
        drives = tuple(drive(a, a.drive_position, a.name, a.direction) for a in axes) + tuple(
            # each gantry's second drive, after the axes (``MachineConfig.drives``)
            drive(a, a.gantry_drive, f"{a.name}2", a.gantry_direction)
            for a in axes if a.gantry_drive is not None)
        io = worker_io(cfg.wiring, cfg.machine, cfg.homing.method, cfg.bus.kind == "sim")
        options: tuple[tuple[str, Any], ...] = ()
        if cfg.bus.kind == "soem":
            options = (("setups", tuple((d.position, d.setup()) for d in cfg.bus.drives)),)
        if cfg.bus.kind == "sim":
            at = tuple(zip(cfg.machine.axes, self._positions.raw_pos))
            counts = tuple(float(a.direction * a.counts_per_unit * x) for a, x in at) + tuple(
                # a gantry's second side starts where its first stands
                float(a.gantry_direction * a.counts_per_unit * x) for a, x in at if a.gantry_drive is not None
            )
            # the simulated machine's switches and the rest state of its inputs
            options = (("initial_positions_counts", counts), ("switches", io.sim_switches),
                       ("input_rest", io.input_rest), ("index_pitch_units", io.sim_index_pitch))
        # core, real-time priority and spin: the WorkerConfig defaults (the worker picks a free
        # core itself and uses SCHED_FIFO 49, below PREEMPT_RT's interrupt threads)
        mode = self.worker_mode
        if mode == "process" and not ordered_stores():
            # the worker's own process shares memory in a way that needs x86's store order;
            # elsewhere (ARM panel PCs) the same loop runs as a thread of the panel
            mode = "thread"
            self._alarms.raise_alarm(
                "worker", "this CPU does not keep stores in order: the 1 ms loop runs as a thread "
                "of the panel, not in its own process (less punctual under GUI load)",
                Severity.WARNING, "worker_thread_mode")
        return WorkerConfig(
            drives=drives,
            ts_s=cfg.machine.planner.ts_s,
            bus_kind=cfg.bus.kind,
            adapter=cfg.bus.adapter,
            wkc_error_limit=cfg.bus.wkc_error_limit,
            mode=mode,
            bus_options=options,
            homing_timeout_s=cfg.homing.timeout_s,
            terminals=io.terminals,
            watches=io.watches,
            switch_homing=io.switch_homing,
            handwheel=io.handwheel,
            gantry=io.gantry,
            compensation=cfg.compensation,
            spindle=cfg.spindle.spec,
            buffer_capacity=ring_capacity(cfg.machine.planner.ts_s, cfg.controller.lead_s,
                                          ramp_bound_s(cfg.machine, self._settings.budget)),
        )

    def connect_bus(self) -> CommandResult:
        """Start the worker (simulated drives when the bus kind is "sim") and enable the drives:
        DISCONNECTED -> IDLE. Saved positions are restored (simulated drives start there); an axis
        whose reported position differs from the saved one loses its homed state (warning alarm).
        """
        action = Action.CONNECT
        if self._states.state is not MachineState.DISCONNECTED:
            return self._states.refuse(action,
                                       f"already connected (machine is {self._states.state.label.lower()})")
        wcfg = self._worker_config()
        try:
            worker = self._worker_factory(wcfg) if self._worker_factory is not None else CyclicWorker(wcfg)
            worker.start()
        except Exception as exc:  # noqa: BLE001 - any bus failure is shown to the operator
            self._alarms.raise_alarm("bus", f"cannot start the bus: {exc}", Severity.WARNING, "bus_start")
            return self._states.refuse(action, f"cannot start the bus: {exc}")
        self._drives.attach(worker)
        self._events.connecting.emit()
        # what the bus start-up adapted to (a drive's own mapping, objects it lacks): recorded
        # for the integrator, nothing to acknowledge
        for k, note in enumerate(self._drives.bus_notes()):
            self._alarms.raise_alarm("bus", note, Severity.INFO, f"bus_note_{k}")
        try:
            self._drives.enable_drives()
        except Exception as exc:  # noqa: BLE001
            self._stop_worker()
            self._alarms.raise_alarm("bus", f"drives cannot be enabled: {exc}", Severity.WARNING, "enable")
            return self._states.refuse(action, f"drives cannot be enabled: {exc}")
        snap = self._drives.snapshot()
        assert snap is not None
        cfg = self._settings.config
        # a gantry's two sides may have been racked while the power was off, and only homing
        # squares them again: such an axis is never homed from the saved state
        gantries = [i for i, a in enumerate(cfg.machine.axes) if a.gantry_drive is not None]
        homed = self._positions.homed
        lost = self._positions.take_actual(snap.actual_position, cfg.controller.position_tolerance, gantries)
        moved = [i for i in lost if i not in gantries]
        if moved:
            names = " ".join(cfg.axes[i] for i in moved)
            self._alarms.raise_alarm(
                "controller",
                f"axes {names} report another position than saved: homed state cleared, home again",
                Severity.WARNING, "position_lost")
        racked = [i for i in gantries if homed[i]]
        if racked:
            names = " ".join(cfg.axes[i] for i in racked)
            self._alarms.raise_alarm(
                "controller", f"gantry {names}: homed state cleared at connecting: only homing squares "
                "its two sides again, home it", Severity.WARNING, "gantry_unhomed")
        self._motion.reset_serials()
        self._states.set_state(MachineState.IDLE, "ready")
        if self._drives.realtime:
            # the feeder thread shares the GIL with the GUI: a short switch interval keeps it on
            # time while the GUI computes (NOTES.md: 5 ms default stretches 1 ms loops to 5 ms)
            if sys.getswitchinterval() > 0.001:
                sys.setswitchinterval(0.001)
            self._feeder_stop.clear()
            self._feeder = threading.Thread(target=self._feeder_main, name="cnc-feeder", daemon=True)
            self._feeder.start()
            self.timer.start()
        self._events.announce.emit()
        self.persist_state()            # "running" from now on, until a clean shutdown
        return self._states.ok(action)

    def _stop_worker(self) -> None:
        """Stop the worker (drives disabled, bus closed), then the feeder thread."""
        self.timer.stop()
        w = self._drives.detach()     # the feeder sees no worker from here on
        if w is not None:
            try:
                w.stop()
            except Exception:  # noqa: BLE001 - stopping must not fail
                pass
        self._feeder_stop.set()
        if self._feeder is not None and self._feeder is not threading.current_thread():
            self._feeder.join(timeout=2.0)
        self._feeder = None

    def disconnect_bus(self) -> CommandResult:
        """Stop any motion (a jerk-limited stop along the path, at most ``RAMP_DOWN_TIMEOUT_S``),
        abandon it, disable the drives and stop the worker, then the feeder: -> DISCONNECTED."""
        if self._states.state is MachineState.DISCONNECTED:
            return self._states.ok("disconnect")
        self._ramp_down("disconnected")
        if self._drives.attached:
            try:
                self._poller.poll()
            except Exception:  # noqa: BLE001
                pass
        self._motion.abandon("disconnected")
        self._stop_worker()
        self.persist_state()            # no controller has the drives any more
        self._states.set_state(MachineState.DISCONNECTED, "disconnected")
        self._poller.emit_bus(BusStatus(kind=self._settings.config.bus.kind, connected=False,
                                        state="disconnected"))
        return self._states.ok("disconnect")

    def _ramp_down(self, reason: str, timeout_s: float = RAMP_DOWN_TIMEOUT_S) -> bool:
        """Bring any motion to a standstill on its path before the worker is stopped: the same
        jerk-limited stop as ``stop()``, fed as usual, waited for here (the poll timer may be
        gone at exit): stopping the feeder first would let the worker's buffer run dry while
        moving, stopping the worker first would cut the drives at speed. True at standstill."""
        job = self._motion.job
        if self._motion.ramp_down(reason):
            return True

        def still() -> bool:
            return self._motion.still(job)

        if not self._drives.realtime:
            return self.run_until(still, timeout_s)
        t_end = time.monotonic() + timeout_s
        while not still():
            if time.monotonic() > t_end:
                return False
            if self._feeder is None or not self._feeder.is_alive():
                self._motion.feed()
            time.sleep(0.005)  # the feeder thread keeps the buffer filled meanwhile
        return True

    def shutdown(self) -> None:
        """Stop any motion (jerk-limited), spindle off, disconnect (worker stopped before the
        feeder), persist positions and offsets; safe to call twice."""
        if self._shutdown:
            return
        self._shutdown = True
        try:
            self._ramp_down("shutdown")
            self._events.shutdown.emit()
            self.disconnect_bus()
        finally:
            self.persist_state()
            self.store.release()

    def _feeder_main(self) -> None:
        while not self._feeder_stop.wait(0.002):
            try:
                self._motion.feed()
            except Exception as exc:  # noqa: BLE001 - never let the feeder die silently
                with self._feeder_error_lock:
                    self._feeder_error = f"set-point feeder failed: {exc}"
                return

    # ------------------------------------------------------------------ the poll
    def tick(self) -> None:
        """The poll (the timer, or each step of simulated time), then what the connection
        watches: a failed feeder, and the position saved while the axes may move."""
        self._poller.poll()
        with self._feeder_error_lock:
            text, self._feeder_error = self._feeder_error, ""
        if text:
            self._alarms.fault(text, "controller", "feeder")
        if self._states.state in _MOVING and time.monotonic() - self.persisted_at >= PERSIST_EVERY_S:
            self.persist_state()     # a power cut loses at most this much of the position

    def machine_time_s(self) -> float:
        """The worker's clock (s): the machine time of traces and scenarios."""
        snap: WorkerSnapshot | None = self._drives.snapshot()
        return float(snap.time_s) if snap is not None else 0.0

    def advance(self, seconds: float, step_cycles: int = 10) -> None:
        """Manual worker mode only: run the machine for ``seconds`` of simulated time
        (feed set-points, run the cycles, poll and emit signals). For tests and tools."""
        if not self._drives.attached:
            return
        ts = self._settings.config.machine.planner.ts_s
        cycles = int(round(seconds / ts))
        since_poll = 0
        poll_every = max(int(round(1.0 / (30.0 * ts))), 1)
        while cycles > 0 and self._drives.attached:
            k = min(step_cycles, cycles)
            self._motion.feed()
            self._drives.step(k)
            cycles -= k
            since_poll += k
            if since_poll >= poll_every or cycles <= 0:
                since_poll = 0
                self.tick()

    def run_until(self, predicate: Callable[[], bool], timeout_s: float = 10.0) -> bool:
        """Manual mode: advance until ``predicate()`` is true (True) or ``timeout_s`` of
        simulated time passed (False)."""
        ts = self._settings.config.machine.planner.ts_s
        step_s = 33 * ts
        steps = int(timeout_s / step_s) + 1
        for _ in range(steps):
            if predicate():
                return True
            self.advance(step_s, step_cycles=11)
        return bool(predicate())

