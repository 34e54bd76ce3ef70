"""The translation catalogue, without Qt: mark strings, extract them, update the .ts files.

    python -m tools.i18n_catalog        # add new strings to resources/translations/*.ts, compile .qm

Strings are found by reading the sources (``tr("...")`` and ``N_("...")`` calls with literal
text), so the test suite can check that every one has a translation.
"""

from __future__ import annotations

import ast
import re
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

from app.i18n import CONTEXT
from resources import TRANSLATIONS

ROOT = Path(__file__).resolve().parent.parent
APP = ROOT / "app"
MARKERS = ("tr", "N_")
EXCLUDED = ("machine",)  # the controller package has its own (English) messages

# The interpreter's messages (planner/gcode, planner/geometry whose refusals it passes on, and the
# bounded reading of its files in planner/core/reading.py) and
# the controller's (app/machine): neither imports Qt or marks its sentences, so they are gathered
# here from the sources and written to app/message_text.py as templates, where the panel's
# catalogue and ``localize`` find them.
INTERPRETER = (ROOT / "planner" / "gcode", ROOT / "planner" / "geometry",
               ROOT / "planner" / "core" / "reading.py")
CONTROLLER = (ROOT / "app" / "machine",)
MESSAGE_TEXT = APP / "message_text.py"
# how a message is raised or recorded, and which argument holds it
MESSAGE_CALLS = {"BlockError": 0, "LexError": 0, "StructureError": 0, "G7xError": 0, "PlannerError": 0,
                 "GeometryError": 0, "ValueError": 0, "error": -1, "error_in": -1}
CONTROLLER_CALLS = {"refuse": 1, "raise_alarm": 1, "stop_job": 0, "emit": 0, "fail": 0, "stop": 0,
                    "ControllerError": 0, "CommandResult": 1, "show_message": 0,
                    "alarm_stop": 0, "SignalDef": 4}
# declarations whose keyword arguments are the operator's words, short as they may be (a
# probing wizard's button title, its name in sentences, what its aim's buttons mean)
KEYWORD_CALLS = {"WizardSpec": ("title", "name", "prompt", "along_title")}
# functions whose returned text is a refusal (``refusal(...)`` returns "" or why not)
REFUSAL_FUNCTIONS = re.compile(r"refusal|problem|^_?why")
MIN_WORDS = 6  # letters outside the values: "{0}: {1}" would match any sentence


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


def _template(node: ast.expr) -> str | None:
    """A message expression as a template: literal text kept (braces doubled), each value
    ``{0}``, ``{1}`` ... in order; None when it is not literal text or an f-string."""
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return node.value.replace("{", "{{").replace("}", "}}")
    if isinstance(node, ast.JoinedStr):
        out: list[str] = []
        n = 0
        for value in node.values:
            if isinstance(value, ast.Constant):
                out.append(str(value.value).replace("{", "{{").replace("}", "}}"))
            else:
                out.append(f"{{{n}}}")
                n += 1
        return "".join(out)
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add):
        left, right = _template(node.left), _template(node.right)
        if left is None or right is None:
            return None
        k = len(_PLACEHOLDER.findall(left))
        return left + _PLACEHOLDER.sub(lambda m: f"{{{int(m.group(1)) + k}}}", right)
    return None


_PLACEHOLDER = re.compile(r"(?<!\{)\{(\d+)\}")


def literal_letters(template: str) -> int:
    """How many letters a template has outside its values (how specific it is)."""
    return sum(c.isalpha() for c in _PLACEHOLDER.sub("", template))


def interpreter_templates(roots: tuple[Path, ...] = INTERPRETER) -> list[str]:
    """The interpreter's messages as templates, sorted: each raised error's text, and each
    module-level constant sentence (ZERO_FEED ...) that one is raised with."""
    return _templates(roots, MESSAGE_CALLS)


def controller_templates(roots: tuple[Path, ...] = CONTROLLER) -> list[str]:
    """The controller's refusals, alarms and messages as templates, sorted: what its commands
    refuse with, raise and say, and what its ``refusal`` functions return."""
    return _templates(roots, CONTROLLER_CALLS, REFUSAL_FUNCTIONS)


def _returned(tree: ast.AST, names: re.Pattern[str] | None) -> set[int]:
    """The ids of the expressions returned by the functions whose name matches ``names``."""
    out: set[int] = set()
    if names is None:
        return out
    for fn in ast.walk(tree):
        if isinstance(fn, ast.FunctionDef) and names.search(fn.name):
            for node in ast.walk(fn):
                if isinstance(node, ast.Return) and node.value is not None:
                    out.add(id(node.value))
    return out


def _called(node: ast.Call) -> str:
    """The name of what ``node`` calls: ``f(...)`` or ``x.f(...)`` -> "f"."""
    return getattr(node.func, "id", "") or getattr(node.func, "attr", "")


def _templates(roots: tuple[Path, ...], calls: dict[str, int], refusals: re.Pattern[str] | None = None
               ) -> list[str]:
    found: set[str] = set()
    for root in roots:
        for path in [root] if root.is_file() else sorted(root.rglob("*.py")):
            tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
            returned = _returned(tree, refusals)
            for node in ast.walk(tree):
                template = None
                if (isinstance(node, ast.Assign) and len(node.targets) == 1
                        and isinstance(node.value, ast.Dict) and isinstance(node.targets[0], ast.Name)
                        and node.targets[0].id.isupper()):
                    # a table of sentences (what an MDI block may not do, and why): each value
                    for value in node.value.values:
                        said = _template(value)
                        if said is not None and " " in said and literal_letters(said) >= MIN_WORDS:
                            found.add(said)
                    continue
                if isinstance(node, ast.Call) and _called(node) in KEYWORD_CALLS:
                    said_words = KEYWORD_CALLS[_called(node)]
                    for keyword in node.keywords:
                        said = _template(keyword.value) if keyword.arg in said_words else None
                        if said:
                            found.add(said)
                    continue
                if id(node) in returned and isinstance(node, ast.expr):
                    template = _template(node)
                elif isinstance(node, ast.Call) and node.args:
                    where = calls.get(_called(node))
                    if where is not None and -len(node.args) <= where < len(node.args):
                        template = _template(node.args[where])
                elif (isinstance(node, ast.Assign) and len(node.targets) == 1
                      and isinstance(node.targets[0], ast.Name) and node.targets[0].id.isupper()):
                    template = _template(node.value)
                    if template is not None and " " not in template:
                        template = None          # a constant that is no sentence
                if template is not None and " " in template and literal_letters(template) >= MIN_WORDS:
                    found.add(template)
    return sorted(found)


def _entries(templates: list[str]) -> list[str]:
    return [f"    N_({t!r}),  # noqa: E501" if len(t) > 90 else f"    N_({t!r})," for t in templates]


def message_text_source(controller: list[str], interpreter: list[str]) -> str:
    """The text of app/message_text.py for the controller's and the interpreter's templates."""
    lines = ['"""The controller\'s and the interpreter\'s messages as templates for the panel\'s',
             "language (``app.controller_text.localize``).",
             "",
             "Written by ``python -m tools.i18n_catalog`` from app/machine, planner/gcode and",
             "planner/geometry; a test fails when a message there is not here. Do not edit: change the",
             'sources and run the tool again."""',
             "",
             "from app.i18n import N_",
             "",
             '__all__ = ["CONTROLLER_TEMPLATES", "GCODE_TEMPLATES"]',
             "",
             "CONTROLLER_TEMPLATES: tuple[str, ...] = (",
             *_entries(controller),
             ")",
             "",
             "GCODE_TEMPLATES: tuple[str, ...] = (",
             *_entries(interpreter),
             ")",
             ""]
    return "\n".join(lines)


def current_message_text() -> str:
    return message_text_source(controller_templates(), interpreter_templates())


def write_message_text(path: Path = MESSAGE_TEXT) -> bool:
    """Write app/message_text.py when the messages changed; True when written."""
    text = current_message_text()
    if path.exists() and path.read_text(encoding="utf-8") == text:
        return False
    path.write_text(text, encoding="utf-8")
    return True


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
    write_message_text()
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
