"""The layout is the architecture: planner/ and ethercat/ never import Qt, pyqtgraph or app/,
and ethercat/ does not depend on planner/. Checked two ways: statically over every import
statement, and at run time by importing every module in a clean interpreter."""

from __future__ import annotations

import ast
import dataclasses
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


def _job_fields() -> set[str]:
    """The fields ``Job.__init__`` makes (``self.<field> = ...``)."""
    tree = ast.parse((MACHINE / "motion" / "jobs.py").read_text(encoding="utf-8"))
    job = next(n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == "Job")
    init = next(n for n in job.body if isinstance(n, ast.FunctionDef) and n.name == "__init__")
    return {t.attr for n in ast.walk(init) if isinstance(n, (ast.Assign, ast.AnnAssign))
            for t in (n.targets if isinstance(n, ast.Assign) else [n.target])
            if isinstance(t, ast.Attribute) and isinstance(t.value, ast.Name) and t.value.id == "self"}


#: how the controller's code names a job it holds: ``job``, ``new``, ``nxt``, ``main``, ``self.job``
_A_JOB = re.compile(r"^(job|new|nxt|main|self\.job)$")


def test_a_field_of_a_job_has_its_writers_in_one_file() -> None:
    """Once made (``Job.__init__``, called by the job maker alone), each field of a job is
    written from one file: its terms by none, the run's progress by the streamer's set-point
    queue (samples, pause points) or by the streamer (the rest). Writes are ``<job>.<field> =``
    anywhere in ``app.machine`` and ``self.<field> =`` in the job's own methods."""
    fields = _job_fields()
    assert {"samples", "pause", "dwell_total_s", "origin", "when_done"} <= fields
    writers: dict[str, set[str]] = {}
    for path in _machine_modules():
        tree = ast.parse(path.read_text(encoding="utf-8"))
        skip: set[int] = set()
        if path.name == "jobs.py":
            job = next(n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == "Job")
            init = next(n for n in job.body if isinstance(n, ast.FunctionDef) and n.name == "__init__")
            skip = {id(n) for n in ast.walk(init)}
        for node in ast.walk(tree):
            if id(node) in skip or not isinstance(node, (ast.Assign, ast.AugAssign, ast.AnnAssign)):
                continue
            for t in (node.targets if isinstance(node, ast.Assign) else [node.target]):
                for leaf in (t.elts if isinstance(t, ast.Tuple) else [t]):
                    if not (isinstance(leaf, ast.Attribute) and leaf.attr in fields):
                        continue
                    owner = ast.unparse(leaf.value)
                    if _A_JOB.match(owner) or (owner == "self" and path.name == "jobs.py"):
                        writers.setdefault(leaf.attr, set()).add(str(path.relative_to(ROOT)))
    assert len(writers) > 15                                  # the run's progress is written
    shared = {f: sorted(files) for f, files in writers.items() if len(files) > 1}
    assert not shared, shared


def test_no_part_is_wired_after_it_is_made() -> None:
    """A part gets what it reads when it is made, or hears it as events: no ``wire(`` call
    that hands it higher parts afterwards."""
    found = [f"{p.relative_to(ROOT)}:{i}" for p in _machine_modules()
             for i, line in enumerate(p.read_text(encoding="utf-8").splitlines(), 1)
             if re.search(r"\bwire\(", line)]
    assert not found, found


def _calls(path: Path, names: tuple[str, ...]) -> list[str]:
    out = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Call):
            f = node.func
            name = f.attr if isinstance(f, ast.Attribute) else f.id if isinstance(f, ast.Name) else ""
            # ``x.refusal(action)`` is a command's refusal (the state machine's), not the stage
            if name in names and not (name == "refusal" and isinstance(f, ast.Attribute)):
                out.append(f"{path.relative_to(ROOT)}:{node.lineno} {name}")
    return out


#: the load's stages: read, refuse, blend, the travel
_STAGES = ("parse_program", "parse_file", "refusal", "pipeline_refusal", "blend_program", "check_and_bound")


def test_programs_are_read_by_the_one_load_alone() -> None:
    """A program, an MDI block, a wizard's routine, the editor's text and a program read again
    with what the machine read (a probe, an input) go through ``planner.pipeline.load`` (read,
    refuse, blend, limits, plan, in that order, each stage an option; ``Loaded.reread`` the same
    stages again): no part of the panel, the controller or the tools calls a stage itself, and
    the pipeline calls each stage in one place."""
    calls = []
    for root in ("app", "cli", "planner"):
        for path in sorted((ROOT / root).rglob("*.py")):
            if path.parent.name in ("gcode", "geometry", "motion") or path.name == "pipeline.py":
                continue                    # where the stages are made, and the pipeline
            calls += _calls(path, _STAGES)
    assert not calls, calls
    staged = [c.split()[1] for c in _calls(ROOT / "planner" / "pipeline.py", _STAGES)]
    assert sorted(staged) == ["blend_program", "check_and_bound", "parse_program", "refusal"], staged


def test_a_programs_moves_have_one_shape() -> None:
    """``Program.moves`` is a ``MoveStore`` whoever made the program (Move objects given are
    stored as columns where the program is made): no code asks which shape it has."""
    asked = []
    for root in ("app", "cli", "planner", "opcua_server", "tools"):
        for path in sorted((ROOT / root).rglob("*.py")):
            for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
                if (isinstance(node, ast.Call) and isinstance(node.func, ast.Name)
                        and node.func.id == "isinstance" and len(node.args) == 2
                        and "MoveStore" in ast.unparse(node.args[1])):
                    asked.append(str(path.relative_to(ROOT)))
    assert asked == ["planner/core/program.py"], asked          # where Move objects are stored
    from planner.pipeline import parse_program

    program = parse_program("G1 X1 F600\nG1 Y1\n")
    again = dataclasses.replace(program, moves=tuple(program.moves))
    assert type(program.moves).__name__ == type(again.moves).__name__ == "MoveStore"
    assert [m.end.tolist() for m in again.moves] == [[1.0, 0.0, 0.0], [1.0, 1.0, 0.0]]


#: offset or rotation maths by hand: a part of an offset added or taken off an indexed
#: coordinate, or the cosine or sine of a coordinate system's rotation
_BY_HAND = re.compile(r"(g5x|g92|tlo|\.tool|work)\[\w+\]\s*[-+]|[-+]\s*[\w.]*(g5x|g92|tlo)\[|"
                      r"(cos|sin|radians)\([^)]*rotation")


def test_offsets_and_rotations_are_composed_by_the_frame_alone() -> None:
    """The interpreter, the canonical calls, the panel's touch-off and tool setter, the preview
    and the backplot convert between machine and program coordinates through
    ``planner.core.frames.Frame``: nowhere else is an offset added, taken off or turned."""
    found = []
    for root in ("app", "cli", "planner", "opcua_server"):
        for path in sorted((ROOT / root).rglob("*.py")):
            if path == ROOT / "planner" / "core" / "frames.py":
                continue
            for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
                if _BY_HAND.search(line.split("#")[0]):
                    found.append(f"{path.relative_to(ROOT)}:{n}: {line.strip()}")
    assert not found, "\n".join(found)
    frames = (ROOT / "planner" / "core" / "frames.py").read_text(encoding="utf-8")
    assert _BY_HAND.search(frames)               # the pattern finds what the frame does


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
