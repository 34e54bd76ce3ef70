"""Display formatting shared by the pages (tested with parametrised tables)."""

from __future__ import annotations

import math
import re

from planner.core.tools import ToolTable


def format_duration(seconds: float) -> str:
    """h:mm:ss, or m:ss under an hour; '--:--' when unknown."""
    if not math.isfinite(seconds) or seconds < 0:
        return "--:--"
    total = int(round(seconds))
    h, rem = divmod(total, 3600)
    m, s = divmod(rem, 60)
    return f"{h}:{m:02d}:{s:02d}" if h else f"{m}:{s:02d}"


def format_speed(mm_s: float) -> str:
    """Path speed in mm/min, as operators read feeds (F words are mm/min)."""
    if not math.isfinite(mm_s):
        return "---"
    return f"{mm_s * 60.0:.0f} mm/min"


def format_value(value: float, digits: int = 4) -> str:
    """Compact engineering form for tables (RMSE 5.52e-05, 0.0032)."""
    if not math.isfinite(value):
        return "---"
    if value == 0:
        return "0"
    if 1e-3 <= abs(value) < 1e4:
        return f"{value:.{digits}g}"
    return f"{value:.{max(digits - 1, 1)}e}"


def tool_text(table: ToolTable, number: int) -> str:
    """``T2 (6 mm flat)``, or "none" (translated) for the empty spindle."""
    from app.i18n import tr

    return table.label(number) if number else tr("none")


def with_column(col: int, message: str) -> str:
    """An error's message as the editor shows it: where in the line it is, when known."""
    return f"column {col}: {message}" if col > 0 else message


def error_column(message: str) -> int:
    """The column ``with_column`` put in front of a message (0: none)."""
    m = _COLUMN.match(message)
    return int(m.group(1)) if m else 0


_COLUMN = re.compile(r"column (\d+): ")
