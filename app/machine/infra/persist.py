"""What survives a restart, in the state directory (default ~/.local/state/cnc-panel):

    state.json    raw drive positions, home offsets, homed flags, active work offset, and whether
                  a controller had the drives (``running``: saved at most once a second while
                  connected, false after a clean shutdown)
    offsets.json  the G54-G59 table (machine coordinates of part zero, per axis)
    alarms.json   the alarm list (active and history, newest last, at most 500)
    machine.toml  the machine configuration when none is given on the command line
    last_run.npz  trace of the last program run (reference and actual per axis)

Every file is written atomically (temporary file + fsync + os.replace). A damaged file is
reported (``MachineError`` text for the alarm list) and moved aside, never silently replaced.
"""

from __future__ import annotations

import json
import math
import os
import time
from pathlib import Path
from typing import Any

from app.machine.errors import StateFolderBusy
from app.machine.model import Alarm, AlarmState, Severity
from planner.core.errors import PlannerError
from planner.core.files import remove_stale_temporaries, write_text
from planner.core.tools import ToolTable, format_tbl, read_tbl

__all__ = ["StateStore"]

MAX_ALARMS = 500


def _finite(x: object) -> float | None:
    """``x`` as a finite number, or None (a string, null, NaN, infinity or a boolean)."""
    if isinstance(x, bool) or not isinstance(x, (int, float)):
        return None
    value = float(x)
    return value if math.isfinite(value) else None


class StateStore:
    """Reads and writes the state directory. Problems found while reading are collected in
    ``problems`` (the controller raises them as alarms)."""

    def __init__(self, state_dir: str | os.PathLike[str], *, exclusive: bool = False) -> None:
        """``exclusive``: take the folder for this control (``StateFolderBusy`` when another
        has it) until ``release``; reading a folder's state needs no lock."""
        self.dir = Path(state_dir).expanduser()
        self.dir.mkdir(parents=True, exist_ok=True)
        self.problems: list[str] = []
        self._lock: Any = None      # the open lock file (a file object: closed, and so released, with us)
        if exclusive:
            self._take()
        # a save interrupted by a power cut or kill -9 leaves its temporary: gone at the next start
        remove_stale_temporaries(self.dir, whole_folder=True)

    def _take(self) -> None:
        import fcntl

        lock = open(self.dir / "lock", "a+b")  # noqa: SIM115 - held open for the controller's life
        try:
            fcntl.flock(lock.fileno(), fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            lock.seek(0)
            holder = lock.read(64).decode("ascii", "replace").strip() or "?"
            lock.close()
            raise StateFolderBusy(f"another control (pid {holder}) uses the state folder {self.dir}: "
                                  "close it first, or start this one with another --state-dir") from None
        lock.truncate(0)
        lock.write(str(os.getpid()).encode())
        lock.flush()
        self._lock = lock            # the kernel releases the lock when this process ends

    def release(self) -> None:
        """Give the folder up (clean shutdown); releasing twice is harmless."""
        lock, self._lock = self._lock, None
        if lock is not None:
            lock.close()

    def path(self, name: str) -> Path:
        return self.dir / name

    def _read_json(self, name: str) -> Any:
        p = self.path(name)
        if not p.exists():
            return None
        try:
            return json.loads(p.read_text(encoding="utf-8"))
        except (OSError, ValueError) as exc:
            aside = p.with_name(f"{p.name}.damaged-{int(time.time())}")
            try:
                os.replace(p, aside)
            except OSError:
                pass
            self.problems.append(f"{p}: damaged ({exc}); moved aside to {aside.name}")
            return None

    def _write_json(self, name: str, data: Any) -> None:
        write_text(self.path(name), json.dumps(data, indent=1))

    # ------------------------------------------------------------------ machine state
    def load_state(self, axes: tuple[str, ...]) -> dict[str, Any] | None:
        data = self._read_json("state.json")
        if not isinstance(data, dict):
            return None
        saved_axes = data.get("axes")
        if not isinstance(saved_axes, list) or tuple(saved_axes) != tuple(axes):
            self.problems.append(f"{self.path('state.json')}: saved for axes {data.get('axes')}, "
                                 f"machine has {list(axes)}: positions and homed state not restored")
            return None
        try:
            n = len(axes)
            numbers = {k: [_finite(x) for x in data[k]][:n] for k in ("raw_position", "home_offset")}
            if any(x is None for v in numbers.values() for x in v):
                raise ValueError("a position is not a number")
            homed = data["homed"]
            if not (isinstance(homed, list) and all(isinstance(x, bool) for x in homed)):
                raise ValueError(f"homed is {homed!r}, not true/false per axis")
            out: dict[str, Any] = {
                "raw_position": numbers["raw_position"],
                "home_offset": numbers["home_offset"],
                "homed": homed[:n],
                "active_offset": str(data.get("active_offset", "G54")),
                # True while a controller had the drives: still True at the next start means
                # it did not shut down cleanly (power loss, kill -9)
                "running": bool(data.get("running", False)),
                "saved": float(data.get("saved", 0.0)),
                # the program that was running and its line, when one was
                "program": str(data.get("program", "") or ""),
                "line": int(data.get("line", 0) or 0),
            }
            if any(len(out[k]) != n for k in ("raw_position", "home_offset", "homed")):
                raise ValueError("wrong number of values")
            return out
        except (KeyError, TypeError, ValueError) as exc:
            self.problems.append(f"{self.path('state.json')}: invalid ({exc}); not restored")
            return None

    def save_state(self, axes: tuple[str, ...], raw_position: list[float], home_offset: list[float],
                   homed: list[bool], active_offset: str, running: bool = False,
                   program: str = "", line: int = 0) -> None:
        """The machine's state; ``program`` and ``line``: the program running and its line (an
        unclean end then says what was interrupted)."""
        self._write_json("state.json", {"axes": list(axes), "raw_position": list(raw_position),
                                        "home_offset": list(home_offset), "homed": list(homed),
                                        "active_offset": active_offset, "running": running,
                                        "program": program, "line": int(line), "saved": time.time()})

    # ------------------------------------------------------------------ work offsets
    def load_offsets(self, n_axes: int) -> dict[str, tuple[float, ...]] | None:
        data = self._read_json("offsets.json")
        if not isinstance(data, dict):
            return None
        out: dict[str, tuple[float, ...]] = {}
        for k, v in data.items():
            if not (isinstance(v, list) and len(v) == n_axes):
                self.problems.append(f"{self.path('offsets.json')}: {k} does not have {n_axes} values; "
                                     "offsets from the configuration used")
                return None
            values = [_finite(x) for x in v]
            if any(x is None for x in values):
                self.problems.append(f"{self.path('offsets.json')}: {k} holds {v!r}, not numbers; "
                                     "offsets from the configuration used")
                return None
            out[k] = tuple(x for x in values if x is not None)
        return out

    def save_offsets(self, offsets: dict[str, tuple[float, ...]]) -> None:
        self._write_json("offsets.json", {k: list(v) for k, v in offsets.items()})

    # ------------------------------------------------------------------ parameters (var file)
    def load_parameters(self) -> dict[int, float]:
        """The persistent G-code parameters (G92, G28/G30 positions, G59.1-G59.3 ...), as
        LinuxCNC's var file keeps them; a damaged file is named and its values not used."""
        data = self._read_json("parameters.json")
        if not isinstance(data, dict):
            return {}
        try:
            values = {int(k): float(v) for k, v in data.items()}
        except (TypeError, ValueError):
            self.problems.append(f"{self.path('parameters.json')}: not a table of parameter numbers and "
                                 "values; G92, G28 and G30 start at zero")
            return {}
        if not all(math.isfinite(v) for v in values.values()):
            self.problems.append(f"{self.path('parameters.json')}: a value is not a finite number; G92, "
                                 "G28 and G30 start at zero")
            return {}
        return values

    def save_parameters(self, values: dict[int, float]) -> None:
        self._write_json("parameters.json", {str(k): v for k, v in sorted(values.items())})

    # ------------------------------------------------------------------ tools
    def load_tools(self) -> tuple[ToolTable, int]:
        """The tool table (``tools.tbl``, LinuxCNC's format) and the tool in the spindle. A
        damaged table is moved aside and named: the table is then empty (G43 of a tool that
        is not in it is refused), never a guess."""
        table = ToolTable()
        p = self.path("tools.tbl")
        if p.exists():
            try:
                table = read_tbl(p)
            except PlannerError as exc:
                aside = p.with_name(f"{p.name}.damaged-{int(time.time())}")
                try:
                    os.replace(p, aside)
                except OSError:
                    pass
                self.problems.append(f"{exc}; the tool table was moved aside to {aside.name}: enter or "
                                     "import the tools again")
        data = self._read_json("tool.json")
        current = data.get("in_spindle", 0) if isinstance(data, dict) else 0
        if not isinstance(current, int) or isinstance(current, bool) or current < 0:
            self.problems.append(f"{self.path('tool.json')}: in_spindle {current!r} is not a tool number; "
                                 "the spindle counts as empty (T0)")
            current = 0
        if current and current not in table:
            self.problems.append(f"the tool in the spindle, T{current}, is not in the tool table; "
                                 "the spindle counts as empty (T0)")
            current = 0
        return table, current

    def save_tools(self, table: ToolTable, in_spindle: int) -> None:
        write_text(self.path("tools.tbl"), format_tbl(table))
        self._write_json("tool.json", {"in_spindle": int(in_spindle)})

    # ------------------------------------------------------------------ alarms
    def load_alarms(self) -> list[Alarm]:
        data = self._read_json("alarms.json")
        if data is None:
            return []
        if not isinstance(data, list):
            self.problems.append(f"{self.path('alarms.json')}: not a list of alarms; the alarm history "
                                 "starts empty")
            return []
        out = []
        skipped = 0
        for d in data:
            try:
                out.append(Alarm(id=int(d["id"]), time_s=float(d["time_s"]), source=str(d["source"]),
                                 cause=str(d["cause"]), severity=Severity(int(d["severity"])),
                                 state=AlarmState(d["state"]), code=str(d.get("code", ""))))
            except (KeyError, TypeError, ValueError, OverflowError):   # int(inf)
                skipped += 1
        if skipped:
            self.problems.append(f"{self.path('alarms.json')}: {skipped} damaged alarm(s) left out of the "
                                 "history")
        return out[-MAX_ALARMS:]

    def save_alarms(self, alarms: list[Alarm]) -> None:
        self._write_json("alarms.json", [
            {"id": a.id, "time_s": a.time_s, "source": a.source, "cause": a.cause,
             "severity": int(a.severity), "state": a.state.value, "code": a.code}
            for a in alarms[-MAX_ALARMS:]])
