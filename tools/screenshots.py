"""Render every page of the panel in demo mode at 1280x800 and 1920x1080, in English and
Turkish, into ``resources/screenshots/all/`` (the README's gallery):

    python -m tools.screenshots [--out DIR] [--jobs N]
    python -m tools.screenshots --probing [--out DIR]
    python -m tools.screenshots --handwheel [--out DIR]
    python -m tools.screenshots --spindle [--out DIR]

``--probing``: each probing wizard run on the demo machine against its simulated workpiece
(the real controller on a manual clock, in this process), the Probe tab shown with the moves
and what was found, into ``resources/screenshots/probing/``. ``--handwheel``: the Manual page with
the handwheel live on X at x10, after 50 detents turned, into ``resources/screenshots/``.
``--spindle``: the Diagnostics page's Spindle tab of the demo mill with a spindle drive, after
M3 S8000, the override to 120 % and a load that bogs the spindle down for a second.

Each picture is the real panel (``cnc-panel --demo --screenshot``), the Auto page after the
demo program has run a few seconds (backplot, spindle and tool showing). The test suite checks
the same pages and sizes for clipping (``tests/app/test_pages.py``).
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Any

from app.pages import PAGE_NAMES

ROOT = Path(__file__).resolve().parent.parent
SIZES = ("1280x800", "1920x1080")
LANGUAGES = ("en", "tr")


def shoot(page: str, size: str, language: str, out: Path) -> str:
    target = out / f"{page}_{size}_{language}.png"
    with tempfile.TemporaryDirectory(prefix="cnc-shot-") as state:
        args = [sys.executable, "-m", "app", "--demo", "--page", page, "--size", size, "--lang", language,
                "--state-dir", state, "--screenshot", str(target)]
        if page == "auto":
            args += ["--run-for", "8"]
        env = dict(os.environ, QT_QPA_PLATFORM=os.environ.get("QT_QPA_PLATFORM", "offscreen"))
        done = subprocess.run(args, cwd=ROOT, env=env, capture_output=True, text=True, timeout=120)
    if done.returncode != 0:
        raise RuntimeError(f"{target.name}: {done.stderr.strip()}")
    return target.name


# each wizard on the demo's workpiece (app.main_window.DEMO_PART, a block with a bore) or on a
# part of its own: (wizard, inputs, part or None for the demo's, the stylus tip's start)
Shot = tuple[str, dict[str, object], dict[str, object] | None, tuple[float, float, float]]
PROBING_SHOTS: tuple[Shot, ...] = (
    ("Z_SURFACE", {}, None, (40.0, -10.0, -55.0)),
    ("EDGE", {"axis": "X", "x_dir": 1}, None, (15.0, -10.0, -64.0)),
    ("OUTSIDE_CORNER", {"x_dir": 1, "y_dir": 1}, None, (16.0, -34.0, -64.0)),
    ("INSIDE_CORNER", {"x_dir": 1, "y_dir": 1},
     {"feature": "POCKET", "feature_x_mm": 70.0, "feature_y_mm": 5.0, "pocket_half_x_mm": 12.0,
      "pocket_half_y_mm": 9.0}, (78.0, 10.0, -64.0)),
    ("BORE", {"diameter_mm": 24.0}, None, (71.0, 6.0, -65.0)),
    ("BOSS", {"diameter_mm": 16.0, "depth_mm": 8.0},
     {"feature": "BOSS", "feature_x_mm": 70.0, "feature_y_mm": 5.0, "feature_radius_mm": 8.0,
      "boss_height_mm": 10.0}, (71.0, 4.0, -47.0)),
    ("ANGLE", {"axis": "Y", "y_dir": 1, "along_mm": 30.0, "search_mm": 15.0}, {"angle_deg": 2.0},
     (35.0, -36.0, -64.0)),
)


def shoot_probing(out: Path) -> list[str]:
    """Each probing wizard run and shown on the Part zero page's Probe tab (1280x800, English)."""
    os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
    from PySide6.QtWidgets import QApplication

    app = QApplication.instance() or QApplication([])
    return [_shoot_wizard(app, out, *shot) for shot in PROBING_SHOTS]


def _demo_window(app: Any, state: str, config: Path | None = None) -> tuple[Any, Any]:
    """The demo panel (1280x800) on the real controller with a manual clock, through its
    start-up (connected, the program loaded, the axes homed where the demo homes them);
    ``config``: another machine than the demo's."""
    from app.application import apply_theme
    from app.context import PanelOptions
    from app.context_factory import build_context
    from app.machine.controller import MachineController
    from app.main_window import MainWindow

    ctl = MachineController(config, state_dir=state, worker_mode="manual")
    options = PanelOptions(demo=True, state_dir=Path(state))
    apply_theme(app)
    window = MainWindow(options, build_context(options, controller=ctl))
    window.resize(1280, 800)
    window.show()
    for _ in range(400):                 # the window's start-up: connect, home, tools
        app.processEvents()
        if ctl.run_until(lambda: ctl.program_info is not None and all(ctl.homed), 0.05):
            break
    return ctl, window


def _shoot_wizard(app: object, out: Path, wizard_name: str, inputs: dict[str, object],
                  own_part: dict[str, object] | None, start: tuple[float, float, float]) -> str:
    from dataclasses import replace

    from app.machine.model import MachineState, ProbeWizard
    from app.main_window import DEMO_PART
    from ethercat.sim_part import Feature

    x, y, z = start
    with tempfile.TemporaryDirectory(prefix="cnc-shot-") as state:
        ctl, window = _demo_window(app, state)

        def idle() -> bool:
            return ctl.state is MachineState.IDLE and ctl.stream.job is None

        res = ctl.set_tool_in_spindle(99)
        assert res, res.reason
        if own_part is not None:
            kw = dict(own_part)
            if "feature" in kw:
                kw["feature"] = Feature[str(kw["feature"])]
            ctl.simulate_part(replace(DEMO_PART, **kw))  # type: ignore[arg-type]
        for block in (f"G53 G0 Z{z + 50.0:.3f}", f"G53 G0 X{x:.3f} Y{y:.3f}"):
            assert ctl.mdi(block), block
            ctl.run_until(idle, 30)
        window.show_page("part_zero")
        page = window.page("part_zero")
        page.tabs.setCurrentIndex(1)
        panel = page.probing
        wizard = ProbeWizard[wizard_name]
        panel.wizard_buttons[wizard].click()
        fields = {"diameter_mm": "diameter", "depth_mm": "depth", "along_mm": "along", "search_mm": "search"}
        for key, value in inputs.items():
            if key in fields:
                panel.fields[fields[key]].setValue(float(value))  # type: ignore[arg-type]
        if "axis" in inputs:
            sign = inputs.get("x_dir" if inputs["axis"] == "X" else "y_dir", 1)
            panel.move_buttons[f"{inputs['axis']}{'+' if sign == 1 else '-'}"].click()
        elif "x_dir" in inputs:
            xs, ys = inputs["x_dir"], inputs["y_dir"]
            panel.corner_buttons[f"X{'+' if xs == 1 else '-'} Y{'+' if ys == 1 else '-'}"].click()
        panel.target_buttons["G55"].click()
        panel.refresh()
        panel.run_button.click()
        ctl.run_until(lambda: ctl.state is not MachineState.RUNNING and ctl.stream.job is None, 120)
        for _ in range(10):
            app.processEvents()  # type: ignore[attr-defined]
        target = out / f"{wizard.value}.png"
        window.grab().save(str(target))
        window.close()
        ctl.shutdown()
    return target.name


def _home(ctl: Any) -> None:
    """The demo starts unhomed: Home all, as the operator would."""
    if not all(ctl.homed):
        assert ctl.home_all()
        ctl.run_until(lambda: all(ctl.homed) and ctl.state.value == "idle", 120)


def _save(app: Any, ctl: Any, window: Any, target: Path) -> str:
    """The window as drawn into ``target``; the window closed and the controller shut down."""
    for _ in range(10):
        app.processEvents()
    window.grab().save(str(target))
    window.close()
    ctl.shutdown()
    return target.name


def shoot_handwheel(out: Path) -> str:
    """The Manual page with the handwheel live (1280x800, English)."""
    os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
    from PySide6.QtWidgets import QApplication

    app = QApplication.instance() or QApplication([])
    with tempfile.TemporaryDirectory(prefix="cnc-shot-") as state:
        ctl, window = _demo_window(app, state)
        _home(ctl)
        window.show_page("manual")
        box = window.page("manual").handwheel
        box.axis_buttons["X"].click()
        box.step_buttons[1].click()
        ctl.advance(0.1)
        ctl.turn_handwheel(4 * 50)
        ctl.advance(1.5)
        return _save(app, ctl, window, out / "manual_handwheel.png")


def shoot_spindle(out: Path) -> str:
    """The Diagnostics page's Spindle tab with the spindle's own drive (1280x800, English)."""
    os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
    from PySide6.QtWidgets import QApplication

    from resources import shipped_machine

    app = QApplication.instance() or QApplication([])
    with tempfile.TemporaryDirectory(prefix="cnc-shot-") as state:
        config = Path(state) / "machine.toml"
        config.write_text(shipped_machine("xyz_mill").read_text(encoding="utf-8")
                          + "\n[spindle]\ndrive = 8\naccel_rpm_s = 4000\n", encoding="utf-8")
        ctl, window = _demo_window(app, state, config)
        _home(ctl)
        diag = window.page("diagnostics")
        window.show_page("diagnostics")
        diag.tabs.setCurrentWidget(diag.spindle)
        diag.spindle.set_drive(ctl.config.spindle)      # the plot from here on
        ctl.advance(0.5)
        steps = [(lambda: ctl.spindle_on(True, 8000), 3.0), (lambda: ctl.set_spindle_override(120), 1.5),
                 (lambda: ctl.worker.inject("spindle_load", 0, 5000), 1.0),
                 (lambda: ctl.worker.inject("spindle_unload", 0), 1.5)]
        for act, seconds in steps:
            act()
            for _ in range(int(seconds / 0.05)):
                ctl.advance(0.05)
                app.processEvents()  # type: ignore[attr-defined]
        diag.spindle.redraw()
        return _save(app, ctl, window, out / "diagnostics_spindle.png")


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m tools.screenshots", description=__doc__.split("\n\n")[0])
    p.add_argument("--out", default=None)
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--probing", action="store_true", help="the probing wizards instead of the pages")
    p.add_argument("--handwheel", action="store_true", help="the Manual page with the handwheel live")
    p.add_argument("--spindle", action="store_true", help="the Diagnostics page's Spindle tab")
    args = p.parse_args(argv)
    if args.spindle:
        out = Path(args.out or ROOT / "resources" / "screenshots")
        print(shoot_spindle(out))
        return 0
    if args.handwheel:
        out = Path(args.out or ROOT / "resources" / "screenshots")
        print(shoot_handwheel(out))
        return 0
    if args.probing:
        out = Path(args.out or ROOT / "resources" / "screenshots" / "probing")
        out.mkdir(parents=True, exist_ok=True)
        for name in shoot_probing(out):
            print(name)
        return 0
    out = Path(args.out or ROOT / "resources" / "screenshots" / "all")
    out.mkdir(parents=True, exist_ok=True)
    work = [(page, size, lang) for page in PAGE_NAMES for size in SIZES for lang in LANGUAGES]
    with ThreadPoolExecutor(max_workers=max(args.jobs, 1)) as pool:
        for name in pool.map(lambda w: shoot(*w, out), work):
            print(name)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
