"""The machine's signals as the drives and terminals report them (``app.machine.wiring``), read
from the newest snapshot of the 1 ms loop, and the refusals they call for.

``MachineSignals`` only reads: what the E-stop chain, the door, a limit switch or a button reads
now, and where each is wired (the Diagnostics page lists them). What the machine does when a
signal changes is ``MachineIo``'s (``app.machine.devices.machine_io``); what the loop does in
the cycle itself (an E-stop chain opening, a limit switch) is the worker's.
"""

from __future__ import annotations

from app.machine.infra.drives import DriveLink
from app.machine.model import SignalReading
from app.machine.ports import Settings
from app.machine.state.gate import Action
from app.machine.wiring import SIGNALS, Direction, SignalWire, axis_at
from ethercat.worker import WorkerSnapshot

__all__ = ["MachineSignals"]

#: what the door, when open, refuses (the jog: unless a setup speed is configured)
_DOOR_REFUSES = frozenset({Action.CYCLE_START, Action.RESUME, Action.RUN_FROM_LINE, Action.MDI, Action.HOME,
                           Action.SPINDLE_ON, Action.PROBE, Action.MEASURE_TOOL})


class MachineSignals:
    """What the machine's signals read now (``controller.signals``)."""

    def __init__(self, settings: Settings, drives: DriveLink) -> None:
        self._settings = settings
        self._drives = drives

    # ------------------------------------------------------------------ values
    def _raw(self, s: SignalWire, snap: WorkerSnapshot) -> bool | None:
        cfg = self._settings.config
        wiring = cfg.wiring
        k = wiring.terminal_index(s.wire.slave)
        out = s.signal.direction is Direction.OUT
        if k >= 0:
            words = snap.terminal_outputs if out else snap.terminal_inputs
            index = k
        else:
            words = snap.digital_outputs if out else snap.digital_inputs
            index = axis_at(cfg.machine, s.wire.slave)
        if not 0 <= index < len(words):
            return None
        return bool(int(words[index]) >> s.wire.bit & 1)

    def value(self, key: str, snap: WorkerSnapshot | None = None) -> bool | None:
        """Whether signal ``key`` is true now; None when it is not wired or the bus is down."""
        s = self._settings.config.wiring.get(key)
        snap = snap if snap is not None else self._drives.last_snapshot
        if s is None or snap is None:
            return None
        raw = self._raw(s, snap)
        return None if raw is None else raw != s.wire.inverted

    def is_false(self, key: str, snap: WorkerSnapshot | None = None) -> bool:
        """Wired and reading false now (the door open, the chain open, the air gone)."""
        return self.value(key, snap) is False

    def readings(self) -> tuple[SignalReading, ...]:
        """Every wired signal, in the order ``wiring.SIGNALS`` lists them."""
        cfg = self._settings.config
        wiring = cfg.wiring
        snap = self._drives.last_snapshot
        order = {d.name: n for n, d in enumerate(SIGNALS)}
        out = []
        for s in sorted(wiring.signals, key=lambda s: (order[s.signal.name], s.axis)):
            k = wiring.terminal_index(s.wire.slave)
            if k >= 0:
                t = wiring.terminals[k]
                where = f"{t.name or t.type} (slave {t.position}) channel {s.wire.bit}"
            else:
                i = axis_at(cfg.machine, s.wire.slave)
                axis = cfg.drives[i][1] if i >= 0 else "?"
                obj = "0x60FE:1" if s.signal.direction is Direction.OUT else "0x60FD"
                where = f"drive {axis} (slave {s.wire.slave}) {obj} bit {s.wire.bit}"
            if s.wire.inverted:
                where += ", normally closed"
            out.append(SignalReading(s.key, s.signal.direction.value, where, s.wire.text(),
                                     self.value(s.key, snap), s.signal.meaning, s.signal.hal))
        return tuple(out)

    # ------------------------------------------------------------------ refusals
    def refusal(self, action: str) -> str:
        """Why ``action`` cannot be done while the signals read as they do ("" when it can)."""
        if self.is_false("estop_chain_ok") and action in (Action.ESTOP_RELEASE, Action.RESET):
            return "the E-stop chain is open: release the E-stop buttons and close the safety circuit first"
        if self.is_false("door_closed"):
            if action in _DOOR_REFUSES:
                return "the door is open: close it first"
            if action == Action.JOG and self._settings.config.wiring.interlocks.door_open_jog_mm_s <= 0.0:
                return ("the door is open: jogging needs it closed on this machine ([interlocks] "
                        "door_open_jog_mm_s)")
        return ""

    def jog_speed_cap(self) -> float | None:
        """The setup speed a jog is capped at while the door is open (mm/s), None when closed."""
        if self.is_false("door_closed"):
            return self._settings.config.wiring.interlocks.door_open_jog_mm_s
        return None

    def has_limit_switches(self, axis: int) -> bool:
        """Whether axis ``axis`` has both its limit switches wired."""
        name = self._settings.config.axes[axis]
        wiring = self._settings.config.wiring
        return wiring.has(f"limit_pos_{name}") and wiring.has(f"limit_neg_{name}")

    def limit_side(self, axis: int) -> int:
        """+1 / -1 when axis ``axis`` stands on its positive / negative limit switch (either
        side's, on a gantry), else 0."""
        name = self._settings.config.axes[axis]
        if self.value(f"limit_pos_{name}") or self.value(f"limit_pos2_{name}"):
            return 1
        if self.value(f"limit_neg_{name}") or self.value(f"limit_neg2_{name}"):
            return -1
        return 0
