"""SimBus: the `Bus` interface over simulated CiA 402 servo drives (`drive_model.DriveModel`).

Seen from above it behaves like `SoemBus` in OP: `exchange()` latches each drive's inputs
(as the LRW passes the slave), hands it the outputs, advances every drive by
`cycle_time_s` of simulated time and returns the working counter of one LRW (3 per drive).
So the inputs show the drive's reaction to outputs one cycle later, as on a real bus.
Simulated time advances per `exchange()`, not with the wall clock, so tests can run many
cycles faster than real time and the worker runs it in real time.

Fault injection (the same names work through `CyclicWorker.inject` in every worker mode):
    inject_drive_fault(i, error_code=0x2310, persistent=False)  drive i trips a fault
    inject_following_error(i, jammed=True)   drive i's load is blocked -> 0x8611 fault
    drop_frames(n)                           the next n frames are lost (wkc -1, inputs stale)
    lose_slave(i) / restore_slave(i)         drive i stops answering (wkc - 3); after
                                             `watchdog_s` without process data it faults 0x8700
    restore_slave(i, power_cycled=True)      drive i is back but in INIT (as after a power
                                             cycle): silent until `recover_slaves()`
    set_probe_surface(i, bit, level, below, input_drive)
                                             a probe wired to bit `bit` of a drive's digital
                                             inputs (0x60FD; axis i's own by default) touches
                                             a surface: the bit is on while axis i (its units,
                                             not counts) is at or below `level` (above, when
                                             not `below`)
    set_probe_part(part, axes, bit, input_drive)
                                             the same probe touches a simulated workpiece
                                             (`sim_part.SimPart`: a block, a bore, a boss) with
                                             a ball-ended stylus; the bit is on while it or the
                                             surface above touches
Terminals and the simulated machine's switches and buttons (``ethercat.sim_io``):
    terminal_input k, input_value(bit, level[, release])   force (or release) a terminal input
    drive_input i, input_value(...)                         the same on a drive's 0x60FD
    encoder_add k, n                                        an encoder terminal counts n more
    lose_terminal k / restore_terminal k                    terminal k stops answering / is back,
                                                            powered again (an encoder counts from 0)
Spindle drives (``spindles``, each a `DriveModel` in a velocity mode):
    spindle_load k, rpm / spindle_unload k                  a load holds spindle k at or below
                                                            rpm (it loses speed in the cut) / lets go
    spindle_fault k, code                                   spindle k's drive trips a fault
Limits: no AL state machine beyond that (OP while open), no DC, SDOs are instantaneous.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import replace

import numpy as np

from .bus import Bus, DriveSpec, SlaveInfo, SpindleDriveSpec
from .drive_model import DriveModel, DriveParams
from .errors import ConfigurationError, SdoAbortError
from .object_dictionary import ERROR_OVERCURRENT, OBJECTS, decode_object, encode_object
from .sim_io import SimIo, SimSwitch
from .sim_part import PART_VALUES, SimPart
from .terminals import TerminalSpec

#: injection names accepted by `SimBus.inject`
INJECTIONS = ("drive_fault", "persistent_fault", "clear_fault", "jam", "unjam", "drop_frames",
              "lose_slave", "restore_slave", "probe_surface", "probe_off", "probe_part_value", "probe_part",
              "probe_part_off", "terminal_input", "drive_input", "encoder_add", "lose_terminal",
              "restore_terminal", "spindle_load", "spindle_unload", "spindle_fault")
#: ``inject("probe_surface", i, value)``: value = ``probe_surface_value(...)``
PROBE_SURFACE_SCALE = 1e6


def probe_part_values(part: SimPart, axes: tuple[int, int, int], bit: int, input_drive: int
                      ) -> list[tuple[str, int, int]]:
    """The injections (name, index, value) that place ``part`` (its numbers one by one, then
    the axes X, Y, Z are drives ``axes`` and the probe is bit ``bit`` of ``input_drive``'s
    inputs)."""
    out = [("probe_part_value", 0, k | int(round(v * PROBE_SURFACE_SCALE)) << 5)
           for k, v in enumerate(part.values())]
    x, y, z = axes
    out.append(("probe_part", 0, (int(bit) & 31) | (int(input_drive) & 63) << 5 | (x & 63) << 11
                | (y & 63) << 17 | (z & 63) << 23))
    return out


def probe_surface_value(bit: int, level_units: float, below: bool = True, input_drive: int = -1) -> int:
    """The ``value`` of ``inject("probe_surface", axis, value)``: the probe on bit ``bit`` of
    drive ``input_drive``'s inputs (-1: the axis' own drive) touching while the axis is at or
    below ``level_units`` (above when not ``below``), packed into one integer."""
    return (int(bit) & 31 | int(below) << 5 | (int(input_drive) + 1 & 63) << 6
            | int(round(level_units * PROBE_SURFACE_SCALE)) << 12)


class SimBus(Bus):
    """Simulated bus. `drive_params`: one `DriveParams` for all drives or one per drive;
    by default `DriveParams.for_axis(counts_per_unit, following_error_window_units=4 x window)`
    (the drive's own monitor is looser than the worker's, as usually configured)."""

    kind = "sim"

    def __init__(self, drives: Sequence[DriveSpec], cycle_time_s: float = 0.001,
                 drive_params: DriveParams | Sequence[DriveParams] | None = None,
                 initial_positions_counts: Sequence[float] | None = None,
                 watchdog_s: float = 0.1, unmapped_objects: Sequence[int] = (),
                 terminals: Sequence[TerminalSpec] = (), switches: Sequence[SimSwitch] = (),
                 input_rest: Sequence[int] = (), index_pitch_units: Sequence[float] = (),
                 spindles: Sequence[SpindleDriveSpec] = (), **_ignored: object) -> None:
        super().__init__(drives, cycle_time_s, terminals, spindles)
        self.io = SimIo(self.terminals, self.n_drives,
                        [1.0 / (d.counts_per_unit * d.direction) for d in self.drives], switches, input_rest)
        # objects left out of the simulated process data, as a drive that cannot map them
        self.unmapped_objects = frozenset(unmapped_objects)
        self._map_error_code = 0x603F not in self.unmapped_objects
        n = self.n_drives
        if drive_params is None:
            params = [DriveParams.for_axis(d.counts_per_unit,
                                           following_error_window_units=4.0 * d.following_error_window)
                      for d in self.drives]
        elif isinstance(drive_params, DriveParams):
            params = [drive_params] * n
        else:
            params = list(drive_params)
            if len(params) != n:
                raise ConfigurationError(f"{len(params)} drive_params for {n} drives")
        if initial_positions_counts is not None:
            if len(initial_positions_counts) != n:
                raise ConfigurationError(f"{len(initial_positions_counts)} initial positions for {n} drives")
            params = [_replace_initial(p, float(x)) for p, x in zip(params, initial_positions_counts)]
        if index_pitch_units:
            if len(index_pitch_units) != n:
                raise ConfigurationError(f"{len(index_pitch_units)} index pitches for {n} drives")
            params = [_replace_index(p, float(x) * d.counts_per_unit)
                      for p, x, d in zip(params, index_pitch_units, self.drives)]
        self.models: tuple[DriveModel, ...] = tuple(
            DriveModel(p, position=d.position) for p, d in zip(params, self.drives))
        self._by_position = {d.position: i for i, d in enumerate(self.drives)}
        self.spindle_models = tuple(_spindle_model(s) for s in self.spindles)
        self._lost = [False] * n
        self._terminal_lost = np.zeros(len(self.terminals), dtype=bool)
        self._terminal_wkc = np.array([t.type.working_counter for t in self.terminals], dtype=np.int64)
        self._init = [False] * n             # back after a power cycle: INIT until recovered
        self._silent_s = [0.0] * n
        self._drop_frames = 0
        self.watchdog_s = float(watchdog_s)
        self.frames_sent = 0
        self.recoveries = 0
        # the simulated probe: (axis watched, drive wired to, bit mask, level in counts, +1
        # contact at or below in counts, -1 at or above), or None
        self._probe: tuple[int, int, int, float, int] | None = None
        # the simulated workpiece: (part, drives of X, Y, Z, drive wired to, bit mask), or None;
        # its numbers as the injections bring them
        self._part: tuple[SimPart, tuple[int, int, int], int, int] | None = None
        self._part_values: list[float] = [0.0] * PART_VALUES

    # ------------------------------------------------------------------ backend
    @property
    def expected_wkc(self) -> int:
        return 3 * (self.n_drives + len(self.spindles)) + sum(t.type.working_counter for t in self.terminals)

    def _open(self) -> None:
        for m in (*self.models, *self.spindle_models):
            m.controlword = 0
            m.step(self.cycle_time_s)            # NOT READY -> SWITCH ON DISABLED
        self._lost = [False] * self.n_drives
        self._terminal_lost[:] = False
        self._init = [False] * self.n_drives
        self._drop_frames = 0
        self._read_inputs_all()
        self.controlword[:] = 0
        self.modes_of_operation[:] = 8
        self.target_position[:] = self.position_actual

    def _close(self) -> None:
        for m in (*self.models, *self.spindle_models):
            m.controlword = 0
            m.step(self.cycle_time_s)

    def _read_inputs_all(self) -> None:
        for i, m in enumerate(self.models):
            self._read_inputs(i, m)

    def set_probe_surface(self, index: int, bit: int, level_units: float, below: bool = True,
                          input_drive: int = -1) -> None:
        """A probe on bit ``bit`` of drive ``input_drive``'s inputs (-1: drive ``index``)
        touching while axis ``index`` is at or below ``level_units`` (axis units; above when
        not ``below``)."""
        wired = index if input_drive < 0 else input_drive
        if not 0 <= index < self.n_drives or not 0 <= wired < self.n_drives or not 0 <= bit < 32:
            raise ConfigurationError(f"probe of axis {index} on drive {wired} bit {bit}: "
                                     "no such drive or bit")
        d = self.drives[index]
        sign = (1 if below else -1) * d.direction
        self.clear_probe_surface()
        self._probe = (index, wired, 1 << bit, level_units * d.counts_per_unit * d.direction, sign)

    def clear_probe_surface(self) -> None:
        if self._probe is not None:
            wired, mask = self._probe[1], self._probe[2]
            self.models[wired].digital_inputs &= ~mask
        self._probe = None

    def set_probe_part(self, part: SimPart, axes: tuple[int, int, int], bit: int, input_drive: int) -> None:
        """The probe on bit ``bit`` of drive ``input_drive``'s inputs touches ``part`` (its
        lengths in the units of the drives ``axes`` of X, Y and Z) besides the surface."""
        if (not all(0 <= a < self.n_drives for a in (*axes, input_drive)) or not 0 <= bit < 32
                or len(set(axes)) != 3):
            raise ConfigurationError(f"simulated part on drives {axes}, probe on drive {input_drive} bit "
                                     f"{bit}: no such drive or bit")
        self.clear_probe_part()
        self._part = (part, axes, input_drive, 1 << bit)

    def clear_probe_part(self) -> None:
        if self._part is not None:
            self.models[self._part[2]].digital_inputs &= ~self._part[3]
        self._part = None

    def _units(self, i: int) -> float:
        d = self.drives[i]
        return self.models[i].position_actual / (d.counts_per_unit * d.direction)

    def _touch(self) -> None:
        touching: dict[tuple[int, int], bool] = {}
        if self._probe is not None:
            i, wired, mask, level, sign = self._probe
            touching[(wired, mask)] = sign * self.models[i].position_actual <= sign * level
        if self._part is not None:
            part, (ix, iy, iz), wired, mask = self._part
            hit = part.touches(self._units(ix), self._units(iy), self._units(iz))
            touching[(wired, mask)] = touching.get((wired, mask), False) or hit
        for (wired, mask), on in touching.items():
            m = self.models[wired]
            if on:
                m.digital_inputs |= mask
            else:
                m.digital_inputs &= ~mask

    def _read_inputs(self, i: int, m: DriveModel) -> None:
        self.statusword[i], self.position_actual[i], self.following_error[i] = m.process_inputs()
        if self._map_error_code:
            self.error_code[i] = m.error_code
        self.modes_display[i] = m.modes_of_operation_display
        self.digital_inputs[i] = m.digital_inputs
        self.touch_probe_status[i] = m.touch_probe_status
        self.touch_probe_value[i] = m.touch_probe_value

    def _exchange(self) -> int:
        self._check_open()
        dt = self.cycle_time_s
        self.frames_sent += 1
        lost_frame = self._drop_frames > 0
        if lost_frame:
            self._drop_frames -= 1
        wkc = 0
        # the outputs as Python ints once a cycle (indexing the arrays drive by drive costs more)
        cw = self.controlword.tolist()
        tp = self.target_position.tolist()
        mode = self.modes_of_operation.tolist()
        dout = self.digital_outputs.tolist()
        tpf = self.touch_probe_function.tolist()
        if self._probe is not None or self._part is not None:
            self._touch()
        io_words = self._io_words() if not lost_frame else None
        lost, init, silent = self._lost, self._init, self._silent_s
        for i, m in enumerate(self.models):
            if lost_frame or lost[i] or init[i]:
                silent[i] += dt
                if silent[i] >= self.watchdog_s:
                    m.watchdog_expired()
                m.step(dt)
                continue
            silent[i] = 0.0
            self._read_inputs(i, m)          # inputs latched before the drive takes the outputs
            m.controlword = cw[i]
            m.target_position = tp[i]
            m.modes_of_operation = mode[i]
            m.digital_outputs = dout[i]
            m.touch_probe_function = tpf[i]
            m.step(dt)
            wkc += 3
        if io_words is not None:
            wkc += self._exchange_terminals(io_words)
        if self.spindle_models:
            wkc += self._exchange_spindles(dt, lost_frame)
        return -1 if lost_frame else wkc

    def _exchange_spindles(self, dt: float, lost_frame: bool) -> int:
        for k, m in enumerate(self.spindle_models):
            if not lost_frame:
                self.spindle_statusword[k] = m.statusword
                self.spindle_velocity_actual[k] = m.velocity_actual
                self.spindle_error_code[k] = m.error_code
                self.spindle_modes_display[k] = m.modes_of_operation_display
                m.controlword = int(self.spindle_controlword[k])
                m.target_velocity = int(self.spindle_target_velocity[k])
                m.modes_of_operation = int(self.spindle_modes[k])
            m.step(dt)
        return 3 * len(self.spindle_models)

    def _io_words(self) -> np.ndarray | None:
        """This cycle's input words of the terminals and drives, None without terminals or
        simulated inputs (the drives' own words stand)."""
        io = self.io
        if not self.terminals and not io.active:
            return None
        drive_words = np.array([m.digital_inputs for m in self.models], dtype=np.int64)
        counts = np.array([m.position_actual for m in self.models], dtype=float)
        return io.words(counts, drive_words)

    def _exchange_terminals(self, words: np.ndarray) -> int:
        """Terminals' inputs latched, their outputs taken; the drives' 0x60FD with the
        switches laid over (as the drives' inputs were read this cycle). Returns their share
        of the working counter."""
        io = self.io
        m = len(self.terminals)
        if io.active:
            for i in range(self.n_drives):
                if not (self._lost[i] or self._init[i]):
                    self.digital_inputs[i] = int(words[m + i]) & 0xFFFF_FFFF
        alive = ~self._terminal_lost             # a lost terminal neither reads nor is written
        np.copyto(self.terminal_inputs, words[:m] & 0xFFFF_FFFF, casting="unsafe", where=alive)
        np.copyto(self.terminal_counts, io.counts, casting="unsafe", where=alive)
        np.copyto(io.outputs, self.terminal_outputs, where=alive)
        return int(self._terminal_wkc[alive].sum())

    def _slaves(self) -> tuple[SlaveInfo, ...]:
        out = [SlaveInfo(position=t.position, name=t.type.name, vendor_id=t.type.vendor_id,
                         product_code=t.type.product_code, state="OP") for t in self.terminals]
        for i, (d, m) in enumerate(zip(self.drives, self.models)):
            out.append(SlaveInfo(
                position=d.position, name=f"SimServo {d.axis_name}",
                vendor_id=d.vendor_id or m.params.vendor_id,
                product_code=d.product_code or m.params.product_code,
                revision=m.params.revision, serial=m.params.serial,
                state="INIT" if self._init[i] else "SAFE-OP" if self._lost[i] else "OP",
                al_status_code=0x001B if self._lost[i] else 0))
        out += [SlaveInfo(position=s.position, name="SimSpindle", vendor_id=m.params.vendor_id,
                          product_code=m.params.product_code, revision=m.params.revision, state="OP")
                for s, m in zip(self.spindles, self.spindle_models)]
        return tuple(sorted(out, key=lambda s: s.position))

    def _model_at(self, position: int) -> DriveModel:
        for s, m in zip(self.spindles, self.spindle_models):
            if s.position == position:
                return m
        try:
            return self.models[self._by_position[position]]
        except KeyError:
            raise ConfigurationError(f"no slave at position {position}") from None

    def _sdo_upload(self, position: int, index: int, subindex: int) -> bytes:
        m = self._model_at(position)
        if (index, subindex) in ((0x1018, 1), (0x1018, 2)):
            info = next(s for s in self._slaves() if s.position == position)
            value = info.vendor_id if subindex == 1 else info.product_code
        else:
            value = m.read_object(index, subindex)
        return encode_object(OBJECTS[(index, subindex)], value)

    def _sdo_download(self, position: int, index: int, subindex: int, data: bytes) -> None:
        m = self._model_at(position)
        entry = m.object_entry(index, subindex)
        try:
            value = decode_object(entry, data)
        except SdoAbortError as exc:
            raise SdoAbortError(position, index, subindex, exc.abort_code) from None
        m.write_object(index, subindex, value)

    def lost_slaves(self) -> tuple[int, ...]:
        drives = [d.position for d, lost, init in zip(self.drives, self._lost, self._init) if lost or init]
        return tuple(drives + [t.position for t, lost in zip(self.terminals, self._terminal_lost) if lost])

    def recover_slaves(self) -> tuple[int, ...]:
        """Bring slaves that came back in INIT to OP again (as `SoemBus.recover_slaves`);
        returns their positions. Slaves still gone are left alone."""
        self._check_open()
        back = []
        for i, d in enumerate(self.drives):
            if self._init[i] and not self._lost[i]:
                self._init[i] = False
                self._silent_s[i] = 0.0
                back.append(d.position)
        self.recoveries += len(back)
        return tuple(back)

    # ------------------------------------------------------------------ fault injection
    def maps_object(self, index: int, obj: int) -> bool:
        return obj not in self.unmapped_objects

    def inject_drive_fault(self, index: int, error_code: int = ERROR_OVERCURRENT,
                           persistent: bool = False) -> None:
        """Drive `index` trips a fault (see `DriveModel.inject_fault`)."""
        self.models[index].inject_fault(error_code, persistent)

    def clear_drive_fault(self, index: int) -> None:
        self.models[index].clear_fault()

    def inject_following_error(self, index: int, jammed: bool = True) -> None:
        """Block (or free) drive `index`'s load: its following error grows."""
        self.models[index].set_jam(jammed)

    def drop_frames(self, n: int) -> None:
        """Lose the next `n` frames (exchange returns -1, inputs not updated)."""
        self._drop_frames = max(0, int(n))

    def lose_slave(self, index: int) -> None:
        """Drive `index` stops answering (cable cut behind it is not modelled)."""
        self._lost[index] = True

    def restore_slave(self, index: int, power_cycled: bool = False) -> None:
        """Drive `index` answers again; `power_cycled`: it comes back in INIT and stays
        silent until `recover_slaves()` (a real slave after losing power)."""
        self._lost[index] = False
        self._init[index] = bool(power_cycled)
        self._silent_s[index] = 0.0

    def inject(self, name: str, index: int = 0, value: int = 0) -> None:
        """Dispatch by name (used by the worker's command channel); see `INJECTIONS`."""
        if name == "drive_fault":
            self.inject_drive_fault(index, value or ERROR_OVERCURRENT)
        elif name == "persistent_fault":
            self.inject_drive_fault(index, value or ERROR_OVERCURRENT, persistent=True)
        elif name == "clear_fault":
            self.clear_drive_fault(index)
        elif name == "jam":
            self.inject_following_error(index, True)
        elif name == "unjam":
            self.inject_following_error(index, False)
        elif name == "drop_frames":
            self.drop_frames(value)
        elif name == "lose_slave":
            self.lose_slave(index)
        elif name == "restore_slave":
            self.restore_slave(index, power_cycled=bool(value))
        elif name == "probe_surface":
            self.set_probe_surface(index, value & 31, (value >> 12) / PROBE_SURFACE_SCALE,
                                   bool(value >> 5 & 1), (value >> 6 & 63) - 1)
        elif name == "probe_off":
            self.clear_probe_surface()
        elif name == "probe_part_value":
            slot = value & 31
            if slot >= PART_VALUES:
                raise ConfigurationError(f"simulated part value {slot}: there are {PART_VALUES}")
            self._part_values[slot] = (value >> 5) / PROBE_SURFACE_SCALE
        elif name == "probe_part":
            axes = ((value >> 11) & 63, (value >> 17) & 63, (value >> 23) & 63)
            self.set_probe_part(SimPart.from_values(self._part_values), axes, value & 31, (value >> 5) & 63)
        elif name == "probe_part_off":
            self.clear_probe_part()
        elif name == "terminal_input":
            if not 0 <= index < self.n_terminals:
                raise ConfigurationError(f"terminal {index}: there are {self.n_terminals}")
            self.io.force(index, value)
        elif name == "drive_input":
            if not 0 <= index < self.n_drives:
                raise ConfigurationError(f"drive {index}: there are {self.n_drives}")
            self.io.force(self.n_terminals + index, value)
        elif name == "encoder_add":
            self.io.encoder_add(index, value - (1 << 31) if value >= 1 << 31 else value)
        elif name in ("spindle_load", "spindle_unload", "spindle_fault"):
            if not 0 <= index < len(self.spindles):
                raise ConfigurationError(f"spindle drive {index}: there are {len(self.spindles)}")
            m = self.spindle_models[index]
            if name == "spindle_fault":
                m.inject_fault(value or ERROR_OVERCURRENT)
            else:
                m.set_load(value * self.spindles[index].velocity_per_rpm if name == "spindle_load" else None)
        elif name in ("lose_terminal", "restore_terminal"):
            if not 0 <= index < self.n_terminals:
                raise ConfigurationError(f"terminal {index}: there are {self.n_terminals}")
            self._terminal_lost[index] = name == "lose_terminal"
            if name == "restore_terminal":
                self.io.counts[index] = 0          # powered again: its counter starts from 0
        else:
            raise ConfigurationError(f"unknown injection {name!r}; known: {INJECTIONS}")


#: the simulated spindle: its motor's top speed and acceleration (rpm, rpm/s) and the lag of its
#: speed loop (the spindle's inertia)
SIM_SPINDLE_RPM = 30_000.0
SIM_SPINDLE_RPM_S = 8_000.0
SIM_SPINDLE_LAG_S = 0.05


def _spindle_model(s: SpindleDriveSpec) -> DriveModel:
    """A simulated spindle drive; its profile velocity ramps (0x6083, 0x6084) at its motor's
    acceleration."""
    a = SIM_SPINDLE_RPM_S * s.velocity_per_rpm
    params = DriveParams(v_max_counts_s=SIM_SPINDLE_RPM * s.velocity_per_rpm, a_max_counts_s2=a,
                         velocity_lag_s=SIM_SPINDLE_LAG_S, quick_stop_deceleration_counts_s2=int(a))
    if s.vendor_id or s.product_code:
        params = replace(params, vendor_id=s.vendor_id, product_code=s.product_code)
    m = DriveModel(params, position=s.position)
    for index in (0x6083, 0x6084):
        m.write_object(index, 0, int(a))
    m.modes_of_operation = s.mode
    return m


def _replace_index(p: DriveParams, pitch_counts: float) -> DriveParams:
    """The drive's encoder with a zero impulse every ``pitch_counts`` (0: none), one of them a
    third of a pitch from the counts' zero (an index is never where a switch is put)."""
    pitch = abs(pitch_counts)
    if not math.isfinite(pitch):
        raise ConfigurationError(f"index pitch {pitch_counts} is not finite")
    return replace(p, index_pitch_counts=pitch, index_phase_counts=pitch / 3.0)


def _replace_initial(p: DriveParams, initial_counts: float) -> DriveParams:
    if not math.isfinite(initial_counts):
        raise ConfigurationError(f"initial position {initial_counts} is not finite")
    return replace(p, initial_position_counts=initial_counts)
