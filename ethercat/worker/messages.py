"""The command mailbox's vocabulary and the texts of alarms and events.

The loop writes only numbers (a code, an axis, a few integers); the controller's handle turns
them into sentences here, outside the cycle.
"""

from __future__ import annotations

import enum

from ..cia402 import Cia402State
from ..sim_bus import INJECTIONS
from .types import AlarmCode, EventCode, HomingStep, WorkerConfig

__all__ = ["INJECT_NAMES", "Command", "Result", "alarm_message", "error_code_text", "event_message"]


class Command(enum.IntEnum):
    NONE = 0
    ENABLE = 1
    DISABLE = 2
    FAULT_RESET = 3
    QUICK_STOP = 4
    ESTOP = 5
    HOME = 6
    DOUT = 7
    INJECT = 8
    FLUSH = 9
    RESET_TRACKING = 10
    STOP = 11
    REPLACE = 12
    PROBE = 13
    HOME_SWITCH = 14        # a: the axes (bit mask) that home to their switches together
    TOUT = 15               # a: terminal index, b: its output word
    OVERRIDE_LIMITS = 16    # a: 1 on, 0 off
    HANDWHEEL = 17          # a: the axis (-1: off), b: the mode; cmd_f: scale, v, a, j, lowest, highest
    COMPENSATE = 18         # a: the axis, b: 1 on (homed) / 0 off; cmd_f[0]: its home offset
    SPINDLE = 19            # cmd_f: the spindle's speed (rpm, signed) and its ramp (rpm/s)


class Result(enum.IntEnum):
    PENDING = 0
    OK = 1
    REFUSED = 2
    TOO_LATE = 3
    BEYOND_END = 4


#: fault injections the simulated bus knows (``Bus.inject``), by index in the mailbox: its own list
INJECT_NAMES = INJECTIONS

_ERROR_TEXT = {
    0x2310: "continuous over-current",
    0x3210: "DC link over-voltage",
    0x4310: "drive temperature",
    0x7305: "encoder",
    0x8611: "following error",
    0x8700: "sync / process data lost",
}


def error_code_text(code: int) -> str:
    """Short text of a CiA 402 error code (0x603F)."""
    return _ERROR_TEXT.get(code, "")


def slave_text(config: WorkerConfig, position: int) -> str:
    for d in config.drives:
        if d.position == position:
            return f"slave {position} (axis {d.axis_name})"
    return f"slave {position}"


def _bits(mask: int) -> list[int]:
    return [p for p in range(63) if mask >> p & 1]


def event_message(config: WorkerConfig, code: EventCode, a: int, b: int, axis: str = "") -> str:
    if code is EventCode.STARTUP_FAULT_RESET:
        what = f"error code 0x{a:04X} {error_code_text(a)}" if b else "error code not in its process data"
        return (f"drive of axis {axis} was in FAULT when the bus came up ({what}): "
                "fault reset sent once")
    if code is EventCode.DRIVE_ERROR_CODE:
        if b:
            return f"drive fault on axis {axis}: error code 0x{a:04X} {error_code_text(a)} (read from 0x603F)"
        return f"drive fault on axis {axis}: its error code 0x603F could not be read"
    if code is EventCode.SLAVE_RECOVERED:
        back = ", ".join(slave_text(config, p) for p in _bits(a))
        how = " (re-configured to OP by recover_slaves)" if b else ""
        return (f"{back} answering again{how}: working counter as expected; "
                "fault reset and enable to resume")
    return code.name


def alarm_message(config: WorkerConfig, code: AlarmCode, axis: str, axis_i: int, a: int, b: int, f: float,
                  reason: str = "", detail: str = "") -> str:
    """The operator's sentence for one alarm record. ``detail``: the loop's text channel
    (bus errors)."""
    if code is AlarmCode.UNDERRUN:
        return f"set-point buffer underrun after {a} set-points: holding the last position"
    if code is AlarmCode.WORKING_COUNTER:
        lost = _bits(b)
        tail = f"; slaves not answering: {lost}" if lost else ""
        return (f"working counter {a} instead of {int(f)} for more than {config.wkc_error_limit} cycles: "
                f"quick stop of all axes{tail}")
    if code is AlarmCode.DRIVE_FAULT:
        pos = config.drives[axis_i].position
        if b:
            return (f"drive of axis {axis} (slave {pos}) left OPERATION ENABLED "
                    f"({Cia402State(b - 1).name}): quick stop of all axes")
        if b == 0 and f < 0:                 # 0x603F is not in this drive's process data
            return (f"drive fault on axis {axis} (slave {pos}): quick stop of all axes; its error code "
                    "is being read from 0x603F")
        return (f"drive fault on axis {axis} (slave {pos}): error code 0x{a:04X} {error_code_text(a)}: "
                "quick stop of all axes")
    if code is AlarmCode.FOLLOWING_ERROR:
        w = config.drives[axis_i].following_error_window
        return (f"following error on axis {axis}: {f:+.4f} exceeds window {w:g} for more than "
                f"{config.following_error_cycles} cycles: quick stop of all axes")
    if code is AlarmCode.ESTOP:
        return f"E-stop: quick stop of all axes ({reason or 'E-stop'})"
    if code is AlarmCode.QUICK_STOP:
        return f"quick stop of all axes: {reason or 'requested'}"
    if code is AlarmCode.ENABLE_TIMEOUT:
        state = Cia402State(a).name if 0 <= a < len(Cia402State) else str(a)
        return (f"axis {axis} did not reach OPERATION ENABLED within {config.enable_timeout_s} s "
                f"(drive state {state})")
    if code is AlarmCode.HOMING_ERROR:
        why = {0: "drive reported homing error", 1: "timeout",
               2: f"the drive refused homing method {b} (0x6098)"}.get(a, "unknown cause")
        return f"homing of axis {axis} failed ({why})"
    if code is AlarmCode.FAULT_RESET_FAILED:
        return (f"fault reset of axis {axis} failed: error code 0x{a:04X} {error_code_text(a)} "
                "still present")
    if code is AlarmCode.SLAVE_LOST:
        return (f"{slave_text(config, a)} lost: not answering process data; "
                "trying to recover it when it comes back")
    if code is AlarmCode.ESTOP_CHAIN:
        return ("E-stop chain open (the machine's safety circuit): quick stop of all axes; "
                "the drives cannot be enabled until it is closed again")
    if code is AlarmCode.LIMIT_SWITCH:
        side = "positive" if a > 0 else "negative"
        return (f"axis {axis} on its {side} limit switch: quick stop of all axes; "
                f"override limits to jog it off the switch (toward {'-' if a > 0 else '+'})")
    if code is AlarmCode.HOMING_SWITCH:
        step = HomingStep(a).name.lower().replace("_", " ") if 0 <= a < len(HomingStep) else str(a)
        why = {1: ("no index pulse within the search travel" if a == HomingStep.INDEX
                   else "the switch did not change within the search travel"),
               2: "a limit switch tripped", 3: "timeout",
               4: ("its drive has no touch probe (0x60B8, 0x60B9, 0x60BA) in its process data "
                   "for the index"),
               5: "squaring the gantry would move this side further than its homing travel",
               6: "a gantry's side homes only together with its other side"}.get(b, "unknown cause")
        return f"homing of axis {axis} failed at step '{step}': {why}; quick stop of all axes"
    if code is AlarmCode.GANTRY_SKEW:
        g = next((g for g in config.gantry if g.follower == axis_i), None)
        lead = config.drives[g.axis].axis_name if g else "?"
        window = f" (window {g.skew_window:g})" if g else ""
        return (f"gantry {lead}: its drives {lead} and {axis} are {f:+.4f} out of square{window} "
                f"for more than {config.following_error_cycles} cycles: quick stop of all axes")
    if code is AlarmCode.HANDWHEEL:
        if a == 1:
            return (f"handwheel on axis {axis}: its counter jumped by {b} counts in one cycle (a terminal "
                    "restarted or a wire is loose): the jump moved nothing, the axis stopped; select the "
                    "axis again to go on")
        return (f"handwheel on axis {axis}: its encoder terminal stopped answering: the axis stopped; "
                "select the axis again once it answers")
    if code is AlarmCode.SPINDLE:
        if a == 2:
            return (f"the spindle's drive did not enable within the enable time (it stays in "
                    f"{Cia402State(b).name if 0 <= b < len(Cia402State) else b}): the spindle is off")
        what = f"error code 0x{b:04X} {error_code_text(b)}".rstrip() if b else "it left OPERATION ENABLED"
        return f"the spindle's drive faulted ({what}): the spindle is off; reset the fault to turn it again"
    if code is AlarmCode.BUS_ERROR:
        return f"bus error in the cyclic loop ({detail}): worker stopped"
    return code.name
