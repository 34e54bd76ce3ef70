"""The main window shell: navigation to every page, each drawn, and `cnc-panel --screenshot`."""

from __future__ import annotations

import os
import signal
import struct
import subprocess
import sys
import time
from pathlib import Path

import pytest

from app.context import PanelOptions
from app.main_window import MainWindow
from app.pages import PAGE_NAMES, PAGES, page_info
from tests.shm import shm_before, wait_for_new_blocks

ROOT = Path(__file__).resolve().parents[2]


def png_size(path: Path) -> tuple[int, int]:
    header = path.read_bytes()[:24]
    assert header[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG file"
    return struct.unpack(">II", header[16:24])


def test_navigation_reaches_every_page(fake_window, dialogs) -> None:
    dialogs.answers.append("1234")  # service password, asked once
    for info in PAGES:
        window = fake_window
        window.show_page(info.name)
        assert window.current_page_name == info.name
    assert len(PAGES) == 11


def test_navigation_buttons_are_touch_sized(fake_window) -> None:
    assert len(fake_window._buttons) == len(PAGES)
    for button in fake_window._buttons.values():
        assert button.height() >= 48 and button.width() >= 48


def test_demo_window_on_the_real_controller(qtbot, qapp, tmp_path: Path) -> None:
    """MainWindow builds its own controller from the options (state under --state-dir)."""
    window = MainWindow(PanelOptions(state_dir=tmp_path / "state"))
    qtbot.addWidget(window)
    try:
        assert window.context.state_dir == tmp_path / "state"
        assert window.context.controller.state.value == "disconnected"  # not --demo: not connected
    finally:
        window.context.controller.shutdown()


def test_every_page_of_the_demo_renders_to_a_screenshot(qtbot, qapp, tmp_path: Path) -> None:
    """Each page of the demo panel, connected and with its sample loaded, drawn to a 1280x800
    PNG in one panel (the command line's ``--screenshot`` is run below for two of them)."""
    from app.application import apply_theme, create_window, save_screenshot

    apply_theme(qapp)
    window = create_window(PanelOptions(demo=True, state_dir=tmp_path / "state"))
    qtbot.addWidget(window)
    controller = window.context.controller
    try:
        window.show()
        qtbot.waitUntil(lambda: controller.bus_status.connected and controller.program_info is not None,
                        timeout=20_000)
        for page in PAGE_NAMES:
            if page_info(page).service:              # the integrator's pages, behind the default password
                assert window.context.access is not None and window.context.access.unlock("1234")
            assert window.show_page(page, ask_password=False), page
            out = tmp_path / f"{page}.png"
            save_screenshot(window, out)
            assert window.current_page_name == page
            assert png_size(out) == (1280, 800), page
    finally:
        controller.shutdown()


@pytest.mark.parametrize("page", ["auto", "parameters"])        # an operator's page, a service page
def test_screenshot_from_the_command_line(tmp_path: Path, page: str) -> None:
    out = tmp_path / f"{page}.png"
    result = subprocess.run(
        [sys.executable, "-m", "app", "--demo", "--screenshot", str(out), "--page", page,
         "--state-dir", str(tmp_path / "state")],
        cwd=ROOT, capture_output=True, text=True, timeout=120,
        env={**__import__("os").environ, "QT_QPA_PLATFORM": "offscreen"},
    )
    assert result.returncode == 0, result.stderr
    assert png_size(out) == (1280, 800)


def test_no_display_gives_advice_instead_of_crashing() -> None:
    env = {k: v for k, v in __import__("os").environ.items()
           if k not in ("DISPLAY", "WAYLAND_DISPLAY", "QT_QPA_PLATFORM")}
    result = subprocess.run([sys.executable, "-m", "app", "--demo"], cwd=ROOT, env=env,
                            capture_output=True, text=True, timeout=60)
    assert result.returncode == 2
    assert "QT_QPA_PLATFORM=offscreen" in result.stderr and "xvfb-run" in result.stderr


@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGINT], ids=["SIGTERM", "SIGINT"])
def test_a_signal_shuts_the_panel_down_cleanly(tmp_path: Path, sig: signal.Signals) -> None:
    """kill or Ctrl+C: the worker stops, its shared memory is released, the state is saved,
    and the panel exits with 0, leaving no shared-memory block behind."""
    before = shm_before()
    env = {**os.environ, "QT_QPA_PLATFORM": "offscreen"}
    proc = subprocess.Popen([sys.executable, "-m", "app", "--demo", "--state-dir", str(tmp_path / "state")],
                            env=env, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    try:
        mine = wait_for_new_blocks(before, proc)
        assert mine, "the panel's worker never started"
        time.sleep(1.0)                       # connected, homed, the demo program loaded
        proc.send_signal(sig)
        assert proc.wait(timeout=30) == 0, proc.stderr.read() if proc.stderr else ""
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait(timeout=10)
    assert not [p for p in mine if p.exists()], "shared memory left behind"
    assert (tmp_path / "state" / "state.json").is_file()


def test_no_checking_text_outlives_the_check(fake_window, fake_controller) -> None:
    """A load refused, or a single-block plan made, ends the check: the status bar no longer
    says the program is being checked."""
    fake_controller.loadingChanged.emit(True, "part.nc")
    assert "Checking part.nc" in fake_window._message.text()
    assert "checking" in fake_window._program_label.text()
    fake_controller.loadingChanged.emit(False, "part.nc")
    assert "Checking" not in fake_window._message.text()
    assert "checking" not in fake_window._program_label.text()


def test_the_status_bar_shows_how_far_a_check_is(fake_window, fake_controller, qtbot) -> None:
    fake_controller.loadingChanged.emit(True, "part.nc")
    fake_controller.loading_progress = 0.42
    qtbot.waitUntil(lambda: "42 %" in fake_window._message.text(), timeout=2_000)
    assert "part.nc" in fake_window._message.text()
    auto = fake_window.page("auto")
    qtbot.waitUntil(lambda: auto.loading_bar.maximum() == 100 and auto.loading_bar.value() == 42,
                    timeout=2_000)
    fake_controller.loadingChanged.emit(False, "part.nc")
    assert "part.nc" not in fake_window._message.text()
    fake_controller.loading_progress = 0.0
