"""A simulated CiA 402 servo drive (one axis or a spindle): object dictionary, power state
machine, cyclic synchronous position (CSP, mode 8), homing (mode 6), cyclic synchronous
velocity (CSV, mode 9) and profile velocity (PV, mode 3), a position loop over a velocity- and
acceleration-limited motor, encoder quantisation, following-error monitoring, a load that
slows the motor (``set_load``) and fault injection.

Shared by `SimBus` (ethercat/sim_bus.py) and the software EtherCAT slave
(ethercat/emulator): both write the RxPDO values, call `step(dt_s)` once per cycle and
read the TxPDO values; SDOs go through `read_object` / `write_object`. Keep this API
stable; it is what the emulator codes against.

Process data (hot path; plain attributes and properties, no allocation):
    model.controlword = 0x0F            # 0x6040, uint16
    model.target_position = 12345       # 0x607A, int32 counts
    model.modes_of_operation = 8        # 0x6060, int8
    model.target_velocity = 50_000      # 0x60FF, int32 counts/s (modes 9 and 3)
    model.step(0.001)                   # advance the drive by dt_s
    model.statusword                    # 0x6041, uint16
    model.position_actual               # 0x6064, int32 counts (quantised encoder)
    model.following_error_actual        # 0x60F4, int32 counts = demand - actual
    model.error_code                    # 0x603F, uint16 (0 = no fault)
    model.modes_of_operation_display    # 0x6061, int8

Object dictionary (SDO): `OBJECTS` lists every object (index, subindex, type, access);
`read_object(index, subindex)` returns an int, `write_object(index, subindex, value)`
range-checks and stores; errors are `SdoAbortError` with the CiA 301 abort code, for the
emulator to send as an SDO abort. `encode_object` / `decode_object` turn values into
the little-endian bytes of the object's type.

Faults: `inject_fault(error_code)` (e.g. 0x2310 over-current; `persistent=True` keeps it
until `clear_fault()`), `set_jam(True)` (the load is blocked: the following error grows
until the drive's own following-error monitor trips with 0x8611), `watchdog_expired()`
(process data lost: fault 0x8700).

Dynamics (per `step`, sub-stepped at <= 1 ms): velocity command = feed-forward of the
demand + kp * (demand - position); the motor follows it with a first-order lag
`velocity_lag_s`, limited to `a_max_counts_s2` and `v_max_counts_s`; CSP targets are
interpolated linearly over the cycle. The encoder reads the nearest multiple of
`encoder_resolution_counts`. The encoder gives a zero impulse (index) every
`index_pitch_counts` (0: none), which touch probe 1 (0x60B8/0x60B9/0x60BA) latches when its
function selects the zero impulse and the positive edge. With the defaults (kp 200 1/s,
90 % velocity feed-forward) the following error is about 0.1 * v / kp: 7.5 um at 15 mm/s,
the order of the paper's Table 4 (RMSE 1-40 um).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .cia402 import (
    CW_FAULT_RESET,
    CW_HOMING_START,
    STATE_STATUSWORD,
    SW_FOLLOWING_ERROR,
    SW_HOMING_ATTAINED,
    SW_HOMING_ERROR,
    SW_INTERNAL_LIMIT,
    SW_OP_SPECIFIC_12,
    SW_REMOTE,
    SW_TARGET_REACHED,
    SW_VOLTAGE_ENABLED,
    TP_CONTINUOUS,
    TP_ENABLE,
    TP_ENABLED,
    TP_POSITIVE_EDGE,
    TP_POSITIVE_STORED,
    Cia402State,
    ModeOfOperation,
)
from .errors import SdoAbortError
from .object_dictionary import (
    ERROR_FOLLOWING,
    ERROR_OVERCURRENT,
    ERROR_SYNC,
    OBJECT_INDICES,
    OBJECTS,
    ObjectEntry,
    wrap,
)

S = Cia402State
# the states in which the drive controls its position and reports a following error
_FE_STATES = frozenset((S.OPERATION_ENABLED, S.QUICK_STOP_ACTIVE, S.FAULT_REACTION_ACTIVE))

@dataclass(frozen=True, slots=True)
class DriveParams:
    """Servo model parameters, in drive counts and seconds.

    Use `DriveParams.for_axis(counts_per_unit, ...)` to give motor limits in axis units.
    """

    vendor_id: int = 0x0000_0A5E
    product_code: int = 0x0402_0001
    revision: int = 1
    serial: int = 0
    kp_1_s: float = 200.0                  # position loop gain
    velocity_feedforward: float = 0.9      # fraction of the demand velocity fed forward
    velocity_lag_s: float = 0.0015         # motor/velocity loop first-order lag
    v_max_counts_s: float = 3.0e6          # motor speed limit (300 mm/s at 10,000 counts/mm)
    a_max_counts_s2: float = 3.0e8         # motor acceleration limit (30,000 mm/s^2)
    encoder_resolution_counts: int = 1     # quantisation step of 0x6064
    initial_position_counts: float = 0.0
    following_error_window_counts: int = 0xFFFF_FFFF   # 0x6065 default: monitor off
    following_error_timeout_ms: int = 10                # 0x6066
    quick_stop_deceleration_counts_s2: int = 100_000_000  # 0x6085
    quick_stop_option_code: int = 2        # 0x605A: 2 = ramp, then SWITCH ON DISABLED
    fault_reaction_s: float = 0.005        # time spent in FAULT REACTION ACTIVE (at least)
    home_switch_counts: float = 0.0        # where the home switch edge is (motor counts)
    homing_max_travel_counts: float = 1e9  # homing error when the switch is not found
    index_pitch_counts: float = 0.0        # the encoder's zero impulse every this many counts (0: none)
    index_phase_counts: float = 0.0        # where one of them is (motor counts)
    substep_s: float = 0.001               # largest integration step
    # behaviours of third-party drives the master must cope with (off by default)
    fault_at_power_up: int = 0             # error code the drive starts in FAULT with (0: none)
    mode_display_delay_s: float = 0.0      # 0x6061 follows 0x6060 this long after it changed
    enable_target_window_counts: int = 0   # >0: enabling with |target - actual| above it is a
                                           # following error fault (drives that jump to a stale target)

    @classmethod
    def for_axis(cls, counts_per_unit: float, v_max_units_s: float = 300.0,
                 a_max_units_s2: float = 30_000.0, following_error_window_units: float | None = None,
                 **kwargs: object) -> DriveParams:
        """Parameters for an axis with `counts_per_unit` counts per mm (or degree)."""
        window = (0xFFFF_FFFF if following_error_window_units is None
                  else min(0xFFFF_FFFF, int(round(following_error_window_units * counts_per_unit))))
        return cls(v_max_counts_s=v_max_units_s * counts_per_unit,
                   a_max_counts_s2=a_max_units_s2 * counts_per_unit,
                   quick_stop_deceleration_counts_s2=int(min(0xFFFF_FFFF, a_max_units_s2 * counts_per_unit)),
                   following_error_window_counts=window, **kwargs)  # type: ignore[arg-type]


class DriveModel:
    """One simulated CiA 402 servo drive. See the module docstring for the API."""

    def __init__(self, params: DriveParams | None = None, position: int = 0) -> None:
        p = params if params is not None else DriveParams()
        self.params = p
        self.position = position   # slave position, used in SDO abort messages
        # RxPDO (written by the master)
        self.controlword = 0
        self.target_position = int(round(p.initial_position_counts))
        self.modes_of_operation = 0
        self.digital_outputs = 0
        self.digital_inputs = 0          # 0x60FD: limit switches, home switch, probe (bits 0-2, 16+)
        self.touch_probe_function = 0    # 0x60B8 (touch probe 1: bits 0, 1, 2-3, 4)
        self.target_velocity = 0         # 0x60FF, counts/s (modes 3 and 9)
        # touch probe 1: status 0x60B9 (bit 0 enabled, bit 1 positive edge stored), its value
        # 0x60BA, and the function it was armed with (re-armed when that changes)
        self.touch_probe_status = 0
        self.touch_probe_value = 0
        self._tp_armed_with = 0
        # Parameters (SDO)
        self._rw: dict[tuple[int, int], int] = {
            (0x605A, 0): p.quick_stop_option_code,
            (0x6065, 0): p.following_error_window_counts,
            (0x6066, 0): p.following_error_timeout_ms,
            (0x607C, 0): 0,
            (0x6085, 0): p.quick_stop_deceleration_counts_s2,
            (0x6098, 0): 35,
            (0x6099, 1): int(min(0xFFFF_FFFF, p.v_max_counts_s * 0.05)),
            (0x6099, 2): int(min(0xFFFF_FFFF, p.v_max_counts_s * 0.005)),
            (0x609A, 0): int(min(0xFFFF_FFFF, p.a_max_counts_s2 * 0.1)),
            (0x606D, 0): int(min(0xFFFF, max(1.0, p.v_max_counts_s * 0.01))),
            (0x6083, 0): int(min(0xFFFF_FFFF, p.a_max_counts_s2 * 0.1)),
            (0x6084, 0): int(min(0xFFFF_FFFF, p.a_max_counts_s2 * 0.1)),
        }
        # State
        self.state = S.NOT_READY_TO_SWITCH_ON
        self.modes_of_operation_display = 0
        self.error_code = 0
        self._motor_counts = float(p.initial_position_counts)   # true shaft position
        self._velocity_counts_s = 0.0
        self._offset_counts = 0           # position actual = encoder + offset (set by homing)
        self._demand_counts = self._motor_counts
        self._prev_demand_counts = self._motor_counts
        self._csp_start_counts = self._motor_counts
        self._fe_time_s = 0.0
        self._fault_pending = p.fault_at_power_up
        self._persistent_fault = 0
        self._mode_requested = 0
        self._mode_since_s = 0.0
        self._jammed = False
        self._fra_time_s = 0.0
        self._prev_fault_reset_bit = False
        self._prev_homing_bit = False
        self._following_error_flag = False
        self._internal_limit = False
        # homing: phase 0 idle, 1 search switch, 2 search edge back, 3 decelerate, 4 done, 5 error
        self._homing_phase = 0
        self._homing_velocity = 0.0
        self._homing_start_counts = 0.0
        self._homing_edge_counts = 0.0
        self._pv_ref = 0.0                # profile velocity mode: the ramped velocity demand
        self._load_cap = math.inf         # a load holds the motor at or below this speed
        self.time_s = 0.0

    # ------------------------------------------------------------------ process data
    @property
    def position_actual(self) -> int:
        """0x6064: quantised encoder position plus the homing offset, int32 counts."""
        res = self.params.encoder_resolution_counts
        return int(math.floor(self._motor_counts / res + 0.5)) * res + self._offset_counts

    @property
    def position_demand(self) -> int:
        """0x6062: the position the drive is currently controlling to, counts."""
        return int(round(self._demand_counts)) + self._offset_counts

    @property
    def following_error_actual(self) -> int:
        """0x60F4: position demand - position actual, counts."""
        if self.state not in _FE_STATES:
            return 0
        return self.position_demand - self.position_actual

    def process_inputs(self) -> tuple[int, int, int]:
        """(statusword, position actual, following error actual) as the TxPDO carries them,
        the position computed once for both."""
        actual = self.position_actual
        fe = self.position_demand - actual if self.state in _FE_STATES else 0
        return self.statusword, actual, fe

    @property
    def velocity_actual(self) -> int:
        """0x606C in counts/s."""
        return int(round(self._velocity_counts_s))

    @property
    def statusword(self) -> int:
        """0x6041 composed from the state and the mode-specific bits."""
        sw = STATE_STATUSWORD.get(self.state, 0) | SW_REMOTE
        if self.state not in (S.NOT_READY_TO_SWITCH_ON, S.SWITCH_ON_DISABLED):
            sw |= SW_VOLTAGE_ENABLED
        if self._internal_limit:
            sw |= SW_INTERNAL_LIMIT
        if self.state is S.OPERATION_ENABLED:
            mode = self.modes_of_operation_display
            if mode == ModeOfOperation.CYCLIC_SYNC_VELOCITY:
                sw |= SW_OP_SPECIFIC_12            # drive follows the command value
            elif mode == ModeOfOperation.PROFILE_VELOCITY:
                if abs(self._velocity_counts_s - self.target_velocity) <= self._rw[(0x606D, 0)]:
                    sw |= SW_TARGET_REACHED
            if self.modes_of_operation_display == ModeOfOperation.CYCLIC_SYNC_POSITION:
                sw |= SW_OP_SPECIFIC_12            # drive follows the command value
                if self._following_error_flag:
                    sw |= SW_FOLLOWING_ERROR
            elif self.modes_of_operation_display == ModeOfOperation.HOMING:
                if self._homing_phase == 4:
                    sw |= SW_HOMING_ATTAINED | SW_TARGET_REACHED
                elif self._homing_phase == 5:
                    sw |= SW_HOMING_ERROR | SW_TARGET_REACHED
                elif self._homing_phase == 0:
                    sw |= SW_TARGET_REACHED
        return sw

    @property
    def motor_position_counts(self) -> float:
        """True (unquantised) shaft position including the homing offset, counts."""
        return self._motor_counts + self._offset_counts

    @property
    def velocity_counts_s(self) -> float:
        return self._velocity_counts_s

    @property
    def homing_phase(self) -> int:
        """0 idle, 1 searching the switch, 2 searching the edge, 3 stopping, 4 attained, 5 error."""
        return self._homing_phase

    # ------------------------------------------------------------------ faults
    def inject_fault(self, error_code: int = ERROR_OVERCURRENT, persistent: bool = False) -> None:
        """Trip a drive fault at the next `step` (FAULT REACTION ACTIVE, then FAULT).

        `persistent=True`: fault reset does not clear it until `clear_fault()`.
        """
        self._fault_pending = error_code
        if persistent:
            self._persistent_fault = error_code

    def clear_fault(self) -> None:
        """Remove the cause of a persistent injected fault (a reset is still needed)."""
        self._persistent_fault = 0

    def set_jam(self, jammed: bool) -> None:
        """Block (or free) the load: the motor cannot move, the following error grows."""
        self._jammed = jammed
        if jammed:
            self._velocity_counts_s = 0.0

    def set_load(self, max_speed_counts_s: float | None) -> None:
        """A load on the motor (a spindle bogged down in the cut): it turns at most this fast
        whatever it is commanded (None: no load)."""
        self._load_cap = math.inf if max_speed_counts_s is None else abs(float(max_speed_counts_s))

    def watchdog_expired(self) -> None:
        """Process data stopped arriving (SM watchdog): fault with error code 0x8700."""
        if self.state not in (S.FAULT, S.FAULT_REACTION_ACTIVE):
            self._fault_pending = ERROR_SYNC

    # ------------------------------------------------------------------ SDO
    def _entry(self, index: int, subindex: int) -> ObjectEntry:
        entry = OBJECTS.get((index, subindex))
        if entry is None:
            code = (SdoAbortError.SUBINDEX_DOES_NOT_EXIST if index in OBJECT_INDICES
                    else SdoAbortError.OBJECT_DOES_NOT_EXIST)
            raise SdoAbortError(self.position, index, subindex, code)
        return entry

    def object_entry(self, index: int, subindex: int = 0) -> ObjectEntry:
        """The entry of an object, or `SdoAbortError` (0x06020000 / 0x06090011)."""
        return self._entry(index, subindex)

    def read_object(self, index: int, subindex: int = 0) -> int:
        """SDO upload of one object as an int (`SdoAbortError` if it does not exist)."""
        self._entry(index, subindex)
        p = self.params
        key = (index, subindex)
        live = {
            (0x1000, 0): 0x0002_0192,     # CiA 402 servo drive
            (0x1018, 0): 4,
            (0x1018, 1): p.vendor_id,
            (0x1018, 2): p.product_code,
            (0x1018, 3): p.revision,
            (0x1018, 4): p.serial,
            (0x603F, 0): self.error_code,
            (0x6040, 0): self.controlword,
            (0x6041, 0): self.statusword,
            (0x6060, 0): self.modes_of_operation,
            (0x6061, 0): self.modes_of_operation_display,
            (0x6062, 0): self.position_demand,
            (0x6064, 0): self.position_actual,
            (0x606C, 0): self.velocity_actual,
            (0x607A, 0): self.target_position,
            (0x60FF, 0): self.target_velocity,
            (0x6099, 0): 2,
            (0x60F4, 0): self.following_error_actual,
            (0x60B8, 0): self.touch_probe_function,
            (0x60B9, 0): self.touch_probe_status,
            (0x60BA, 0): self.touch_probe_value,
            (0x60FD, 0): self.digital_inputs,
            (0x60FE, 0): 1,
            (0x60FE, 1): self.digital_outputs,
        }
        if key in live:
            return wrap(live[key], OBJECTS[key])
        return self._rw[key]

    def write_object(self, index: int, subindex: int, value: int) -> None:
        """SDO download of one object (`SdoAbortError`: read only, value range, missing)."""
        entry = self._entry(index, subindex)
        if entry.access != "rw":
            raise SdoAbortError(self.position, index, subindex, SdoAbortError.READ_ONLY)
        if not entry.check_range(int(value)):
            raise SdoAbortError(self.position, index, subindex, SdoAbortError.VALUE_RANGE,
                                f"{value} out of range for {entry.data_type}")
        value = int(value)
        if index == 0x6040:
            self.controlword = value
        elif index == 0x607A:
            self.target_position = value
        elif index == 0x60FF:
            self.target_velocity = value
        elif index == 0x6060:
            self.modes_of_operation = value
        elif index == 0x60FE:
            self.digital_outputs = value
        elif index == 0x60B8:
            self.touch_probe_function = value
        else:
            self._rw[(index, subindex)] = value

    # ------------------------------------------------------------------ cyclic
    def step(self, dt_s: float) -> None:
        """Advance the drive by `dt_s`: state machine on the current controlword, then the
        mode's demand and the motor (sub-stepped at `params.substep_s`)."""
        self._update_state_machine()
        n = max(1, int(math.ceil(dt_s / self.params.substep_s - 1e-9)))
        h = dt_s / n
        self._csp_start_counts = self._demand_counts
        if self.touch_probe_function != self._tp_armed_with:
            self._arm_touch_probe()
        before = self._motor_counts
        for j in range(n):
            self._step_motion(h, (j + 1) / n)
        if self.touch_probe_status & TP_ENABLED:
            self._sample_index(before)
        self.time_s += dt_s

    # ------------------------------------------------------------------ touch probe 1
    def _arm_touch_probe(self) -> None:
        """A new 0x60B8: touch probe 1 on (its stored edge cleared) or off. The model samples
        the encoder's zero impulse at the positive edge (bits 2-3 = 01, bit 4), first event or
        continuous (bit 1); the probe input as the source (bits 2-3 = 00) is the worker's own
        latch of 0x60FD here, so the model leaves it enabled and never triggered."""
        f = self.touch_probe_function
        self._tp_armed_with = f
        self.touch_probe_status = TP_ENABLED if f & TP_ENABLE else 0

    def _sample_index(self, before: float) -> None:
        """The positive-edge latch of touch probe 1 on a zero impulse passed in this step:
        the position actual (0x6064's coding) where the index lies."""
        f = self.touch_probe_function
        pitch = self.params.index_pitch_counts
        if pitch <= 0.0 or (f >> 2) & 3 != 1 or not f & TP_POSITIVE_EDGE:
            return
        if self.touch_probe_status & TP_POSITIVE_STORED and not f & TP_CONTINUOUS:
            return                                       # first event: kept until re-armed
        phase = self.params.index_phase_counts
        k0 = math.floor((before - phase) / pitch)
        k1 = math.floor((self._motor_counts - phase) / pitch)
        if k0 == k1:
            return
        at = phase + pitch * max(k0, k1)
        res = self.params.encoder_resolution_counts
        self.touch_probe_value = int(math.floor(at / res + 0.5)) * res + self._offset_counts
        self.touch_probe_status = TP_ENABLED | TP_POSITIVE_STORED

    def _trip(self, code: int) -> None:
        self.error_code = code
        self._fault_pending = 0
        self._fra_time_s = 0.0
        self.state = S.FAULT_REACTION_ACTIVE

    def _update_state_machine(self) -> None:
        cw = self.controlword
        st = self.state
        if st is S.OPERATION_ENABLED and (cw & 0x8F) == 0x0F and not self._fault_pending:
            self._prev_fault_reset_bit = False
            return                                           # fast path: stays enabled
        fault_reset_edge = bool(cw & CW_FAULT_RESET) and not self._prev_fault_reset_bit
        self._prev_fault_reset_bit = bool(cw & CW_FAULT_RESET)
        if self._fault_pending and st not in (S.FAULT, S.FAULT_REACTION_ACTIVE):
            self._trip(self._fault_pending)
            return
        if st is S.NOT_READY_TO_SWITCH_ON:
            self.state = S.SWITCH_ON_DISABLED                # transition 1 (self test done)
            return
        if st is S.FAULT_REACTION_ACTIVE:
            return                                           # left in _step_motion when stopped
        if st is S.FAULT:
            if fault_reset_edge and not self._persistent_fault:
                self.error_code = 0
                self._fault_pending = 0
                self.state = S.SWITCH_ON_DISABLED            # transition 15
            return
        if cw & CW_FAULT_RESET:
            return                                           # bit 7 set: no other command
        cmd = cw & 0x8F
        disable_voltage = not (cw & 0x02)
        quick_stop = (cw & 0x06) == 0x02
        shutdown = (cw & 0x87) == 0x06
        switch_on = cmd == 0x07
        enable = cmd == 0x0F
        if st is S.SWITCH_ON_DISABLED:
            if shutdown:
                self.state = S.READY_TO_SWITCH_ON            # 2
        elif st is S.READY_TO_SWITCH_ON:
            if disable_voltage or quick_stop:
                self.state = S.SWITCH_ON_DISABLED            # 7
            elif switch_on:
                self.state = S.SWITCHED_ON                   # 3
            elif enable:
                self.state = S.SWITCHED_ON                   # 3, then 4 next cycle
        elif st is S.SWITCHED_ON:
            if disable_voltage or quick_stop:
                self.state = S.SWITCH_ON_DISABLED            # 10
            elif shutdown:
                self.state = S.READY_TO_SWITCH_ON            # 6
            elif enable:
                self._enter_operation_enabled()              # 4
        elif st is S.OPERATION_ENABLED:
            if disable_voltage:
                self.state = S.SWITCH_ON_DISABLED            # 9
            elif quick_stop:
                self.state = S.QUICK_STOP_ACTIVE             # 11
            elif shutdown:
                self.state = S.READY_TO_SWITCH_ON            # 8
            elif switch_on:
                self.state = S.SWITCHED_ON                   # 5
        elif st is S.QUICK_STOP_ACTIVE:
            if self._velocity_counts_s == 0.0 and self._rw[(0x605A, 0)] in (1, 2, 3, 4):
                self.state = S.SWITCH_ON_DISABLED            # 12 (automatic once stopped)
            elif disable_voltage:
                self.state = S.SWITCH_ON_DISABLED            # 12
            elif enable and self._rw[(0x605A, 0)] in (5, 6, 7, 8) and self._velocity_counts_s == 0.0:
                self._enter_operation_enabled()              # 16

    def _enter_operation_enabled(self) -> None:
        window = self.params.enable_target_window_counts
        if (window and self.modes_of_operation == ModeOfOperation.CYCLIC_SYNC_POSITION
                and abs(self.target_position - self.position_actual) > window):
            self._trip(ERROR_FOLLOWING)
            return
        self.state = S.OPERATION_ENABLED
        self._demand_counts = self._motor_counts
        self._prev_demand_counts = self._motor_counts
        self._csp_start_counts = self._motor_counts
        self._fe_time_s = 0.0
        self._pv_ref = self._velocity_counts_s
        self._prev_homing_bit = bool(self.controlword & CW_HOMING_START)

    def _decelerate(self, decel_counts_s2: float, h: float) -> None:
        v = self._velocity_counts_s
        dv = decel_counts_s2 * h
        v = 0.0 if abs(v) <= dv else v - math.copysign(dv, v)
        self._velocity_counts_s = v
        self._motor_counts += v * h
        self._demand_counts = self._motor_counts
        self._prev_demand_counts = self._motor_counts

    def _step_motion(self, h: float, frac: float) -> None:
        """One sub-step of length h; `frac` = how far through the cycle its end is (CSP
        targets are interpolated linearly over the cycle, as drives do)."""
        p = self.params
        st = self.state
        if self.modes_of_operation != self._mode_requested:
            self._mode_requested = self.modes_of_operation
            self._mode_since_s = self.time_s
        if self.time_s - self._mode_since_s >= p.mode_display_delay_s:
            self.modes_of_operation_display = self.modes_of_operation
        self._internal_limit = False
        if self._jammed:
            self._velocity_counts_s = 0.0
        if st is S.FAULT_REACTION_ACTIVE:
            self._decelerate(float(self._rw[(0x6085, 0)]), h)
            self._fra_time_s += h
            if self._velocity_counts_s == 0.0 and self._fra_time_s >= p.fault_reaction_s - 1e-12:
                self.state = S.FAULT                         # 14
            return
        if st is S.QUICK_STOP_ACTIVE:
            self._decelerate(float(self._rw[(0x6085, 0)]), h)
            return
        if st is not S.OPERATION_ENABLED:
            # power stage off: the holding brake stops the motor
            self._decelerate(p.a_max_counts_s2, h)
            self._homing_phase = 0 if self._homing_phase in (1, 2, 3) else self._homing_phase
            return
        mode = self.modes_of_operation_display
        if mode == ModeOfOperation.CYCLIC_SYNC_VELOCITY or mode == ModeOfOperation.PROFILE_VELOCITY:
            self._velocity_mode(h, mode == ModeOfOperation.PROFILE_VELOCITY)
            return
        if mode == ModeOfOperation.CYCLIC_SYNC_POSITION:
            start = self._csp_start_counts
            demand = start + (float(self.target_position - self._offset_counts) - start) * frac
        elif mode == ModeOfOperation.HOMING:
            demand = self._homing_demand(h)
        else:
            demand = self._demand_counts                     # unsupported mode: hold
        self._prev_demand_counts = self._demand_counts
        self._demand_counts = demand
        self._servo(h)
        # following error monitor (0x6065 window, 0x6066 time out)
        window = self._rw[(0x6065, 0)]
        fe = abs(self._demand_counts - self._motor_counts)
        if window != 0xFFFF_FFFF and fe > window:
            self._following_error_flag = True
            self._fe_time_s += h
            if self._fe_time_s * 1000.0 > self._rw[(0x6066, 0)] + 1e-9:
                self._trip(ERROR_FOLLOWING)
        else:
            self._following_error_flag = False
            self._fe_time_s = 0.0

    def _velocity_mode(self, h: float, profile: bool) -> None:
        """Modes 9 and 3: the motor follows 0x60FF, at once (cyclic synchronous velocity) or
        along a ramp at 0x6083 up and 0x6084 down (profile velocity), within its own limits
        and a load's; the position demand follows the motor (no following error)."""
        p = self.params
        target = float(self.target_velocity)
        if profile:
            r = self._pv_ref
            up = abs(target) > abs(r) and target * r >= 0.0
            rate = float(self._rw[(0x6083 if up else 0x6084, 0)]) * h
            r = target if abs(target - r) <= rate else r + math.copysign(rate, target - r)
            self._pv_ref = target = r
        cap = min(p.v_max_counts_s, self._load_cap)
        if abs(target) > cap:
            target = math.copysign(cap, target)
            self._internal_limit = True
        v = self._velocity_counts_s
        a = max(-p.a_max_counts_s2, min(p.a_max_counts_s2, (target - v) / max(p.velocity_lag_s, h)))
        v_new = 0.0 if self._jammed else v + a * h
        self._motor_counts += 0.5 * (v + v_new) * h
        self._velocity_counts_s = v_new
        self._demand_counts = self._prev_demand_counts = self._motor_counts

    def _servo(self, h: float) -> None:
        """Position loop (P + velocity feed-forward) over a lagging, limited motor."""
        p = self.params
        # the demand moves from prev to current over this sub-step: P term on the error at its
        # start, velocity feed-forward of the interpolated demand
        v_ff = (self._demand_counts - self._prev_demand_counts) / h
        v_cmd = p.velocity_feedforward * v_ff + p.kp_1_s * (self._prev_demand_counts - self._motor_counts)
        if v_cmd > p.v_max_counts_s:
            v_cmd = p.v_max_counts_s
            self._internal_limit = True
        elif v_cmd < -p.v_max_counts_s:
            v_cmd = -p.v_max_counts_s
            self._internal_limit = True
        v = self._velocity_counts_s
        a = (v_cmd - v) / max(p.velocity_lag_s, h)
        if a > p.a_max_counts_s2:
            a = p.a_max_counts_s2
            self._internal_limit = True
        elif a < -p.a_max_counts_s2:
            a = -p.a_max_counts_s2
            self._internal_limit = True
        if self._jammed:
            self._velocity_counts_s = 0.0
            return
        v_new = v + a * h
        self._motor_counts += 0.5 * (v + v_new) * h
        self._velocity_counts_s = v_new

    # ------------------------------------------------------------------ homing (mode 6)
    def _homing_demand(self, h: float) -> float:
        """Demand position of the homing procedure (method from 0x6098).

        Methods 35 and 37: the current position becomes the home offset (0x607C) at once.
        Other methods: search the home switch edge at `params.home_switch_counts`, towards
        negative for odd methods and positive for even ones, at speed 0x6099:1, come back
        over the edge at 0x6099:2, set position actual = home offset there, and stop.
        """
        bit = bool(self.controlword & CW_HOMING_START)
        start = bit and not self._prev_homing_bit
        self._prev_homing_bit = bit
        demand = self._demand_counts
        method = self._rw[(0x6098, 0)]
        if not bit and self._homing_phase in (1, 2, 3):
            self._homing_phase = 0            # bit 4 cleared: homing interrupted
            self._homing_velocity = 0.0
        if start:
            if method in (35, 37):
                self._set_home_at(self._motor_counts)
                self._homing_phase = 4
                return self._motor_counts
            self._homing_phase = 1
            self._homing_velocity = 0.0
            self._homing_start_counts = self._motor_counts
        phase = self._homing_phase
        if phase not in (1, 2, 3):
            return demand
        acc = float(self._rw[(0x609A, 0)])
        sign = -1.0 if method % 2 else 1.0
        switch = self.params.home_switch_counts
        if phase == 1:
            v_target = sign * float(self._rw[(0x6099, 1)])
            if (demand - switch) * sign >= 0.0:       # crossed the switch edge
                self._homing_phase = phase = 2
            elif abs(demand - self._homing_start_counts) > self.params.homing_max_travel_counts:
                self._homing_phase = 5
                self._homing_velocity = 0.0
                return demand
        if phase == 2:
            v_target = -sign * float(self._rw[(0x6099, 2)])
            if (demand - switch) * sign < 0.0:         # back over the edge: home found here
                self._homing_edge_counts = demand
                self._homing_phase = phase = 3
        if phase == 3:
            v_target = 0.0
        v = self._homing_velocity
        dv = acc * h
        v = v_target if abs(v_target - v) <= dv else v + math.copysign(dv, v_target - v)
        self._homing_velocity = v
        demand += v * h
        if phase == 3 and v == 0.0:
            # home offset applies at the edge; the motor stopped a little past it
            self._set_home_at(self._homing_edge_counts)
            self._homing_phase = 4
        return demand

    def _set_home_at(self, motor_counts_at_home: float) -> None:
        res = self.params.encoder_resolution_counts
        enc = int(math.floor(motor_counts_at_home / res + 0.5)) * res
        self._offset_counts = self._rw[(0x607C, 0)] - enc
