"""The translation catalogue, without Qt: mark strings, extract them, update the .ts files.

    python -m tools.i18n_catalog        # add new strings to resources/translations/*.ts, compile .qm

Strings are found by reading the sources (``tr("...")`` and ``N_("...")`` calls with literal
text), so the test suite can check that every one has a translation.
"""

from __future__ import annotations

import ast
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

from app.i18n import CONTEXT
from resources import TRANSLATIONS

APP = Path(__file__).resolve().parent.parent / "app"
MARKERS = ("tr", "N_")
EXCLUDED = ("machine",)  # the controller package has its own (English) messages


def extract_strings(root: Path = APP) -> dict[str, list[str]]:
    """{source text: [file:line, ...]} for every marked literal string under ``root``."""
    found: dict[str, list[str]] = {}
    for path in sorted(root.rglob("*.py")):
        rel = path.relative_to(root)
        if rel.parts and rel.parts[0] in EXCLUDED:
            continue
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        for node in ast.walk(tree):
            if not isinstance(node, ast.Call) or not node.args:
                continue
            func = node.func
            name = getattr(func, "id", "") or getattr(func, "attr", "")
            arg = node.args[0]
            if name in MARKERS and isinstance(arg, ast.Constant) and isinstance(arg.value, str):
                found.setdefault(arg.value, []).append(f"{rel}:{node.lineno}")
    return found


def read_ts(path: Path) -> dict[str, str]:
    """{source: translation} of the finished messages of a .ts file."""
    out: dict[str, str] = {}
    if not path.exists():
        return out
    for message in ET.parse(path).getroot().iter("message"):
        source = message.findtext("source") or ""
        tr_el = message.find("translation")
        done = tr_el is not None and tr_el.get("type") not in ("unfinished", "obsolete", "vanished")
        if done and tr_el.text:
            out[source] = tr_el.text
    return out


def write_ts(path: Path, language: str, strings: dict[str, list[str]], translations: dict[str, str]) -> None:
    ts = ET.Element("TS", version="2.1", language=language)
    context = ET.SubElement(ts, "context")
    ET.SubElement(context, "name").text = CONTEXT
    for source in sorted(strings):
        message = ET.SubElement(context, "message")
        where = strings[source][0]
        file_name, _, line = where.rpartition(":")
        ET.SubElement(message, "location", filename=f"../../app/{file_name}", line=line)
        ET.SubElement(message, "source").text = source
        translation = ET.SubElement(message, "translation")
        if source in translations:
            translation.text = translations[source]
        else:
            translation.set("type", "unfinished")
    ET.indent(ts)
    body = ET.tostring(ts, encoding="unicode")
    path.write_text('<?xml version="1.0" encoding="utf-8"?>\n<!DOCTYPE TS>\n' + body + "\n", encoding="utf-8")


def update(directory: Path = TRANSLATIONS) -> list[str]:
    """Refresh every .ts from the sources; returns the strings still untranslated (all files)."""
    strings = extract_strings()
    missing = []
    for ts in sorted(directory.glob("cnc_*.ts")):
        language = ts.stem.split("_", 1)[1]
        translations = read_ts(ts)
        write_ts(ts, language, strings, translations)
        missing += [f"{ts.name}: {s!r}" for s in strings if s not in translations]
    return missing


def main() -> int:
    missing = update()
    from app.i18n import compile_translations

    for qm in compile_translations():
        print(f"compiled {qm}")
    for m in missing:
        print(f"untranslated: {m}")
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main())
