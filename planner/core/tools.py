"""The tool table: tools with their number, pocket, length offsets and diameter, read and
written in LinuxCNC's ``.tbl`` format, one tool a line::

    T3 P3 Z12.5 D6.0 ;6 mm flat end mill

T (tool number, whole, >= 1), P (pocket, whole, >= 0; default the tool number), offsets along
X Y Z A B C U V W, D (diameter) and, as LinuxCNC lathes write them, I J Q (front and back angle,
orientation: kept as read); what follows ``;`` is the description. Values are in machine units
(mm, deg), whatever the program's G20/G21. Every error names the file, the line and the word.
"""

from __future__ import annotations

import math
import os
import re
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, field, replace

from planner.core.errors import PlannerError
from planner.core.reading import TOOL_TABLE, read_text

__all__ = ["OFFSET_AXES", "Tool", "ToolTable", "format_tbl", "parse_tbl", "read_tbl"]

#: axes a tool offset may have, in LinuxCNC's order
OFFSET_AXES = "XYZABCUVW"
_LATHE = "IJQ"
_WORD = re.compile(r"([A-Za-z])\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)")
_MAX_TOOL = 99_999_999
_LIMIT = 1e6        # mm or deg: larger offsets or diameters are typing mistakes


@dataclass(frozen=True, slots=True)
class Tool:
    number: int
    pocket: int
    offsets_mm: tuple[tuple[str, float], ...] = ()   # (axis, offset) for the axes the line gives
    diameter_mm: float = 0.0
    description: str = ""
    lathe: tuple[tuple[str, float], ...] = ()        # I J Q as read (front/back angle, orientation)

    def offset(self, axis: str) -> float:
        """The tool's offset along ``axis`` (0 when the table does not give one)."""
        for a, v in self.offsets_mm:
            if a == axis:
                return v
        return 0.0

    @property
    def length_mm(self) -> float:
        """The length offset (Z)."""
        return self.offset("Z")

    def with_offset(self, axis: str, value_mm: float) -> Tool:
        others = tuple((a, v) for a, v in self.offsets_mm if a != axis)
        merged = dict((*others, (axis, float(value_mm))))
        return replace(self, offsets_mm=tuple((a, merged[a]) for a in OFFSET_AXES if a in merged))

    def label(self) -> str:
        """``T2 (6 mm flat)``: the number and what the operator knows it by."""
        text = self.description.strip()
        if not text and self.diameter_mm:
            text = f"{self.diameter_mm:g} mm"
        return f"T{self.number} ({text})" if text else f"T{self.number}"


@dataclass(frozen=True)
class ToolTable:
    """Tools by number (T0, the empty spindle, is never in the table: its offsets are 0)."""

    tools: Mapping[int, Tool] = field(default_factory=dict)

    def __contains__(self, number: object) -> bool:
        return number in self.tools

    def __iter__(self) -> Iterator[Tool]:
        return iter(sorted(self.tools.values(), key=lambda t: t.number))

    def __len__(self) -> int:
        return len(self.tools)

    def get(self, number: int) -> Tool | None:
        return self.tools.get(number)

    def label(self, number: int) -> str:
        """``T2 (6 mm flat)`` for a tool in the table, ``T9`` for one that is not."""
        tool = self.tools.get(number)
        return tool.label() if tool is not None else f"T{number}"

    def with_tool(self, tool: Tool) -> ToolTable:
        _check_tool(tool, "tool table")
        tools = dict(self.tools)
        tools[tool.number] = tool
        return ToolTable(tools)

    def without(self, number: int) -> ToolTable:
        tools = dict(self.tools)
        tools.pop(number, None)
        return ToolTable(tools)

    @staticmethod
    def of(tools: Iterable[Tool]) -> ToolTable:
        table = ToolTable()
        for t in tools:
            if t.number in table:
                raise PlannerError(f"tool table: T{t.number} is given twice")
            table = table.with_tool(t)
        return table


def _check_tool(tool: Tool, where: str) -> None:
    if not 1 <= tool.number <= _MAX_TOOL:
        raise PlannerError(f"{where}: tool number T{tool.number} must be 1-{_MAX_TOOL}")
    if not 0 <= tool.pocket <= _MAX_TOOL:
        raise PlannerError(f"{where}: pocket P{tool.pocket} of T{tool.number} must be 0-{_MAX_TOOL}")
    for axis, v in tool.offsets_mm:
        if axis not in OFFSET_AXES or not (math.isfinite(v) and abs(v) <= _LIMIT):
            raise PlannerError(f"{where}: T{tool.number} offset {axis}{v:g} must be a number within "
                               f"+-{_LIMIT:g}")
    if not (math.isfinite(tool.diameter_mm) and 0.0 <= tool.diameter_mm <= _LIMIT):
        raise PlannerError(f"{where}: T{tool.number} diameter D{tool.diameter_mm:g} must be 0-{_LIMIT:g}")
    if "\n" in tool.description or "\r" in tool.description:
        raise PlannerError(f"{where}: T{tool.number} description must be one line")


def parse_tbl(text: str, where: str = "<tool table>") -> ToolTable:
    """Read a LinuxCNC tool table (PlannerError ``file:line:col: ...`` at the first mistake)."""
    tools: dict[int, Tool] = {}
    for number, raw in enumerate(text.split("\n"), 1):
        code, _, comment = raw.partition(";")
        if not code.strip():
            continue
        at = f"{where}:{number}"
        words: dict[str, float] = {}
        pos = 0
        while pos < len(code):
            if code[pos].isspace():
                pos += 1
                continue
            m = _WORD.match(code, pos)
            if m is None:
                raise PlannerError(f"{at}:{pos + 1}: expected a letter and a number, "
                                   f"found {code[pos:pos + 12]!r}")
            letter = m.group(1).upper()
            if letter not in "TPD" + OFFSET_AXES + _LATHE:
                raise PlannerError(f"{at}:{pos + 1}: {letter} is not a tool table word (T P D X Y Z A B C "
                                   "U V W I J Q)")
            if letter in words:
                raise PlannerError(f"{at}:{pos + 1}: two {letter} words for one tool")
            value = float(m.group(2))
            if not math.isfinite(value):
                raise PlannerError(f"{at}:{pos + 1}: {letter} is not a finite number")
            words[letter] = value
            pos = m.end()
        if "T" not in words:
            raise PlannerError(f"{at}:1: a tool line needs a T word (the tool number)")
        for letter in ("T", "P"):
            if letter in words and words[letter] != int(words[letter]):
                raise PlannerError(f"{at}: {letter}{words[letter]:g} must be a whole number")
        t = int(words["T"])
        if t in tools:
            raise PlannerError(f"{at}: T{t} is given twice (first at another line)")
        tool = Tool(
            number=t,
            pocket=int(words.get("P", t)),
            offsets_mm=tuple((a, words[a]) for a in OFFSET_AXES if a in words),
            diameter_mm=words.get("D", 0.0),
            description=comment.strip(),
            lathe=tuple((a, words[a]) for a in _LATHE if a in words),
        )
        _check_tool(tool, at)
        tools[t] = tool
    return ToolTable(tools)


def read_tbl(path: str | os.PathLike[str]) -> ToolTable:
    """Read a tool table file (PlannerError naming the file when it cannot be read)."""
    return parse_tbl(read_text(path, TOOL_TABLE), str(path))


def _num(v: float) -> str:
    text = repr(float(v))            # the shortest text that reads back to the same number
    return text[:-2] if text.endswith(".0") else text


def format_tbl(table: ToolTable) -> str:
    """The table as LinuxCNC writes it: one line a tool, by tool number."""
    lines = []
    for t in table:
        words = [f"T{t.number}", f"P{t.pocket}"]
        words += [f"{a}{_num(v)}" for a, v in t.offsets_mm]
        if t.diameter_mm:
            words.append(f"D{_num(t.diameter_mm)}")
        words += [f"{a}{_num(v)}" for a, v in t.lathe]
        lines.append(" ".join(words) + (f" ;{t.description}" if t.description else " ;"))
    return "\n".join(lines) + ("\n" if lines else "")
