"""G-code syntax highlighting: motion words, M codes, axis words, feeds, comments.

One regular expression with a named group per token kind, scanned once per line (a
35,000-line program highlights in a fraction of a second).
"""

from __future__ import annotations

import re

from PySide6.QtGui import QColor, QFont, QSyntaxHighlighter, QTextCharFormat, QTextDocument


def _fmt(color: str, bold: bool = False, italic: bool = False) -> QTextCharFormat:
    f = QTextCharFormat()
    f.setForeground(QColor(color))
    if bold:
        f.setFontWeight(QFont.Weight.Bold)
    f.setFontItalic(italic)
    return f


_NUMBER = r"\s*[-+]?\s*(?:\d+\.?\d*|\.\d+)"
# (group name, pattern, format), earlier alternatives win at the same position.
TOKENS: tuple[tuple[str, str, QTextCharFormat], ...] = (
    ("comment", r"\([^)]*\)?|;.*$", _fmt("#8a9aa8", italic=True)),
    ("percent", r"^%\s*$", _fmt("#7a8796")),
    ("delete", r"^\s*/", _fmt("#7a8796")),
    ("number", r"[Nn]\s*\d+", _fmt("#7a8796")),
    ("arc", r"[Gg]\s*0*[23](?![\d.])", _fmt("#40e0d0", bold=True)),   # arcs: turquoise (paper)
    ("line", r"[Gg]\s*0*1(?![\d.])", _fmt("#4cdf6a", bold=True)),     # lines: green (paper)
    ("rapid", r"[Gg]\s*0*0(?![\d.])", _fmt("#ffb347", bold=True)),
    ("gcode", r"[Gg]\s*\d+(?:\.\d+)?", _fmt("#8fb8ff", bold=True)),
    ("mcode", r"[Mm]\s*\d+", _fmt("#ff7fd0", bold=True)),
    ("axis", r"[XYZABCxyzabc]" + _NUMBER, _fmt("#f2f6fa")),
    ("arcword", r"[IJKRPijkrp]" + _NUMBER, _fmt("#c0a0ff")),
    ("feed", r"[FSTfst]" + _NUMBER, _fmt("#ffd27f")),
)
PATTERN = re.compile("|".join(f"(?P<{name}>{pattern})" for name, pattern, _ in TOKENS))
FORMATS: dict[str, QTextCharFormat] = {name: fmt for name, _, fmt in TOKENS}


def tokens(text: str) -> list[tuple[int, int, str]]:
    """(start, length, kind) of every highlighted token of one line."""
    return [(m.start(), m.end() - m.start(), m.lastgroup or "") for m in PATTERN.finditer(text)]


class GCodeHighlighter(QSyntaxHighlighter):
    def __init__(self, document: QTextDocument) -> None:
        super().__init__(document)

    def highlightBlock(self, text: str) -> None:  # noqa: N802 - Qt override
        set_format = self.setFormat
        for m in PATTERN.finditer(text):
            set_format(m.start(), m.end() - m.start(), FORMATS[m.lastgroup])  # type: ignore[index]
