"""Fixtures for the panel tests: scripted dialogs, windows on the fake or the real controller.

Everything persists under pytest's tmp_path (``state_dir``), never in the user's home.
"""

from __future__ import annotations

from collections import deque
from pathlib import Path

import pytest

from app.dialogs import Dialogs


class ScriptedDialogs(Dialogs):
    """Answers queued by the test; confirmations default to yes. Records every question."""

    def __init__(self) -> None:
        self.answers: deque[object] = deque()
        self.asked: list[tuple[str, str]] = []
        self.default_confirm = True

    def _next(self, default: object) -> object:
        return self.answers.popleft() if self.answers else default

    def confirm(self, parent, title, text) -> bool:  # type: ignore[override]
        self.asked.append(("confirm", text))
        return bool(self._next(self.default_confirm))

    def choose(self, parent, title, text, options) -> int:  # type: ignore[override]
        self.asked.append(("choose", text))
        return int(self._next(-1))  # type: ignore[call-overload]

    def ask_number(self, parent, title, value, minimum=-1e9, maximum=1e9, decimals=3):  # type: ignore[override]
        self.asked.append(("number", title))
        return self._next(None)

    def ask_text(self, parent, title, label, password=False, text=""):  # type: ignore[override]
        self.asked.append(("text", label))
        return self._next(None)

    def ask_open_file(self, parent, directory, folders=None, suffixes=None):  # type: ignore[override]
        self.asked.append(("open", directory))
        return self._next(None)

    def ask_save_file(self, parent, directory):  # type: ignore[override]
        self.asked.append(("save", directory))
        return self._next(None)

    def inform(self, parent, title, text) -> None:  # type: ignore[override]
        self.asked.append(("inform", text))


@pytest.fixture
def dialogs() -> ScriptedDialogs:
    return ScriptedDialogs()


@pytest.fixture
def state_dir(tmp_path: Path) -> Path:
    d = tmp_path / "state"
    d.mkdir()
    return d


@pytest.fixture
def fake_controller():
    from tests.app.fake_controller import FakeController

    return FakeController()


@pytest.fixture
def fake_window(qtbot, qapp, state_dir, dialogs, fake_controller):
    """Main window on the fake controller (no worker): fast page tests."""
    from app.application import apply_theme
    from app.context import PanelOptions
    from app.context_factory import build_context
    from app.main_window import MainWindow

    options = PanelOptions(state_dir=state_dir)
    apply_theme(qapp)
    ctx = build_context(options, dialogs=dialogs, controller=fake_controller)
    window = MainWindow(options, ctx)
    qtbot.addWidget(window)
    window.resize(1280, 800)
    window.show()
    yield window
    ctx.i18n.set_language("en")  # the translator is installed application-wide


@pytest.fixture
def real_controller(state_dir):
    """The real controller on simulated drives, with a manual clock (tests advance time)."""
    from app.machine.controller import MachineController

    controller = MachineController(None, state_dir=state_dir, worker_mode="manual")
    yield controller
    controller.shutdown()


def make_window(qtbot, qapp, options, dialogs, controller):
    from app.application import apply_theme
    from app.context_factory import build_context
    from app.main_window import MainWindow

    apply_theme(qapp)
    ctx = build_context(options, dialogs=dialogs, controller=controller)
    window = MainWindow(options, ctx)
    qtbot.addWidget(window)
    window.resize(1280, 800)
    window.show()
    return window


def window_on(qtbot, qapp, tmp_path, dialogs, config_text: str):  # type: ignore[no-untyped-def]
    """The panel over a real controller (manual clock) on the configuration ``config_text``
    (the test lead appended), connected and zeroed where the axes stand: (window, controller);
    the caller shuts the controller down."""
    from app.context import PanelOptions
    from app.machine.controller import MachineController
    from tests.machine.conftest import TEST_LEAD_S

    config = tmp_path / "machine.toml"
    config.write_text(config_text + f"\n[controller]\nlead_s = {TEST_LEAD_S}\n", encoding="utf-8")
    state = tmp_path / "state"
    state.mkdir()
    c = MachineController(config, state_dir=state, worker_mode="manual")
    assert c.connect_bus() and c.set_machine_zero_here()
    return make_window(qtbot, qapp, PanelOptions(state_dir=state), dialogs, c), c


@pytest.fixture
def demo_window(qtbot, qapp, state_dir, dialogs, real_controller):
    """``cnc-panel --demo`` on the real controller (manual clock): connected, pocket.nc loaded, and
    machine zero set where the axes stand."""
    from app.context import PanelOptions

    window = make_window(qtbot, qapp, PanelOptions(demo=True, state_dir=state_dir), dialogs, real_controller)
    qtbot.waitUntil(lambda: real_controller.program_info is not None, timeout=20000)
    # the demo machine homes to its switches when the operator asks (test_flows shows it); the
    # pages' tests start from a homed machine
    assert all(real_controller.homed) or real_controller.set_machine_zero_here()
    return window
