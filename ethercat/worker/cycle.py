"""The cycle, run in the worker's process or thread: it owns the bus.

Per cycle (``CycleLoop.cycle``): command mailbox -> outputs (set-point from the ring when
ENABLED, else target := actual) -> ``bus.exchange()`` -> supervision (working counter, drive
faults, following error over its window for ``following_error_cycles``) -> tracking
(e = reference - actual per axis, the paper's Eq. 18) -> at ``snapshot_hz`` and right after a
cycle that applied a command, a snapshot. Reactions: underrun while moving holds the last
position (alarm UNDERRUN, not a quick stop); working counter wrong for more than
``wkc_error_limit`` cycles, a drive fault, a following error or E-stop: quick stop of all
axes, the set-point ring flushed, an alarm naming the cause. Lost slaves are recovered by the
bus's ``recover_slaves`` on the acyclic helper; the homing method is written there too.
Nothing in the cycle allocates arrays, logs or makes an SDO.
"""

from __future__ import annotations

import math

import numpy as np

from .. import cia402
from ..bus import Bus, make_bus
from ..cia402 import Cia402State
from ..errors import EtherCATError
from .acyclic import AcyclicHelper, SlaveRecovery
from .clocked import run_clocked
from .compensation import Compensation
from .gantry import Gantry
from .handwheel import Handwheel, WheelFault, WheelState
from .homing import Homing, HomingPhase, HomingResult
from .messages import INJECT_NAMES, Command, Result
from .ring import replace_queued
from .shared import ALARM_SLOTS, SharedBlock
from .spindle import SpindleLoop
from .switch_homing import SwitchHomer
from .tracking import Tracker
from .types import REF_HISTORY, AlarmCode, EventCode, WorkerConfig, WorkerState
from .watches import Watches

__all__ = ["CycleLoop"]

_FAULTED_LUT = np.array([s in (Cia402State.FAULT, Cia402State.FAULT_REACTION_ACTIVE) for s in Cia402State])
_NOT_ENABLED_LUT = np.array([s is not Cia402State.OPERATION_ENABLED for s in Cia402State])
_HOMING_METHOD = "homing method"
_ERROR_CODE = "error code"
#: a drive found in FAULT this soon after the bus came up gets one fault reset by itself
#: (drives that power up faulted, e.g. after an under-voltage while the bus was down)
STARTUP_RESET_WINDOW_S = 0.5


class CycleLoop:
    """The cycle and its state. Owns the bus; reads and writes the shared block."""

    def __init__(self, config: WorkerConfig, block: SharedBlock) -> None:
        self.cfg = config
        self.block = block
        self.ctl = block.ctl
        self.lv = block.live
        n = config.n_axes
        self.n = n
        self.ring = block.ring
        self.cap = config.buffer_capacity
        self.bus: Bus | None = None
        scales = tuple(cia402.AxisScale(d.counts_per_unit, d.direction) for d in config.drives)
        self.gain, self.offset = cia402.scale_arrays(scales)
        self.window = np.array([d.following_error_window for d in config.drives], dtype=np.float64)
        lv = self.lv
        self.ref, self.act, self.fe = lv.ref, lv.act, lv.fe
        self.prev_ref = np.zeros(n)
        self.ref_hist = np.zeros((REF_HISTORY, n))
        # row views made once, so the cycle indexes lists instead of creating array views
        self.ref_rows = [self.ref_hist[i] for i in range(REF_HISTORY)]
        # the serial of the set-point in ``ref`` at each of those cycles (-1: none taken yet)
        self.serial_hist = np.full(REF_HISTORY, -1, dtype=np.int64)
        self.ring_rows = [self.ring[i] for i in range(config.buffer_capacity)]
        self.tmp = np.zeros(n)
        self.cmd = np.zeros(n)             # the set-points sent: ref + leadscrew compensation
        self.comp = Compensation(config.compensation, n, config.ts_s, REF_HISTORY, lv.comp, lv.comp_on)
        self.tmp2 = np.zeros(n)
        self.states = np.zeros(n, dtype=np.int8)
        self.scratch_i = np.zeros(n, dtype=np.int64)
        self.fe_count = np.zeros(n, dtype=np.int64)
        self.fault_seen = np.zeros(n, dtype=bool)
        self.bool_tmp = np.zeros(n, dtype=bool)
        self.tracker = Tracker(lv, n, config.ts_s, config.tracking_window_s)
        self.eps_units = config.underrun_velocity_units_s * config.ts_s   # per cycle
        self.snapshot_every = max(1, int(round(1.0 / (config.snapshot_hz * config.ts_s))))
        self.state = WorkerState.STARTING
        self.state_cycles = 0
        self.moving = False
        self.wkc_bad_run = 0
        self.wkc_alarmed = False
        self.cmd_seen = int(self.ctl.cmd_seq)
        self.homing = Homing(lv.homing, lv.homed, int(config.homing_timeout_s / config.ts_s))
        self.fault_reset_cycle = 0
        self.trace_cap = config.trace_capacity
        self.trace = block.trace
        self.stop_requested = False
        self.publish_now = False           # a command was applied: publish after this cycle
        self.helper = AcyclicHelper(inline=config.mode == "manual")
        # slave loss and recovery
        self.lost_mask = 0
        every = max(1, int(round(config.recover_interval_s / config.ts_s)))
        self.recovery = SlaveRecovery(self.helper, every)
        # drives without 0x603F in their process data: read by SDO after a fault
        self.error_code_by_sdo: list[bool] = [False] * n
        self.error_code_pending: list[int] = []
        # the armed probe input: drive (-1: none), bit mask and the level that trips it
        self.probe_axis, self.probe_mask, self.probe_level = -1, 0, True
        self.startup_reset_tried = False
        self.error_code_axis = -1
        self.enable_after_reset = False
        self.enable_confirmed = 0
        # every input word of a cycle: the drives' 0x60FD, then the terminals' inputs
        m = config.n_terminals
        self.m = m
        self.words = np.zeros(n + m, dtype=np.int64)
        self.words_d, self.words_t = self.words[:n], self.words[n:]
        self.watches = Watches(config.watches, lv.watch)
        self.switch_homer = SwitchHomer(config.switch_homing, config.ts_s, lv.homing, lv.homed,
                                        lv.home_step, lv.home_latch,
                                        int(config.homing_timeout_s / config.ts_s), config.gantry)
        self.gantry = Gantry(config.gantry, lv.skew, config.following_error_cycles)
        spec = config.handwheel
        self.wheel = Handwheel(config.ts_s, spec.counter_bits if spec else 16,
                               spec.max_counts_per_cycle if spec else 1, lv.wheel_state, lv.wheel_axis)
        self.wheel_terminal = spec.terminal if spec else -1
        self.wheel_slave = config.terminals[spec.terminal].position if spec else -1
        self.spindle = SpindleLoop(config.spindle, config.ts_s, config.enable_timeout_s, lv)

    # ------------------------------------------------------------------ bus
    def open_bus(self) -> None:
        cfg = self.cfg
        options = dict(cfg.bus_options)
        if cfg.bus_kind == "soem":
            options.setdefault("adapter", cfg.adapter)
        self.bus = make_bus(cfg.bus_kind, cfg.drives, cycle_time_s=cfg.ts_s, terminals=cfg.terminals,
                            spindles=(cfg.spindle,) if cfg.spindle else (), **options)
        self.bus.open()
        bus = self.bus
        self.lv.wkc_expected[...] = bus.expected_wkc
        self.error_code_by_sdo = [not bus.maps_object(i, 0x603F) for i in range(self.n)]
        self.switch_homer.bind(bus, self.gain, self.offset)
        bus.modes_of_operation[:] = cia402.CSP
        self._read_actual()
        np.copyto(self.ref, self.act)
        np.copyto(self.prev_ref, self.act)
        self._target_from_actual()
        self.lv.period_min[...] = math.inf
        self._set_state(WorkerState.DISABLED)

    def close_bus(self) -> None:
        bus = self.bus
        if bus is None:
            return
        self.stop_requested = True
        self.helper.close()
        try:
            if bus.is_open:
                for _ in range(5):          # leave drives disabled (best effort)
                    cia402.DISABLE_LUT.take(self.states, out=bus.controlword)
                    bus.spindle_controlword.fill(cia402.CW_QUICK_STOP)
                    bus.target_position[:] = bus.position_actual
                    bus.exchange()
                    cia402.decode_states(bus.statusword, self.states, self.scratch_i)
        except Exception:  # noqa: BLE001 - the bus is closed below whatever happened
            pass
        finally:
            bus.close()
            self.bus = None

    # ------------------------------------------------------------------ helpers
    def _set_state(self, st: WorkerState) -> None:
        if st is WorkerState.ENABLED:
            self.gantry.hold(self.ref)       # the pairs as they stand: square from now on
        self.state = st
        self.state_cycles = 0
        self.lv.state[...] = int(st)

    def _read_actual(self) -> None:
        """Actual positions, less the compensation sent with the set-points they answer."""
        assert self.bus is not None
        cia402.counts_to_units(self.bus.position_actual, self.gain, self.offset, self.act)
        self.comp.nominal(self.act, (int(self.lv.cycle) - self.cfg.tracking_delay_cycles) % REF_HISTORY)

    def _target_from_actual(self) -> None:
        assert self.bus is not None
        np.copyto(self.bus.target_position, self.bus.position_actual)

    def _alarm(self, code: AlarmCode | EventCode, axis: int = -1, a: int = 0, b: int = 0,
               f: float = 0.0) -> None:
        k = int(self.ctl.alarms)
        row = self.block.alarm[k % ALARM_SLOTS]
        row["code"] = int(code)
        row["axis"] = axis
        row["cycle"] = int(self.lv.cycle)
        row["a"] = a
        row["b"] = b
        row["command"] = self.cmd_seen     # the command behind it (quick stop reason lookup)
        row["f"] = f
        self.ctl.alarms[...] = k + 1

    def _flush(self) -> None:
        self.ctl.tail[...] = int(self.ctl.head)
        self.moving = False

    def _hold_actual(self) -> None:
        np.copyto(self.ref, self.act)
        np.copyto(self.prev_ref, self.act)
        self.ref_hist[:] = self.act
        self._target_from_actual()

    def _reaction(self, code: AlarmCode, axis: int = -1, a: int = 0, b: int = 0, f: float = 0.0,
                  state: WorkerState = WorkerState.QUICK_STOP) -> None:
        """Quick stop of all axes, buffer flushed, alarm raised."""
        self._alarm(code, axis, a, b, f)
        self._flush()
        self.wheel.off()
        self.spindle.quick_stop()
        self.homing.cancel()
        if self.bus is not None:
            self.bus.modes_of_operation[:] = cia402.CSP
        self._set_state(state)

    # ------------------------------------------------------------------ commands
    def poll_command(self) -> None:
        ctl = self.ctl
        seq = int(ctl.cmd_seq)
        if seq == self.cmd_seen:
            return
        self.cmd_seen = seq
        result = self._command(int(ctl.cmd_code), int(ctl.cmd_a), int(ctl.cmd_b))
        ctl.cmd_result[...] = int(result)
        self.lv.cmd_applied[...] = seq       # snapshots published from now on show its effect
        self.publish_now = True
        ctl.cmd_ack[...] = seq

    def _command(self, code: int, a: int, b: int) -> Result:
        st = self.state
        bus = self.bus
        assert bus is not None
        if code == Command.ENABLE:
            if st in (WorkerState.ENABLED, WorkerState.ENABLING):
                return Result.OK
            if (st not in (WorkerState.DISABLED, WorkerState.QUICK_STOP) or self.fault_seen.any()
                    or self.watches.chain_open() or self.watches.blocking_limit()):
                return Result.REFUSED
            self._flush()
            self.fe_count[:] = 0
            bus.modes_of_operation[:] = cia402.CSP
            self.enable_confirmed = 0
            self._set_state(WorkerState.ENABLING)
        elif code == Command.DISABLE:
            self._flush()
            self.wheel.off()
            self.spindle.quick_stop()
            bus.modes_of_operation[:] = cia402.CSP
            self.homing.cancel()
            if st not in (WorkerState.FAULT, WorkerState.FAULT_RESET, WorkerState.ERROR):
                self._set_state(WorkerState.DISABLED)
        elif code == Command.FAULT_RESET:
            self._flush()
            self.spindle.fault_reset()
            self.fault_reset_cycle = 0
            self.wkc_bad_run = 0
            self.wkc_alarmed = False
            self._set_state(WorkerState.FAULT_RESET)
        elif code in (Command.QUICK_STOP, Command.ESTOP):
            self.switch_homer.cancel()
            self._reaction(AlarmCode.ESTOP if code == Command.ESTOP else AlarmCode.QUICK_STOP,
                           state=WorkerState.FAULT if st is WorkerState.FAULT else WorkerState.QUICK_STOP)
        elif code == Command.HOME:
            if st is not WorkerState.ENABLED or self.moving or self.wheel.state or not 0 <= a < self.n \
                    or self.helper.busy:
                return Result.REFUSED
            self._flush()
            position = self.cfg.drives[a].position
            self.homing.begin(a, b)
            self._set_state(WorkerState.HOMING)
            self.helper.submit(_HOMING_METHOD, lambda: bus.sdo_write(position, 0x6098, 0, "<b", b))
        elif code == Command.HOME_SWITCH:
            if (st is not WorkerState.ENABLED or self.moving or self.wheel.state
                    or not self.switch_homer.begin(a, self.words)):
                if self.switch_homer.failure:
                    self._homing_failed()            # an axis cannot home as configured: why
                return Result.REFUSED
            self._flush()
            self._set_state(WorkerState.HOMING)
        elif code == Command.TOUT:
            if not 0 <= a < self.m:
                return Result.REFUSED
            bus.terminal_outputs[a] = b & 0xFFFF_FFFF_FFFF_FFFF      # (an analog word as unsigned)
            self.lv.tout[a] = b
        elif code == Command.OVERRIDE_LIMITS:
            self.watches.override = bool(a)
            self.lv.override[...] = int(bool(a))
        elif code == Command.DOUT:
            if not 0 <= a < self.n or not bus.digital_outputs_mapped(a):
                return Result.REFUSED
            bus.digital_outputs[a] = b       # travels in the next frame (0x60FE:1 in the RxPDO)
            self.lv.dout[a] = b
        elif code == Command.INJECT:
            name_index = b & 0xFF
            if not 0 <= name_index < len(INJECT_NAMES):
                return Result.REFUSED
            try:
                bus.inject(INJECT_NAMES[name_index], a, b >> 8)
            except EtherCATError:
                return Result.REFUSED
        elif code == Command.FLUSH:
            self._flush()
        elif code == Command.REPLACE:
            return replace_queued(self.block, self.cap, a, b)
        elif code == Command.RESET_TRACKING:
            self.tracker.reset()
        elif code == Command.PROBE:
            return self._arm_probe(a, b)
        elif code == Command.HANDWHEEL:
            return self._handwheel(a, b)
        elif code == Command.SPINDLE:      # turning only with the machine's drives on
            rpm, ramp = float(self.ctl.cmd_f[0]), float(self.ctl.cmd_f[1])
            if (rpm != 0.0 and st is not WorkerState.ENABLED) or not self.spindle.command(rpm, ramp):
                return Result.REFUSED
        elif code == Command.COMPENSATE:
            return Result.OK if self.comp.switch(a, bool(b), float(self.ctl.cmd_f[0])) else Result.REFUSED
        elif code == Command.STOP:
            self.stop_requested = True
        else:
            return Result.REFUSED
        return Result.OK

    def _arm_probe(self, word: int, how: int) -> Result:
        """``word``: the input word (a drive's 0x60FD, or n + a terminal's inputs); ``how``: bit 0
        arm (else disarm), bits 1-5 the bit, bit 6 the level that trips. Refused when the input
        reads that level already, or is not mapped."""
        lv = self.lv
        lv.probe_state[...] = 0
        self.probe_axis = -1
        if not how & 1:
            return Result.OK
        bus = self.bus
        if (not 0 <= word < self.n + self.m or bus is None
                or (word < self.n and not bus.maps_object(word, 0x60FD))):
            return Result.REFUSED
        mask, level = 1 << (how >> 1 & 31), how >> 6 & 1
        if (int(self.words[word]) & mask != 0) == bool(level):
            return Result.REFUSED
        self.probe_axis, self.probe_mask, self.probe_level = word, mask, bool(level)
        lv.probe_state[...] = 1
        return Result.OK

    def _handwheel(self, axis: int, mode: int) -> Result:
        """Axis ``axis`` follows the handwheel (``Handwheel.arm``, the reals: scale, v, a, j, lowest,
        highest), refused unless ENABLED with nothing queued; -1: ``Handwheel.release``."""
        wheel = self.wheel
        if axis < 0:
            return Result.OK if wheel.release() else Result.REFUSED
        f, bus = self.ctl.cmd_f, self.bus
        if (self.wheel_terminal < 0 or self.state is not WorkerState.ENABLED or not axis < self.n
                or int(self.ctl.head) > int(self.ctl.tail) or bus is None
                or not wheel.arm(axis, mode, float(f[0]), f[1:6], float(self.ref[axis]),
                                 int(bus.terminal_counts[self.wheel_terminal]))):
            return Result.REFUSED
        return Result.OK

    def _send_ref(self, bus: Bus, row: int) -> None:
        self.comp.command(self.ref, self.cmd, row)
        cia402.units_to_counts(self.cmd, self.gain, self.offset, bus.target_position, self.tmp2)

    def _axis_of(self, position: int) -> int:
        return next((i for i, d in enumerate(self.cfg.drives) if d.position == position), -1)

    # ------------------------------------------------------------------ the cycle
    def cycle(self) -> None:
        """One cycle: commands, outputs, exchange, supervision, tracking. No allocation."""
        bus = self.bus
        assert bus is not None
        self.poll_command()
        lv = self.lv
        ctl = self.ctl
        cycle = int(lv.cycle) + 1
        lv.cycle[...] = cycle
        lv.time_s[...] = cycle * self.cfg.ts_s
        self.state_cycles += 1
        st = self.state
        states = self.states
        # ---- outputs
        if st is WorkerState.ENABLED:
            head = int(ctl.head)
            tail = int(ctl.tail)
            np.copyto(self.prev_ref, self.ref)
            wheel = self.wheel
            if wheel.state is not WheelState.OFF:
                if head > tail:
                    wheel.disarm()               # queued set-points wait until its axis stands
                if not wheel.step(int(bus.terminal_counts[self.wheel_terminal]), self.ref):
                    self._alarm(AlarmCode.HANDWHEEL, wheel.axis, int(WheelFault.JUMP), wheel.fault_counts)
            elif head > tail:
                np.copyto(self.ref, self.ring_rows[tail % self.cap])
                self.gantry.follow(self.ref)     # before judging the motion: the pairs' offsets
                ctl.tail[...] = tail + 1
                lv.consumed[...] = int(lv.consumed) + 1
                np.subtract(self.ref, self.prev_ref, out=self.tmp)
                np.abs(self.tmp, out=self.tmp)
                self.moving = bool(self.tmp.max() > self.eps_units)
            elif self.moving:
                # the ring ran dry while moving: hold the last set-point and say so
                self.moving = False
                lv.underruns[...] = int(lv.underruns) + 1
                self._alarm(AlarmCode.UNDERRUN, -1, int(lv.consumed))
            self.gantry.follow(self.ref)         # (the handwheel's axis may be a gantry's)
            self._send_ref(bus, cycle % REF_HISTORY)
            bus.controlword.fill(cia402.CW_ENABLE_OPERATION)
        elif st is WorkerState.HOMING:
            if self.switch_homer.active:
                np.copyto(self.prev_ref, self.ref)
                if not self.switch_homer.step(self.ref, self.act, self.words):
                    self._homing_failed()
            self._send_ref(bus, cycle % REF_HISTORY)
            bus.controlword.fill(cia402.CW_ENABLE_OPERATION)
            if self.homing.active:
                self.homing.outputs(bus)
        else:
            self._target_from_actual()
            self.comp.hold(cycle % REF_HISTORY)
            if st is WorkerState.ENABLING:
                cia402.ENABLE_LUT.take(states, out=bus.controlword)
            elif st is WorkerState.DISABLED:
                cia402.DISABLE_LUT.take(states, out=bus.controlword)
            elif st is WorkerState.FAULT_RESET:
                self.fault_reset_cycle += 1
                cw = cia402.fault_reset_controlword(self.fault_reset_cycle)
                for i in range(self.n):
                    faulted = states[i] == Cia402State.FAULT
                    bus.controlword[i] = cw if faulted else cia402.DISABLE_LUT[states[i]]
            else:  # QUICK_STOP, FAULT, ERROR
                cia402.QUICK_STOP_LUT.take(states, out=bus.controlword)
        np.copyto(self.ref_rows[cycle % REF_HISTORY], self.ref)
        self.serial_hist[cycle % REF_HISTORY] = int(lv.consumed) - 1
        if self.spindle.present:
            self.spindle.outputs(bus)
        # ---- exchange
        wkc = bus.exchange()
        lv.wkc[...] = wkc
        if wkc != int(lv.wkc_expected):
            self._bad_working_counter(bus, wkc)
            return
        self.wkc_bad_run = 0
        if self.lost_mask and not self.recovery.running:  # every slave answers again
            self.recovery.collect()
            self._alarm(EventCode.SLAVE_RECOVERED, -1, self.lost_mask, self.recovery.recovered)
            self.lost_mask = 0
            self.recovery.recovered = 0
            lv.lost[...] = 0
        # ---- inputs and supervision
        cia402.decode_states(bus.statusword, states, self.scratch_i)
        self._read_actual()
        np.copyto(lv.statusword, bus.statusword)
        np.copyto(lv.error_code, bus.error_code)
        np.copyto(lv.drive_state, states)
        np.copyto(lv.din, bus.digital_inputs)
        np.copyto(self.words_d, bus.digital_inputs, casting="unsafe")
        if self.m:
            np.copyto(self.words_t, bus.terminal_inputs, casting="unsafe")
            np.copyto(lv.tin[:self.m], bus.terminal_inputs, casting="unsafe")
            np.copyto(lv.tcount[:self.m], bus.terminal_counts, casting="unsafe")
        spindle = self.spindle
        if spindle.present:
            spindle.inputs(bus)
            if spindle.fault is not None:
                self._alarm(AlarmCode.SPINDLE, -1, *spindle.fault)
                spindle.fault = None
        watches = self.watches
        if watches.evaluate(self.words) or watches.chain_was_open or watches.override:
            self._watched_inputs()
            self.lv.override[...] = int(watches.override)
        if self.probe_axis >= 0 and (int(self.words[self.probe_axis]) & self.probe_mask != 0) \
                == self.probe_level:
            # latched in the cycle the input is read: where the axes were, and how far along
            # the set-points; the controller stops the motion from there
            np.copyto(lv.probe_pos, self.act)
            lv.probe_consumed[...] = int(lv.consumed)
            lv.probe_state[...] = 2
            self.probe_axis = -1
        # following error against the set-point this actual position answers (bus delay)
        np.subtract(self.ref_rows[(cycle - self.cfg.tracking_delay_cycles) % REF_HISTORY], self.act,
                    out=self.fe)
        # drive faults (FAULT or FAULT REACTION ACTIVE)
        _FAULTED_LUT.take(states, out=self.bool_tmp)
        if self.bool_tmp.any():
            if (not self.startup_reset_tried and cycle * self.cfg.ts_s < STARTUP_RESET_WINDOW_S
                    and (self.state is WorkerState.DISABLED or self.state is WorkerState.ENABLING)):
                self._startup_fault_reset(bus)
            for i in range(self.n):
                if self.bool_tmp[i] and not self.fault_seen[i]:
                    self.fault_seen[i] = True
                    if self.error_code_by_sdo[i]:
                        self._reaction(AlarmCode.DRIVE_FAULT, i, 0, 0, -1.0, state=WorkerState.FAULT)
                        self.error_code_pending.append(i)
                    else:
                        self._reaction(AlarmCode.DRIVE_FAULT, i, int(bus.error_code[i]),
                                       state=WorkerState.FAULT)
            if self.state is not WorkerState.FAULT and self.state is not WorkerState.FAULT_RESET:
                self._set_state(WorkerState.FAULT)
        if self.error_code_pending or self.helper.kind == _ERROR_CODE:
            self._read_error_codes(bus)
        st = self.state
        if st is WorkerState.ENABLED or st is WorkerState.HOMING:
            self._supervise_enabled(bus, st)
        elif st is WorkerState.ENABLING:
            _NOT_ENABLED_LUT.take(states, out=self.bool_tmp)
            # a drive answers a controlword a cycle or more later: OPERATION ENABLED seen right
            # after a disable may be the state from before it. Enabled means seen so for
            # enable_confirm_cycles in a row while enable operation is being sent.
            self.enable_confirmed = 0 if self.bool_tmp.any() else self.enable_confirmed + 1
            if self.enable_confirmed >= self.cfg.enable_confirm_cycles:
                self._hold_actual()
                self.moving = False
                self._set_state(WorkerState.ENABLED)
            elif self.state_cycles * self.cfg.ts_s > self.cfg.enable_timeout_s:
                i = int(np.argmax(self.bool_tmp))
                self._reaction(AlarmCode.ENABLE_TIMEOUT, i, int(states[i]), state=WorkerState.DISABLED)
        elif st is WorkerState.FAULT_RESET:
            _FAULTED_LUT.take(states, out=self.bool_tmp)
            if not self.bool_tmp.any():
                self.fault_seen[:] = False
                self._hold_actual()
                self.enable_confirmed = 0
                self._set_state(WorkerState.ENABLING if self.enable_after_reset else WorkerState.DISABLED)
                self.enable_after_reset = False
            elif self.state_cycles * self.cfg.ts_s > self.cfg.fault_reset_timeout_s:
                i = int(np.argmax(states == Cia402State.FAULT))
                self._alarm(AlarmCode.FAULT_RESET_FAILED, i, int(bus.error_code[i]))
                self._set_state(WorkerState.FAULT)
        if self.state is not WorkerState.ENABLED and self.state is not WorkerState.HOMING:
            np.copyto(self.ref, self.act)
            self.fe.fill(0.0)

    def _watched_inputs(self) -> None:
        """An E-stop chain open or a limit switch active this cycle: the reaction (once; the
        state it leaves refuses enabling until the chain closes or limits are overridden)."""
        st = self.state
        watches = self.watches
        chain = watches.chain_open()
        if chain != watches.chain_was_open:
            watches.chain_was_open = chain
            if chain and st in (WorkerState.ENABLED, WorkerState.ENABLING, WorkerState.HOMING):
                self.switch_homer.cancel()
                self._reaction(AlarmCode.ESTOP_CHAIN)
            elif chain:
                self._alarm(AlarmCode.ESTOP_CHAIN)       # told, though the drives are off already
        if chain:
            return
        if st is not WorkerState.ENABLED and st is not WorkerState.HOMING:
            watches.limit_hit(self.tmp)          # ends an override once no limit reads active
            return
        np.subtract(self.ref, self.prev_ref, out=self.tmp)
        w = watches.limit_hit(self.tmp)
        if w is None:
            return
        if st is WorkerState.HOMING and self.switch_homer.active:
            if not self.switch_homer.limit_tripped(w.axis):
                self._homing_failed()            # (an axis homing with its limits ignored goes on)
            return
        self._reaction(AlarmCode.LIMIT_SWITCH, w.axis, w.side)

    def _homing_failed(self) -> None:
        h = self.switch_homer
        self._reaction(AlarmCode.HOMING_SWITCH, h.failed_axis, int(h.failed_step), h.failure)

    def _startup_fault_reset(self, bus: Bus) -> None:
        """Drives in FAULT as the bus comes up (before anything was commanded) get one fault
        reset, told as an event; a fault that stays is then an alarm as any other."""
        self.startup_reset_tried = True
        # an enable asked for before the fault showed is carried out once the reset worked
        self.enable_after_reset = self.state is WorkerState.ENABLING
        for i in range(self.n):
            if self.bool_tmp[i]:
                known = not self.error_code_by_sdo[i]
                code = int(bus.error_code[i]) if known else 0
                self._alarm(EventCode.STARTUP_FAULT_RESET, i, code, int(known))
                self.fault_seen[i] = True
        self.bool_tmp.fill(False)
        self.fault_reset_cycle = 0
        self._set_state(WorkerState.FAULT_RESET)

    def _read_error_codes(self, bus: Bus) -> None:
        """0x603F of faulted drives that do not map it, one SDO at a time beside the cycle."""
        helper = self.helper
        if helper.busy:
            return
        if helper.kind == _ERROR_CODE:
            axis = self.error_code_axis
            if helper.error:
                self._alarm(EventCode.DRIVE_ERROR_CODE, axis, 0, 0)
            else:
                code = int(helper.value) if isinstance(helper.value, int) else 0
                self.lv.error_code[axis] = code
                bus.error_code[axis] = code
                self._alarm(EventCode.DRIVE_ERROR_CODE, axis, code, 1)
            helper.kind = ""
        if self.error_code_pending:
            axis = self.error_code_pending.pop(0)
            position = self.cfg.drives[axis].position
            self.error_code_axis = axis
            helper.submit(_ERROR_CODE, lambda: bus.sdo_read(position, 0x603F, 0, "<H"))

    def _bad_working_counter(self, bus: Bus, wkc: int) -> None:
        lv = self.lv
        lv.wkc_errors[...] = int(lv.wkc_errors) + 1
        self.wkc_bad_run += 1
        if self.wkc_bad_run == 1:
            self.wkc_alarmed = False       # a new burst may alarm again
        if self.wkc_bad_run > self.cfg.wkc_error_limit and not self.wkc_alarmed:
            self.wkc_alarmed = True
            lost = 0
            for pos in bus.lost_slaves():
                lost |= 1 << min(pos, 62)
            if self.wheel.state is WheelState.LIVE and lost >> self.wheel_slave & 1:
                self._alarm(AlarmCode.HANDWHEEL, self.wheel.axis, int(WheelFault.LOST))
            self._reaction(AlarmCode.WORKING_COUNTER, -1, wkc, lost, float(lv.wkc_expected))
            new = lost & ~self.lost_mask
            self.lost_mask |= lost
            lv.lost[...] = self.lost_mask
            for pos in range(63):
                if new >> pos & 1:
                    self._alarm(AlarmCode.SLAVE_LOST, self._axis_of(pos), pos)
            self.recovery.countdown = 0
        if self.lost_mask:
            self.recovery.attempt(bus.recover_slaves)

    def _supervise_enabled(self, bus: Bus, st: WorkerState) -> None:
        """Following error over its window, drives leaving OPERATION ENABLED, tracking, homing."""
        homing = self.homing
        np.abs(self.fe, out=self.tmp)
        np.greater(self.tmp, self.window, out=self.bool_tmp)
        if st is WorkerState.HOMING and homing.active:
            self.bool_tmp[homing.axis] = False
        np.add(self.fe_count, 1, out=self.fe_count)
        np.multiply(self.fe_count, self.bool_tmp, out=self.fe_count)   # reset where within
        if self.fe_count.max() > self.cfg.following_error_cycles:
            i = int(self.fe_count.argmax())
            self._reaction(AlarmCode.FOLLOWING_ERROR, i, f=float(self.fe[i]))
            return
        if st is WorkerState.ENABLED:
            f = self.gantry.check(self.act)
            if f >= 0:
                self._reaction(AlarmCode.GANTRY_SKEW, f, f=float(self.lv.skew[f]))
                return
            # a drive leaving OPERATION ENABLED on its own (e.g. its quick stop input)
            _NOT_ENABLED_LUT.take(self.states, out=self.bool_tmp)
            if self.bool_tmp.any():
                i = int(np.argmax(self.bool_tmp))
                self._reaction(AlarmCode.DRIVE_FAULT, i, int(bus.error_code[i]), int(self.states[i]) + 1)
            else:
                self._track()
            return
        if not homing.active:
            if st is WorkerState.HOMING and not self.switch_homer.active:
                np.copyto(self.prev_ref, self.ref)       # stopped at the latch: holds there
                self.ref_hist[:] = self.ref
                self._set_state(WorkerState.ENABLED)
            return
        a = homing.axis
        self.ref[a] = self.act[a]
        self.fe[a] = 0.0
        if homing.phase is HomingPhase.WRITING_METHOD:   # 0x6098 being written outside the cycle
            if self.helper.busy:
                return
            result = homing.method_written(bus, self.helper.error)
        else:
            result = homing.inputs(bus)
        if result is HomingResult.FAILED:
            self._alarm(AlarmCode.HOMING_ERROR, a, homing.failure, homing.method)
        if not homing.active:
            self._hold_actual()
            self._set_state(WorkerState.ENABLED)

    def _track(self) -> None:
        """Tracking error per axis against the set-point of ``tracking_delay_cycles`` ago (the
        following error computed in ``cycle``), and its trace row."""
        cycle = int(self.lv.cycle)
        back = (cycle - self.cfg.tracking_delay_cycles) % REF_HISTORY
        self.tracker.add(self.fe)
        if self.trace_cap:
            self.tracker.trace_row(self.ctl, self.trace, cycle, self.ref_rows[back], self.act,
                                   int(self.serial_hist[back]))

    # ------------------------------------------------------------------ running
    def publish(self) -> None:
        self.block.publish()

    def run_manual(self, n_cycles: int) -> None:
        for _ in range(n_cycles):
            self.cycle()
        self.publish()

    def run_realtime(self, default_spin_s: float = 0.0) -> None:
        """The cyclic loop on absolute deadlines until Command.STOP (``clocked.run_clocked``)."""
        run_clocked(self, default_spin_s)
