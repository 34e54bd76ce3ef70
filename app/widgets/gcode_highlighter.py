"""G-code syntax highlighting: motion words, M codes, axis words, feeds, comments, errors."""

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


# (pattern, format); later rules win where they overlap (comments last).
RULES: tuple[tuple[re.Pattern[str], QTextCharFormat], ...] = (
    (re.compile(r"[Nn]\s*\d+"), _fmt("#7a8796")),
    (re.compile(r"[Gg]\s*0*[23](?!\d)(?:\.\d+)?"), _fmt("#40e0d0", bold=True)),   # arcs: turquoise
    (re.compile(r"[Gg]\s*0*1(?!\d)"), _fmt("#4cdf6a", bold=True)),                  # lines: green
    (re.compile(r"[Gg]\s*0*0(?!\d)"), _fmt("#ffb347", bold=True)),                  # rapids
    (re.compile(r"[Gg]\s*(?:[4-9]\d*|1\d+|2\d+|3\d+)(?:\.\d+)?"), _fmt("#8fb8ff", bold=True)),
    (re.compile(r"[Mm]\s*\d+"), _fmt("#ff7fd0", bold=True)),
    (re.compile(r"[XYZABCxyzabc]\s*[-+]?\s*(?:\d+\.?\d*|\.\d+)"), _fmt("#f2f6fa")),
    (re.compile(r"[IJKRPijkrp]\s*[-+]?\s*(?:\d+\.?\d*|\.\d+)"), _fmt("#c0a0ff")),
    (re.compile(r"[FSTfst]\s*[-+]?\s*(?:\d+\.?\d*|\.\d+)"), _fmt("#ffd27f")),
    (re.compile(r"^\s*/"), _fmt("#7a8796")),
    (re.compile(r"\([^)]*\)?|;.*$"), _fmt("#8a9aa8", italic=True)),
    (re.compile(r"^%\s*$"), _fmt("#7a8796")),
)


class GCodeHighlighter(QSyntaxHighlighter):
    def __init__(self, document: QTextDocument) -> None:
        super().__init__(document)

    def highlightBlock(self, text: str) -> None:  # noqa: N802 - Qt override
        for pattern, fmt in RULES:
            for m in pattern.finditer(text):
                self.setFormat(m.start(), m.end() - m.start(), fmt)
