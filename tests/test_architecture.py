"""The layout is the architecture: planner/ and ethercat/ never import Qt, pyqtgraph or app/,
and ethercat/ does not depend on planner/. Checked two ways: statically over every import
statement, and at run time by importing every module in a clean interpreter."""

from __future__ import annotations

import ast
import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
FORBIDDEN = {
    "planner": ("PySide6", "shiboken6", "pyqtgraph", "app"),
    "ethercat": ("PySide6", "shiboken6", "pyqtgraph", "app", "planner"),
}


def imported_modules(path: Path) -> list[tuple[int, str]]:
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    found: list[tuple[int, str]] = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found += [(node.lineno, alias.name) for alias in node.names]
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            found.append((node.lineno, node.module))
    return found


@pytest.mark.parametrize("package", sorted(FORBIDDEN))
def test_no_forbidden_import_statements(package: str) -> None:
    offenders = []
    for path in sorted((ROOT / package).rglob("*.py")):
        for lineno, module in imported_modules(path):
            top = module.split(".")[0]
            if top in FORBIDDEN[package]:
                offenders.append(f"{path.relative_to(ROOT)}:{lineno}: imports {module}")
    assert not offenders, "\n".join(offenders)


def _module_names(package: str) -> list[str]:
    names = []
    for path in sorted((ROOT / package).rglob("*.py")):
        rel = path.relative_to(ROOT).with_suffix("")
        parts = list(rel.parts)
        if parts[-1] == "__main__":
            continue
        if parts[-1] == "__init__":
            parts = parts[:-1]
        names.append(".".join(parts))
    return names


@pytest.mark.parametrize("package", sorted(FORBIDDEN))
def test_importing_every_module_loads_no_forbidden_package(package: str) -> None:
    code = (
        "import importlib, json, sys\n"
        f"for name in {_module_names(package)!r}:\n"
        "    importlib.import_module(name)\n"
        "print(json.dumps(sorted({m.split('.')[0] for m in sys.modules})))\n"
    )
    result = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True,
                            text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    loaded = set(json.loads(result.stdout.strip().splitlines()[-1]))
    assert not loaded & set(FORBIDDEN[package]), sorted(loaded & set(FORBIDDEN[package]))


def test_top_level_layout() -> None:
    for name in ("pyproject.toml", "README.md", "app", "planner", "ethercat", "resources", "tests"):
        assert (ROOT / name).exists(), f"{name} missing at the top level"


MACHINE = ROOT / "app" / "machine"


def _machine_modules() -> list[Path]:
    return sorted(MACHINE.rglob("*.py"))


def test_only_the_facade_knows_the_controller() -> None:
    """The controller's parts get narrow interfaces (``app.machine.ports``), never the facade:
    no module of ``app.machine`` but the facade's own imports it."""
    offenders = []
    for path in _machine_modules():
        if path == MACHINE / "controller.py":
            continue
        for lineno, module in imported_modules(path):
            if module == "app.machine.controller":
                offenders.append(f"{path.relative_to(ROOT)}:{lineno}")
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom) and any(a.name == "MachineController" for a in node.names):
                offenders.append(f"{path.relative_to(ROOT)}:{node.lineno}: imports MachineController")
    assert not offenders, "\n".join(offenders)


def test_a_part_writes_only_its_own_fields() -> None:
    """A part keeps the interfaces it was given as ``self._<name>``; ``self._<name>.<field> = ...``
    would write into another part's state: each field has one writer, its owner (a part
    changes another through that part's methods)."""
    offenders = []
    for path in _machine_modules():
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            targets: list[ast.expr] = []
            if isinstance(node, ast.Assign):
                targets = list(node.targets)
            elif isinstance(node, (ast.AugAssign, ast.AnnAssign)):
                targets = [node.target]
            for t in targets:
                for leaf in (t.elts if isinstance(t, ast.Tuple) else [t]):
                    if (isinstance(leaf, ast.Attribute) and isinstance(leaf.value, ast.Attribute)
                            and isinstance(leaf.value.value, ast.Name) and leaf.value.value.id == "self"
                            and leaf.value.attr.startswith("_")):
                        offenders.append(f"{path.relative_to(ROOT)}:{leaf.lineno}: "
                                         f"self.{leaf.value.attr}.{leaf.attr} = ...")
    assert not offenders, "\n".join(offenders)


def test_no_lock_is_taken_from_outside_its_owner() -> None:
    """A lock is its owner's: ``x._lock`` is read only as ``self._lock``."""
    offenders = []
    for path in _machine_modules():
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, ast.Attribute) and node.attr.endswith("_lock") and node.attr.startswith("_") \
                    and not (isinstance(node.value, ast.Name) and node.value.id == "self"):
                offenders.append(f"{path.relative_to(ROOT)}:{node.lineno}")
    assert not offenders, "\n".join(offenders)


@pytest.mark.parametrize(("package", "most"), [("app/machine", 700), ("ethercat", 700), ("planner", 1000)])
def test_no_file_holds_more_than_a_reader_can(package: str, most: int) -> None:
    """700 lines at most a module in the controller and the bus package, 1,000 in the planner."""
    files = sorted((ROOT / package).rglob("*.py"))
    assert len(files) > 10
    long = [f"{p.relative_to(ROOT)}: {n} lines" for p in files
            if (n := len(p.read_text(encoding="utf-8").splitlines())) > most]
    assert not long, long


def test_the_interpreter_names_its_codes() -> None:
    """The interpreter's families compare G codes by name (``G.G38_2``), not as the bare
    numbers times ten they are (``== 382``): no comparison of a code-like variable with a
    literal of two or three digits."""
    pattern = re.compile(r"\b(code|motion|plane|feed_mode|comp_code|work_code|tlo_code|g0|g1|previous_motion)"
                         r"\s*(==|!=|<|>|<=|>=|in|not in)\s*\(?\d{2,3}\b")
    files = sorted((ROOT / "planner" / "gcode").glob("*.py"))
    assert len(files) > 10
    found = [f"{p.relative_to(ROOT)}:{i}: {line.strip()}" for p in files
             for i, line in enumerate(p.read_text(encoding="utf-8").splitlines(), 1) if pattern.search(line)]
    assert not found, "\n".join(found)
