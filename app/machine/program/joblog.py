"""Job data: the part counter (a program run to its end makes a part; a target count stops
further cycle starts with the reason) and the run log (one line per run, in the state folder).

The log is ``<state>/runs.jsonl``: each run a line of JSON (program, file, start and end,
result, the line it stopped at, its cycle time, the alarms raised during it), appended and
synced to the disk at the run's end. A power cut or kill -9 while a line is written leaves at
most that line incomplete: reading skips it, every complete run before it is kept. A run under
way is marked in ``<state>/run.open`` (its start, program and file); a run that a power loss or
a kill cut is logged at the next start from that mark and the line the saved state names
(result "interrupted ...", its cycle time unknown). The counter
is ``<state>/parts.json``, written whole and atomically. ``export`` writes both forms (CSV and
JSON) where the operator saves programs.
"""

from __future__ import annotations

import csv
import io
import json
import math
import os
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Protocol

from app.machine.infra.events import MachineEvents, PanelChannels
from app.machine.model import Activity, Alarm, ProgramInfo, RunSummary, Severity
from planner.core.files import write_text

__all__ = ["JobLog", "RunRecord"]

LOG_NAME = "runs.jsonl"
OPEN_NAME = "run.open"
PARTS_NAME = "parts.json"
#: the runs the page shows and ``runs`` returns: the newest (the file keeps them all)
SHOWN_RUNS = 500


@dataclass(frozen=True, slots=True)
class RunRecord:
    program: str
    path: str
    start_s: float               # UNIX time the run began
    end_s: float
    result: str                  # "completed", or why it stopped ("stopped by the operator", ...)
    completed: bool
    last_line: int
    cycle_time_s: float          # motion time measured by the worker
    alarms: tuple[str, ...]      # "source: cause" of each alarm raised during the run
    part: int                    # the part counter after the run (0 when it made none)

    def as_json(self) -> dict[str, object]:
        """The record as JSON values: an unknown cycle time (a run a power loss cut) is null."""
        data: dict[str, object] = asdict(self)
        if not math.isfinite(self.cycle_time_s):
            data["cycle_time_s"] = None
        return data

    def line(self) -> str:
        return json.dumps(self.as_json(), ensure_ascii=False)


class _Alarms(Protocol):
    @property
    def all(self) -> tuple[Alarm, ...]: ...

    def raise_alarm(self, source: str, cause: str, severity: Severity, code: str = "") -> Alarm: ...


class _Loaded(Protocol):
    @property
    def program_info(self) -> ProgramInfo | None: ...


class JobLog:
    """The counter and the log (``controller.jobs_log``)."""

    def __init__(self, state_dir: Path, alarms: _Alarms, loader: _Loaded, out: PanelChannels,
                 events: MachineEvents, clock: Callable[[], float] = time.time) -> None:
        self._dir, self._alarms, self._loader, self._clock = Path(state_dir), alarms, loader, clock
        self._out = out
        self.count, self.target = self._read_parts()
        self._open: tuple[float, int, str, str] | None = None    # start, last alarm id, name, path
        out.activityChanged.connect(self._on_activity)
        out.programFinished.connect(self._on_finished)
        events.run_interrupted.connect(self._on_interrupted)

    # ------------------------------------------------------------------ the counter
    def _read_parts(self) -> tuple[int, int]:
        try:
            data = json.loads((self._dir / PARTS_NAME).read_text(encoding="utf-8"))
            return max(0, int(data.get("count", 0))), max(0, int(data.get("target", 0)))
        except (OSError, ValueError, TypeError, AttributeError):
            return 0, 0

    def _save_parts(self) -> None:
        try:
            write_text(self._dir / PARTS_NAME, json.dumps({"count": self.count, "target": self.target}))
        except OSError as exc:
            self._alarms.raise_alarm("persistence", f"cannot save the part counter: {exc.strerror or exc}",
                                     Severity.WARNING, "run_log")

    @property
    def target_reached(self) -> bool:
        return self.target > 0 and self.count >= self.target

    def refusal(self) -> str:
        """Why a cycle start is refused by the counter ("" when it is not)."""
        if self.target_reached:
            return (f"the target of {self.target} part(s) is reached: reset the part counter (or raise "
                    "the target) to run again")
        return ""

    def set_target(self, target: int) -> None:
        self.target = max(0, int(target))
        self._save_parts()

    def reset_count(self) -> None:
        self.count = 0
        self._save_parts()

    # ------------------------------------------------------------------ the runs
    def _on_activity(self, activity: Activity) -> None:
        if activity is Activity.PROGRAM and self._open is None:
            info = self._loader.program_info
            last = max((a.id for a in self._alarms.all), default=0)
            self._open = (self._clock(), last, info.name if info else "", info.path if info else "")
            start, _, name, path = self._open
            try:
                write_text(self._dir / OPEN_NAME,
                           json.dumps({"start_s": start, "program": name, "path": path}))
            except OSError:
                pass                 # the run is logged at its end all the same

    def _on_finished(self, summary: RunSummary) -> None:
        start, last, name, path = self._open or (self._clock(), max((a.id for a in self._alarms.all),
                                                                    default=0),
                                                 summary.name, "")
        self._open = None
        _remove(self._dir / OPEN_NAME)
        part = 0
        if summary.completed:
            self.count += 1
            part = self.count
            self._save_parts()
            if self.target_reached:
                self._out.message.emit(f"{self.count} part(s) made: the target of {self.target} is reached")
        alarms = tuple(f"{a.source}: {a.cause}" for a in self._alarms.all if a.id > last)
        record = RunRecord(program=name or summary.name, path=path, start_s=start, end_s=self._clock(),
                           result=summary.reason or ("completed" if summary.completed else "stopped"),
                           completed=summary.completed, last_line=int(summary.last_line),
                           cycle_time_s=float(summary.cycle_time_s), alarms=alarms, part=part)
        self._append(record)

    def _on_interrupted(self, path: str, line: int, saved_s: float) -> None:
        """The last run was cut by a power loss or a kill: logged from its mark (its start) and
        the line and time of the last position saved."""
        mark_path = self._dir / OPEN_NAME
        try:
            mark = json.loads(mark_path.read_text(encoding="utf-8"))
            start, name = float(mark["start_s"]), str(mark["program"])
        except (OSError, ValueError, TypeError, KeyError):
            start, name = saved_s, ""
        _remove(mark_path)
        why = f"interrupted at line {line}: the control stopped (power loss or killed)"
        self._append(RunRecord(program=name or os.path.basename(path), path=path, start_s=start,
                               end_s=saved_s, result=why, completed=False, last_line=int(line),
                               cycle_time_s=float("nan"), alarms=(), part=0))

    def _append(self, record: RunRecord) -> None:
        path = self._dir / LOG_NAME
        data = (record.line() + "\n").encode("utf-8")
        try:
            fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_APPEND, 0o644)
            try:
                # a line left incomplete by a crash is ended first: the next line stays whole
                if os.fstat(fd).st_size and not _ends_with_newline(path):
                    data = b"\n" + data
                os.write(fd, data)
                os.fsync(fd)
            finally:
                os.close(fd)
        except OSError as exc:
            self._alarms.raise_alarm("persistence", f"{path}: cannot record the run: {exc.strerror or exc}",
                                     Severity.WARNING, "run_log")

    def runs(self, newest: int = SHOWN_RUNS) -> list[RunRecord]:
        """The complete runs of the log, oldest first (the newest ``newest`` of them)."""
        path = self._dir / LOG_NAME
        try:
            lines = path.read_text(encoding="utf-8", errors="replace").splitlines()
        except OSError:
            return []
        out: list[RunRecord] = []
        for text in lines[-newest:] if newest else lines:
            try:
                data = json.loads(text)
                cycle_s = data.get("cycle_time_s")
                out.append(RunRecord(**{**data, "alarms": tuple(data.get("alarms", ())),
                                        "cycle_time_s": math.nan if cycle_s is None else float(cycle_s)}))
            except (ValueError, TypeError):
                continue                 # a line a crash cut short
        return out

    def export(self, folder: Path) -> tuple[Path, Path]:
        """The whole log as ``runs.csv`` and ``runs.json`` in ``folder``."""
        runs = self.runs(0)
        buf = io.StringIO()
        writer = csv.writer(buf)
        writer.writerow(["program", "path", "start", "end", "result", "completed", "last_line",
                         "cycle_time_s",
                         "alarms", "part"])
        for r in runs:
            writer.writerow([r.program, r.path, _iso(r.start_s), _iso(r.end_s), r.result, r.completed,
                             r.last_line,
                             f"{r.cycle_time_s:.3f}" if math.isfinite(r.cycle_time_s) else "",
                             "; ".join(r.alarms), r.part])
        csv_path, json_path = folder / "runs.csv", folder / "runs.json"
        write_text(csv_path, buf.getvalue())
        write_text(json_path, json.dumps([r.as_json() for r in runs], ensure_ascii=False, indent=1))
        return csv_path, json_path


def _remove(path: Path) -> None:
    try:
        path.unlink()
    except OSError:
        pass


def _iso(t: float) -> str:
    return time.strftime("%Y-%m-%d %H:%M:%S", time.localtime(t))


def _ends_with_newline(path: Path) -> bool:
    with open(path, "rb") as f:
        f.seek(-1, os.SEEK_END)
        return f.read(1) == b"\n"
