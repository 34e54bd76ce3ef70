"""A non-editable install works on its own: the shipped machines, programs, style and
translations travel inside the package, so from another directory the panel starts in demo
mode and cnc-plan plans a shipped sample, with nothing read from this checkout."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent


def _run(cmd: list[str], cwd: Path, env: dict[str, str] | None = None, timeout: float = 300) -> str:
    done = subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True, timeout=timeout)
    assert done.returncode == 0, f"{' '.join(cmd)}\n{done.stdout[-3000:]}\n{done.stderr[-3000:]}"
    return done.stdout


@pytest.fixture(scope="module")
def installed(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A fresh virtual environment with the project installed from a wheel (not editable).
    Its dependencies come from the test environment's site-packages through a plain path
    entry, which does not run that environment's editable-install hook."""
    base = tmp_path_factory.mktemp("install")
    # build from a copy of the files git knows (tracked, or new and not ignored): a build/
    # directory left in the checkout would otherwise lend the wheel files it should not have
    source = base / "source"
    listed = _run(["git", "ls-files", "-co", "--exclude-standard", "-z"], cwd=ROOT).split("\0")
    for rel in filter(None, listed):
        if (ROOT / rel).is_file():
            (source / rel).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(ROOT / rel, source / rel)
    wheels = base / "wheels"
    _run([sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", str(wheels), str(source)], cwd=base)
    venv = base / "venv"
    _run([sys.executable, "-m", "venv", "--without-pip", str(venv)], cwd=base)
    py = venv / "bin" / "python"
    purelib = "import sysconfig; print(sysconfig.get_paths()['purelib'])"
    site = Path(_run([str(py), "-c", purelib], cwd=base).strip())
    (site / "test-deps.pth").write_text(sysconfig.get_paths()["purelib"] + "\n", encoding="utf-8")
    wheel = next(wheels.glob("cnc_panel-*.whl"))
    pip = [sys.executable, "-m", "pip", "--python", str(py)]
    _run([*pip, "install", "--no-deps", "-q", str(wheel)], cwd=base)
    return venv


def test_installed_packages_come_from_the_install_not_the_checkout(installed: Path, tmp_path: Path) -> None:
    out = _run([str(installed / "bin" / "python"), "-c",
                "import app, cli, planner, ethercat, opcua_server, resources, json; "
                "mods = (app, cli, planner, ethercat, opcua_server, resources); "
                "print(json.dumps([m.__file__ for m in mods]))"],
               cwd=tmp_path)
    for path in json.loads(out):
        assert str(installed) in path and str(ROOT) not in path, path


def test_cnc_plan_plans_a_shipped_sample(installed: Path, tmp_path: Path) -> None:
    py = installed / "bin" / "python"
    where = "from resources import shipped_program; print(shipped_program('fig7_circle.nc'))"
    sample = _run([str(py), "-c", where], cwd=tmp_path).strip()
    assert str(installed) in sample
    report = json.loads(_run([str(installed / "bin" / "cnc-plan"), sample, "--json"], cwd=tmp_path))
    assert report["ok"] and report["moves"] == 6


def test_panel_starts_in_demo_mode_and_takes_a_screenshot(installed: Path, tmp_path: Path) -> None:
    shot = tmp_path / "x.png"
    env = {**os.environ, "QT_QPA_PLATFORM": "offscreen"}
    _run([str(installed / "bin" / "cnc-panel"), "--demo", "--screenshot", str(shot),
          "--state-dir", str(tmp_path / "state")], cwd=tmp_path, env=env, timeout=120)
    assert shot.stat().st_size > 10_000


def test_the_opcua_nodesets_and_their_notice_travel_with_the_package(installed: Path, tmp_path: Path) -> None:
    out = _run([str(installed / "bin" / "python"), "-c",
                "from importlib import resources; import json; "
                "d = resources.files('opcua_server') / 'nodesets'; "
                "print(json.dumps(sorted(p.name for p in d.iterdir())))"], cwd=tmp_path)
    names = json.loads(out)
    assert names == ["NOTICE.md", "Opc.Ua.Di.NodeSet2.xml", "Opc.Ua.IA.NodeSet2.xml",
                     "Opc.Ua.MachineTool.NodeSet2.xml",
                     "Opc.Ua.Machinery.NodeSet2.xml"]
    text = _run([str(installed / "bin" / "cnc-opcua"), "--state-dir", str(tmp_path / "state")], cwd=tmp_path)
    assert "certificate:" in text and "SHA-1" in text
