"""The O-word language of LinuxCNC 2.9 (subroutines and control flow), its static part: which
lines are control statements, and where each one leads. ``scan`` reads a program's lines once
and matches every ``sub``/``endsub``, ``if``/``elseif``/``else``/``endif``, ``while``/``endwhile``,
``do``/``while``, ``repeat``/``endrepeat`` by their label (``o100`` or ``o<name>``), and resolves
``break``/``continue`` to their loop. The interpreter (``planner.gcode.interpreter``) runs the program
with these jump tables; a mismatch is an error naming the line and what is missing.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Any

from planner.gcode.lexer import LexError, compact

__all__ = ["KEYWORDS", "Statement", "Structure", "StructureError", "has_control_flow", "scan"]

KEYWORDS = ("SUB", "ENDSUB", "CALL", "RETURN", "IF", "ELSEIF", "ELSE", "ENDIF", "WHILE", "ENDWHILE", "DO",
            "REPEAT", "ENDREPEAT", "BREAK", "CONTINUE")
_KEYWORDS_RE = "|".join(sorted(KEYWORDS, key=len, reverse=True))
_STMT_RE = re.compile(r"(?:N\d+(?:\.\d*)?)?O(\d+|<[^>]*>)(" + _KEYWORDS_RE + r")(.*)\Z")
# LinuxCNC 2.9 also calls a subroutine whose number is an expression or a parameter:
# O[#2 * 10] call, O#<sub> call
_CALL_EXPR_RE = re.compile(r"(?:N\d+(?:\.\d*)?)?O(\[.*\]|#<[^>]*>|#\d+)CALL(.*)\Z")
# a quick look for any control statement, so that programs without one keep the plain path
_ANY_RE = re.compile(r"(?im)^[ \t]*(?:/[ \t]*)?(?:n[ \t\d.]*)?(?:o[ \t]*(?:\d+|<[^>\n]*>)[ \t]*"
                     r"(?:sub|endsub|call|return|if|elseif|else|endif|while|endwhile|do|repeat|endrepeat|break"
                     r"|continue)\b|m[ \t]*0*9[ \t]*[89](?![ \t]*[\d.]))")
# Fanuc-style subprograms, which LinuxCNC 2.9 runs too: a line holding only "O<number>" starts
# one, "M98 P<number> [L<count>]" (a line of its own) calls it, "M99" returns from it (in the
# main program it ends the program, as M02 does)
_PROG_RE = re.compile(r"(?:N\d+(?:\.\d*)?)?O(\d+|<[^>]*>)\Z")
_M98_RE = re.compile(r"(?:N\d+(?:\.\d*)?)?M0*98(?![\d.])(.*)\Z")
_M99_RE = re.compile(r"(?:N\d+(?:\.\d*)?)?M0*99\Z")


def has_control_flow(text: str | bytes, piece_chars: int = 1 << 20) -> bool:
    """Whether the program (its text, or its UTF-8 bytes) has an O-word statement. Searched a
    megabyte of whole lines at a time: a regular expression holds the interpreter lock for as
    long as it searches, and the panel's GUI thread must not wait a quarter of a second on a
    program of millions of lines."""
    raw = isinstance(text, bytes)
    newline: Any = b"\n" if raw else "\n"
    letters: Any = (b"o", b"O", b"m", b"M") if raw else "oOmM"
    start, n = 0, len(text)
    while start < n:
        end = text.find(newline, min(n, start + piece_chars))
        end = n if end < 0 else end
        # no letter O and no M98/M99 in the piece (a CAM raster): no statement, no regular
        # expression (one letter: a memchr); bytes are decoded only for such a piece
        if any(text.find(c, start, end) >= 0 for c in letters):
            found = (_ANY_RE.search(text[start:end].decode("utf-8", "replace")) if isinstance(text, bytes)
                     else _ANY_RE.search(text, start, end))    # '^' matches at start: a line start
            if found is not None:
                return True
        start = end + 1
    return False


class StructureError(Exception):
    def __init__(self, index: int, col: int, message: str) -> None:
        super().__init__(message)
        self.index = index      # 0-based line index
        self.col = col
        self.message = message


@dataclass(slots=True)
class Statement:
    index: int                  # 0-based line index
    label: str                  # "100" or "<name>" (lower case inside the brackets)
    keyword: str
    rest: str                   # the compact text after the keyword (conditions, arguments)
    # where it leads (line indices), filled by scan
    target: int = -1            # if/elseif: next branch; while: its endwhile; do-while's while: its do;
    #                             repeat: endrepeat; break/continue: the loop's statement; sub: endsub
    end: int = -1               # if-chain: its endif; loops: the closing statement
    loop: int = -1              # break/continue: the loop's opening statement
    # the name LinuxCNC keeps its place under: a local statement's label is qualified by the
    # subroutine it is written in ("sub#label", "#label" outside any), a sub's is global
    qname: str = ""


@dataclass(slots=True)
class Structure:
    statements: dict[int, Statement] = field(default_factory=dict)
    # label -> every (sub, endsub) of that label, in the file's order: LinuxCNC defines a sub
    # as the program runs through it (or as a call finds it ahead), so one inside an if is
    # defined only when that branch runs, and a label may have one in each branch
    subs: dict[str, list[tuple[int, int]]] = field(default_factory=dict)
    programs: dict[str, int] = field(default_factory=dict)            # Fanuc "O<n>" -> its line


def _label(text: str) -> str:
    return text.lower() if text.startswith("<") else str(int(text))


def _name(label: str) -> str:
    return f"o{label}"


def scan(lines: list[str]) -> Structure:
    """Control statements of ``lines`` and their matching; raises StructureError."""
    st = Structure()
    stack: list[Statement] = []
    for index, raw in enumerate(lines):
        if "o" not in raw and "O" not in raw and "9" not in raw:
            continue
        try:
            code = compact(raw)
        except LexError:
            continue                       # the line's own error is reported when it runs
        if code.startswith("/"):
            code = code[1:]
        m = _STMT_RE.match(code)
        if m is None:
            expr = _CALL_EXPR_RE.match(code)
            if expr is not None:             # the label is evaluated when the call runs
                st.statements[index] = Statement(index, expr.group(1), "CALL", expr.group(2))
            else:
                _fanuc(st, index, code)
            continue
        col = raw.upper().find("O") + 1
        s = Statement(index, _label(m.group(1)), m.group(2), m.group(3))
        st.statements[index] = s
        kw, label = s.keyword, s.label
        sub = next((x.label for x in stack if x.keyword == "SUB"), "")
        s.qname = label if kw in ("SUB", "ENDSUB", "CALL", "RETURN") else f"{sub}#{label}"
        if kw == "SUB":
            if any(x.keyword == "SUB" for x in stack):
                raise StructureError(index, col, f"{_name(label)} sub inside another sub definition")
            stack.append(s)
        elif kw in ("IF", "DO", "REPEAT"):
            stack.append(s)
        elif kw == "WHILE":
            if stack and stack[-1].keyword == "DO" and stack[-1].label == label:
                do = stack.pop()           # the closing while of a do-while
                s.target = do.index
                do.end = index
                s.keyword = "DOWHILE"
            else:
                stack.append(s)
        elif kw in ("ELSEIF", "ELSE"):
            top = _top(stack, "IF", label, index, col, kw)
            previous = _last_branch(st, top)
            if previous.keyword == "ELSE":
                raise StructureError(index, col, f"{_name(label)} {kw.lower()} after {_name(label)} else")
            previous.target = index
        elif kw == "ENDIF":
            top = _top(stack, "IF", label, index, col, kw)
            stack.pop()
            _last_branch(st, top).target = index
            k = top.index
            while True:                    # every branch of the chain knows the endif
                branch = st.statements[k]
                branch.end = index
                if branch.target in (index, -1):
                    break
                k = branch.target
        elif kw in ("ENDWHILE", "ENDREPEAT", "ENDSUB"):
            opening = {"ENDWHILE": "WHILE", "ENDREPEAT": "REPEAT", "ENDSUB": "SUB"}[kw]
            top = _top(stack, opening, label, index, col, kw)
            stack.pop()
            top.end = index
            s.target = top.index
            if kw == "ENDSUB":
                st.subs.setdefault(label, []).append((top.index, index))
        elif kw in ("BREAK", "CONTINUE"):
            loop = next((x for x in reversed(stack)
                         if x.label == label and x.keyword in ("WHILE", "DO", "REPEAT")), None)
            if loop is None:
                raise StructureError(index, col, f"{_name(label)} {kw.lower()} outside a loop labelled "
                                     f"{_name(label)}")
            s.loop = loop.index
        elif kw == "RETURN":
            # LinuxCNC returns from the subroutine it is in, whatever the label (often an if's)
            if not any(x.keyword == "SUB" for x in stack):
                raise StructureError(index, col, f"{_name(label)} return outside a subroutine")
    if stack:
        s = stack[-1]
        closing = {"SUB": "endsub", "IF": "endif", "WHILE": "endwhile", "DO": "while", "REPEAT": "endrepeat"}
        raise StructureError(s.index, 1, f"{_name(s.label)} {s.keyword.lower()} without its "
                             f"{_name(s.label)} {closing[s.keyword]}")
    return st


def _fanuc(st: Structure, index: int, code: str) -> None:
    """A Fanuc-style subprogram line, if ``code`` is one: its start "O<n>" (PROG), a call
    "M98 P.. L.." (M98, the words after it in ``rest``) or a return "M99"."""
    m = _PROG_RE.match(code)
    if m is not None:
        label = _label(m.group(1))
        st.programs.setdefault(label, index)    # LinuxCNC finds the first one; a second is no error
        st.statements[index] = Statement(index, label, "PROG", "")
        return
    m = _M98_RE.match(code)
    if m is not None:
        st.statements[index] = Statement(index, "", "M98", m.group(1))
    elif _M99_RE.match(code) is not None:
        st.statements[index] = Statement(index, "", "M99", "")


def _top(stack: list[Statement], keyword: str, label: str, index: int, col: int, kw: str) -> Statement:
    if not stack or stack[-1].keyword != keyword or stack[-1].label != label:
        inside = f" (inside {_name(stack[-1].label)} {stack[-1].keyword.lower()})" if stack else ""
        raise StructureError(index, col, f"{_name(label)} {kw.lower()} without {_name(label)} "
                             f"{keyword.lower()}{inside}")
    return stack[-1]


def _last_branch(st: Structure, opening: Statement) -> Statement:
    s = opening
    while s.target != -1:
        s = st.statements[s.target]
    return s
