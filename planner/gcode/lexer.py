"""RS274/NGC line reader: comments, words, numbers, and LinuxCNC expressions/parameters.

One compiled-regex pass per ordinary line (the fast path). Lines with ``[``, ``#`` or
``O`` go through a small recursive-descent reader for LinuxCNC's expression syntax
(``X[1 + 2 * sqrt[2]]``, ``#<name> = 5``, ``Z#<name>``); see the LinuxCNC G-code manual,
chapters "O codes"/"Numbered and named parameters"/"Expressions".
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable

__all__ = ["LexError", "Params", "compact", "evaluate_brackets", "original_column", "read_line"]

# A word: letter + number with optional sign, digits with optional dot, or a leading dot.
_NUM = r"[-+]?(?:\d+\.?\d*|\.\d+)"
# '@' and '^' are LinuxCNC's polar words (radius and angle in the XY plane)
_WORD_RE = re.compile(r"([A-Z@^])(" + _NUM + r")")
_LINE_RE = re.compile(r"(?:[A-Z@^]" + _NUM + r")*")
_COMMENT_RE = re.compile(r"\([^()]*\)")


class LexError(Exception):
    """A syntax error at a 0-based index into the compact (comment- and space-free) line."""

    def __init__(self, message: str, index: int = 0, raw_col: int | None = None):
        super().__init__(message)
        self.message = message
        self.index = index
        self.raw_col = raw_col  # 1-based column in the raw line if already known


class Params:
    """Numbered (#1-#5602) and named (#<name>) parameters; unset numbered ones read as 0.

    Named parameters are local to the subroutine that sets them (``named``: the current
    scope's), except those starting with ``_``, which are global (``globals``); ``system``
    answers LinuxCNC's predefined read-only ones (``#<_x>``, ``#<_line>``, ...) or None."""

    def __init__(self) -> None:
        self.numbered: dict[int, float] = {}
        self.named: dict[str, float] = {}
        self.globals: dict[str, float] = {}
        self.system: Callable[[str], float | None] = lambda name: None
        # read-only numbered ones computed when read (#5420-#5428 the current position, #5021-
        # #5029 the machine position, #5400-#5410 the tool in the spindle and its table data)
        self.system_numbered: Callable[[int], float | None] = lambda number: None

    def get_numbered(self, number: int) -> float:
        computed = 5420 <= number <= 5428 or 5021 <= number <= 5029 or 5400 <= number <= 5410
        v = self.system_numbered(number) if computed else None
        return self.numbered.get(number, 0.0) if v is None else v

    def get_named(self, name: str) -> float | None:
        if name.startswith("_"):
            v = self.globals.get(name)
            return self.system(name) if v is None else v
        return self.named.get(name)

    def set_named(self, name: str, value: float) -> None:
        (self.globals if name.startswith("_") else self.named)[name] = value


def _strip_comments(raw: str) -> str:
    """Remove ( ) comments and everything after ';'. Raises LexError with the raw column."""
    out = []
    i = 0
    n = len(raw)
    while i < n:
        ch = raw[i]
        if ch == "(":
            j = raw.find(")", i + 1)
            if j < 0:
                raise LexError("unclosed comment: '(' without ')'", raw_col=i + 1)
            k = raw.find("(", i + 1, j)
            if k >= 0:
                raise LexError("nested comment: '(' inside a comment", raw_col=k + 1)
            i = j + 1
            out.append(" ")  # a comment separates like a space (it is removed anyway)
            continue
        if ch == ";":
            break
        if ch == ")":
            raise LexError("')' without '('", raw_col=i + 1)
        out.append(ch)
        i += 1
    return "".join(out)


def original_column(raw: str, index: int) -> int:
    """1-based column in ``raw`` of the character at ``index`` of the compact line."""
    count = 0
    i = 0
    n = len(raw)
    while i < n:
        ch = raw[i]
        if ch == "(":
            j = raw.find(")", i + 1)
            i = n if j < 0 else j + 1
            continue
        if ch == ";":
            break
        if not ch.isspace():
            if count == index:
                return i + 1
            count += 1
        i += 1
    return max(1, min(n, i) + (1 if index >= count else 0))


def compact(raw: str) -> str:
    """The line without comments and whitespace, upper case (what the words are read from)."""
    code = _strip_comments(raw) if ("(" in raw or ";" in raw or ")" in raw) else raw
    return "".join(code.split()).upper()


#: the longest block of code read (its words and expressions, comments aside): LinuxCNC refuses
#: any line over 255 characters; a longer one here is most likely a file that is no program,
#: and its words would each cost a Python object
MAX_CODE_CHARS = 4096


def read_line(raw: str, params: Params | None) -> tuple[list, list[tuple[object, float]]]:
    """Words of one line (block delete and '%' handled by the caller).

    Returns (words, assignments): words as (LETTER, value) in order, value a number's text
    (fast path) or a float (expression path): ``float(value)`` works for both; assignments
    as (key, value) for parameter settings, applied after the line (LinuxCNC rule).
    """
    code = compact(raw)
    if len(code) > MAX_CODE_CHARS:
        raise LexError(f"{len(code):,} characters of code in one block (comments aside): more than "
                       f"{MAX_CODE_CHARS:,}, the most a block may have (LinuxCNC reads 255 a line)", 0)
    if "#" in code or "[" in code or "O" in code:
        return _Reader(code, params).read()
    m = _LINE_RE.match(code)
    end = m.end() if m is not None else 0
    if end != len(code):
        raise LexError(_bad_char_message(code, end), end)
    return _WORD_RE.findall(code), []  # values as text here; the caller applies float()


def _bad_char_message(code: str, i: int) -> str:
    ch = code[i]
    if ch.isalpha():
        return f"letter '{ch}' without a number"
    if ch.isdigit() or ch in ".+-":
        return f"unexpected number text '{code[i:i + 8]}' (two decimal points, or a number without a letter?)"
    if not ch.isprintable():            # a NUL or a control byte is named, never written raw
        return f"unexpected character U+{ord(ch):04X}"
    return f"unexpected character '{ch}'"


# ---------------------------------------------------------------- expressions (slow path)

_FUNCS_1: dict[str, Callable[[float], float]] = {
    "ABS": abs,
    "ACOS": lambda v: math.degrees(math.acos(v)),
    "ASIN": lambda v: math.degrees(math.asin(v)),
    "COS": lambda v: math.cos(math.radians(v)),
    "SIN": lambda v: math.sin(math.radians(v)),
    "TAN": lambda v: math.tan(math.radians(v)),
    "EXP": math.exp,
    "LN": math.log,
    "SQRT": math.sqrt,
    "FIX": lambda v: float(math.floor(v)),
    "FUP": lambda v: float(math.ceil(v)),
    "ROUND": lambda v: float(math.floor(v + 0.5)) if v >= 0 else -float(math.floor(-v + 0.5)),
}
# Binary operators by precedence level (LinuxCNC: ** > * / MOD > + - > comparisons > logic).
_OPS = [
    ("AND", 1), ("OR", 1), ("XOR", 1),
    ("EQ", 2), ("NE", 2), ("GT", 2), ("GE", 2), ("LT", 2), ("LE", 2),
    ("MOD", 4), ("**", 5), ("+", 3), ("-", 3), ("*", 4), ("/", 4),
]
_OPS_BY_LENGTH = sorted(_OPS, key=lambda o: -len(o[0]))
_NUM_RE = re.compile(_NUM)
_NAME_RE = re.compile(r"[A-Z]+")
_MAX_NUMBERED = 5602   # LinuxCNC RS274NGC_MAX_PARAMETERS - 1


class _Reader:
    def __init__(self, code: str, params: Params | None):
        self.s = code
        self.i = 0
        self.params = params if params is not None else Params()

    def fail(self, message: str) -> LexError:
        return LexError(message, min(self.i, max(len(self.s) - 1, 0)))

    def read(self) -> tuple[list[tuple[str, float]], list[tuple[object, float]]]:
        s = self.s
        words: list[tuple[str, float]] = []
        assigns: list[tuple[object, float]] = []
        if s.startswith("O"):
            if re.fullmatch(r"O\d+", s):  # Fanuc-style program number line: "O0001"
                return [("O", float(s[1:]))], []
            if re.fullmatch(r"O<[^>]*>", s):  # ... or name, as LinuxCNC 2.9 reads it: "O<part>"
                return [("O", 0.0)], []
            self.i = 0
            raise self.fail("unknown O-word statement (o-codes are sub, endsub, call, return, if, elseif, "
                            "else, endif, while, endwhile, do, repeat, endrepeat, break, continue)")
        while self.i < len(s):
            ch = s[self.i]
            if ch == "#":
                start = self.i
                key = self.param_key()
                if self.i < len(s) and s[self.i] == "=":
                    self.i += 1
                    assigns.append((key, self.value()))
                else:
                    self.i = start
                    raise self.fail("parameter reference without a word letter (expected '#...=value')")
            elif "A" <= ch <= "Z" or ch in "@^":
                if ch == "O":
                    raise self.fail("an O-word must begin its line")
                self.i += 1
                words.append((ch, self.value()))
            else:
                raise self.fail(_bad_char_message(self.s, self.i) if not ch.isprintable()
                                else f"unexpected character '{ch}'")
        return words, assigns

    # value: number | [expr] | #param | FUNC[expr] | sign + one of those
    def value(self) -> float:
        s = self.s
        if self.i >= len(s):
            raise self.fail("missing value at end of line")
        ch = s[self.i]
        if ch in "+-" and self.i + 1 < len(s) and s[self.i + 1] in "[#":
            self.i += 1
            v = self.value()
            return -v if ch == "-" else v
        if ch == "[":
            self.i += 1
            v = self.expr()
            self.expect("]")
            return v
        if ch == "#":
            return self.param_value()
        if "A" <= ch <= "Z":
            return self.function()
        m = _NUM_RE.match(s, self.i)
        if not m:
            raise self.fail(f"expected a number, found '{s[self.i:self.i + 8]}'")
        self.i = m.end()
        return float(m.group())

    def expect(self, text: str) -> None:
        if not self.s.startswith(text, self.i):
            raise self.fail(f"expected '{text}'")
        self.i += len(text)

    def function(self) -> float:
        s = self.s
        m = _NAME_RE.match(s, self.i)
        name = m.group() if m else ""
        if m is not None and name == "ATAN":
            self.i = m.end()
            self.expect("[")
            a = self.expr()
            self.expect("]")
            self.expect("/")
            self.expect("[")
            b = self.expr()
            self.expect("]")
            return math.degrees(math.atan2(a, b))
        if m is not None and name == "EXISTS":
            # a named parameter that is set, or a numbered one in range (those always exist)
            self.i = m.end()
            self.expect("[")
            self.expect("#")
            if self.i < len(s) and s[self.i] == "<":
                self.i -= 1
                key = self.param_key()
                found = self.lookup(key, must=False) is not None
            else:
                v = self.value()
                found = math.isfinite(v) and v == round(v) and 1 <= v <= _MAX_NUMBERED
            self.expect("]")
            return 1.0 if found else 0.0
        for fname, fn in _FUNCS_1.items():
            if name.startswith(fname) and s.startswith(fname + "[", self.i):
                self.i += len(fname) + 1
                a = self.expr()
                self.expect("]")
                try:
                    return float(fn(a))
                except (ValueError, OverflowError):
                    raise self.fail(f"{fname}[{a:g}] is outside the function's domain") from None
        raise self.fail(f"unknown function or misplaced letters '{name[:10]}'")

    def expr(self, min_level: int = 1) -> float:
        """Precedence climbing; ** is right-associative."""
        left = self.unary()
        while True:
            op = self.peek_op()
            if op is None or op[1] < min_level:
                return left
            name, level = op
            self.i += len(name)
            right = self.expr(level if name == "**" else level + 1)
            left = self.apply(name, left, right)

    def peek_op(self) -> tuple[str, int] | None:
        s = self.s
        for name, level in _OPS_BY_LENGTH:
            if s.startswith(name, self.i):
                return name, level
        return None

    def unary(self) -> float:
        s = self.s
        if (self.i + 1 < len(s) and s[self.i] in "+-"
                and (s[self.i + 1] in "[#" or "A" <= s[self.i + 1] <= "Z")):
            ch = s[self.i]
            self.i += 1
            v = self.unary()
            return -v if ch == "-" else v
        return self.value()

    def apply(self, op: str, a: float, b: float) -> float:
        try:
            if op == "+":
                return a + b
            if op == "-":
                return a - b
            if op == "*":
                return a * b
            if op == "/":
                return a / b
            if op == "**":
                return float(a**b)
            if op == "MOD":
                r = math.fmod(a, b)
                return r + abs(b) if r < 0.0 else r  # LinuxCNC: result in [0, |b|)
        except (ZeroDivisionError, OverflowError, ValueError, TypeError):
            raise self.fail(f"arithmetic error: {a:g} {op} {b:g}") from None
        return float(
            {
                "EQ": a == b, "NE": a != b, "GT": a > b, "GE": a >= b, "LT": a < b, "LE": a <= b,
                "AND": bool(a) and bool(b), "OR": bool(a) or bool(b), "XOR": bool(a) != bool(b),
            }[op]
        )

    def param_key(self) -> str | int:
        s = self.s
        self.expect("#")
        if self.i < len(s) and s[self.i] == "<":
            j = s.find(">", self.i)
            if j < 0:
                raise self.fail("named parameter without closing '>'")
            name = s[self.i + 1:j]
            if not name:
                raise self.fail("empty parameter name '#<>'")
            self.i = j + 1
            return name
        v = self.value()
        # NaN or infinity (#[1e400-1e400]) is no parameter number: refuse before rounding it
        n = int(round(v)) if math.isfinite(v) else 0
        if abs(v - n) > 1e-9 or not 1 <= n <= _MAX_NUMBERED:
            raise self.fail(f"parameter number #{v:g} out of range (1-{_MAX_NUMBERED})")
        return n

    def lookup(self, key: str | int, must: bool = True) -> float | None:
        if isinstance(key, str):
            v = self.params.get_named(key)
            if v is None and must:
                raise self.fail(f"named parameter #<{key.lower()}> is not defined")
            return v
        return self.params.get_numbered(key)

    def param_value(self) -> float:
        return self.lookup(self.param_key())  # type: ignore[return-value]


def evaluate_brackets(code: str, params: Params | None, offset: int = 0) -> list[float]:
    """The values of a sequence of bracketed expressions (``[1][#2+3]``), as O-word calls,
    conditions and returns carry them; LexError indices count from ``offset``."""
    reader = _Reader(code, params)
    out: list[float] = []
    try:
        while reader.i < len(code):
            if code[reader.i] != "[":
                found = code[reader.i:reader.i + 8]
                raise reader.fail(f"expected '[' (an expression in brackets), found '{found}'")
            out.append(reader.value())
    except LexError as exc:
        exc.index += offset
        raise
    return out
