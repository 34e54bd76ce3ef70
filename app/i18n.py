"""Translations: Qt .ts files compiled to .qm (pyside6-lrelease), switched at run time.

Every user-visible string goes through ``tr(text)`` (one translation context, "cnc"), so the
catalogue in resources/translations/cnc_tr.ts can be checked against the sources by a test.
Widgets register their texts with ``I18n.bind`` and are retranslated when the language changes;
widgets that compose texts (numbers, states) listen to ``I18n.languageChanged`` instead.
"""

from __future__ import annotations

import hashlib
import shutil
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path

import shiboken6
from PySide6.QtCore import QCoreApplication, QObject, QTranslator, Signal

from app.paths import TRANSLATIONS

# One translation context for every string: the catalogue tool (tools/i18n_catalog.py)
# extracts them by the markers below and writes them under this context.
CONTEXT = "cnc"
__all__ = ["CONTEXT", "I18n", "LANGUAGES", "N_", "compile_translations", "tr"]
LANGUAGES: dict[str, str] = {"en": "English", "tr": "Türkçe"}


def N_(text: str) -> str:  # noqa: N802 - gettext's name: "mark for translation, translate later"
    """Mark a string for the catalogue; it is translated where it is shown (``tr``)."""
    return text


def tr(text: str) -> str:
    """The text in the current language (source strings are English)."""
    return QCoreApplication.translate(CONTEXT, text)


def lrelease_path() -> Path | None:
    """pyside6-lrelease of this interpreter's environment (PySide6-Essentials ships it)."""
    candidate = Path(sys.executable).parent / "pyside6-lrelease"
    if candidate.exists():
        return candidate
    found = shutil.which("pyside6-lrelease") or shutil.which("lrelease")
    return Path(found) if found else None


def source_digest(ts: Path) -> str:
    return hashlib.sha256(ts.read_bytes()).hexdigest()


def digest_path(qm: Path) -> Path:
    """Sidecar holding the sha256 of the .ts a .qm was compiled from. File times are no use
    here: a git checkout gives both files whatever times it likes."""
    return qm.with_name(qm.name + ".sha256")


def is_stale(ts: Path) -> bool:
    qm = ts.with_suffix(".qm")
    stamp = digest_path(qm)
    if not qm.exists() or not stamp.exists():
        return True
    return stamp.read_text(encoding="ascii").strip() != source_digest(ts)


def compile_translations(directory: Path = TRANSLATIONS) -> list[Path]:
    """Compile every stale .ts to .qm; returns the .qm files written."""
    tool = lrelease_path()
    written = []
    for ts in sorted(directory.glob("*.ts")):
        if not is_stale(ts):
            continue
        qm = ts.with_suffix(".qm")
        if tool is None:
            raise RuntimeError(f"{qm} is missing or out of date with {ts.name} and pyside6-lrelease "
                               "is not installed (pip install PySide6-Essentials)")
        subprocess.run([str(tool), "-silent", str(ts), "-qm", str(qm)], check=True)
        digest_path(qm).write_text(source_digest(ts) + "\n", encoding="ascii")
        written.append(qm)
    return written


class I18n(QObject):
    """Owns the installed QTranslator and the registry of bound texts."""

    languageChanged = Signal(str)

    def __init__(self, parent: QObject | None = None) -> None:
        super().__init__(parent)
        self.language = "en"
        self._translator: QTranslator | None = None
        self._bound: list[tuple[QObject, Callable[[str], None], str]] = []

    def set_language(self, language: str) -> None:
        if language not in LANGUAGES:
            raise ValueError(f"unknown language {language!r}; choose one of {', '.join(LANGUAGES)}")
        app = QCoreApplication.instance()
        if self._translator is not None and app is not None:
            app.removeTranslator(self._translator)
            self._translator = None
        if language != "en" and app is not None:
            qm = TRANSLATIONS / f"cnc_{language}.qm"
            ts = qm.with_suffix(".ts")
            if not qm.exists() or (ts.exists() and is_stale(ts)):
                compile_translations()
            translator = QTranslator(self)
            if not translator.load(str(qm)):
                raise RuntimeError(f"could not load translation {qm}")
            app.installTranslator(translator)
            self._translator = translator
        self.language = language
        self._apply()
        self.languageChanged.emit(language)

    def bind(self, owner: QObject, text: str, setter: Callable[[str], None] | None = None) -> None:
        """Call ``setter(tr(text))`` (default ``owner.setText``) now and on every language change."""
        if setter is None:
            setter = owner.setText  # type: ignore[attr-defined]
        setter(tr(text))
        self._bound.append((owner, setter, text))

    def _apply(self) -> None:
        alive = []
        for owner, setter, text in self._bound:
            if shiboken6.isValid(owner):
                setter(tr(text))
                alive.append((owner, setter, text))
        self._bound = alive
