"""Build the QApplication and the main window; render a screenshot when asked."""

from __future__ import annotations

import signal
import sys
import time

from PySide6.QtCore import QTimer
from PySide6.QtWidgets import QApplication

from app.context import PanelOptions
from app.machine.model import MachineState
from app.main_window import MainWindow
from app.paths import STYLES
from planner.core.files import write_output_via_path


def apply_theme(app: QApplication) -> None:
    """Fusion style + the dark touch theme; set once (re-setting re-polishes every widget)."""
    # the style's pictures (scroll arrows) are found beside it, wherever the package is installed
    qss = (STYLES / "dark.qss").read_text(encoding="utf-8").replace("@STYLES@", STYLES.as_posix())
    if app.styleSheet() != qss:
        app.setStyle("Fusion")
        app.setStyleSheet(qss)


def create_window(options: PanelOptions) -> MainWindow:
    window = MainWindow(options)
    window.resize(options.width_px, options.height_px)
    return window


def save_screenshot(window: MainWindow, path) -> None:
    window.resize(window.options.width_px, window.options.height_px)
    pixmap = window.grab()

    def save(tmp: str) -> None:
        if not pixmap.save(tmp, "PNG"):
            raise OSError(f"could not write screenshot to {path}")

    write_output_via_path(path, save)     # the one output writer: atomic, devices and - too


def run(options: PanelOptions) -> int:
    running = QApplication.instance()
    app = running if isinstance(running, QApplication) else QApplication(sys.argv[:1])
    app.setApplicationName("cnc-panel")
    apply_theme(app)
    from app.machine.errors import ConfigError, StateFolderBusy

    try:
        window = create_window(options)
    except ConfigError as exc:  # never fall back silently to defaults over the user's values
        sys.stderr.write(f"cnc-panel: {exc}\n")
        if exc.backup:
            sys.stderr.write(f"  the previous good file is {exc.backup}; copy it over {exc.path} to use it\n")
        return 2
    except StateFolderBusy as exc:  # a second panel on the same machine state: refused, not both
        sys.stderr.write(f"cnc-panel: {exc}\n")
        return 2
    app.aboutToQuit.connect(window.context.controller.shutdown)
    quit_on_signals(app)
    window.show()
    if options.screenshot_path is not None:
        schedule_screenshot(app, window, options)
    return app.exec()


def quit_on_signals(app: QApplication) -> None:
    """SIGTERM (a service manager, ``kill``) and SIGINT (Ctrl+C) end the panel like closing it:
    motion stopped along the path, the worker stopped and its shared memory released, positions
    and settings saved. Python runs signal handlers only between bytecodes, so a timer gives
    the interpreter a turn a few times a second while Qt's loop runs."""

    def request_quit(signum: int, _frame: object) -> None:
        QTimer.singleShot(0, app.quit)

    for sig in (signal.SIGTERM, signal.SIGINT):
        signal.signal(sig, request_quit)
    ticker = QTimer(app)
    ticker.setInterval(200)
    ticker.timeout.connect(lambda: None)
    ticker.start()


def schedule_screenshot(app: QApplication, window: MainWindow, options: PanelOptions) -> None:
    """Shoot once the demo is connected (at most 5 s), or ``run_for_s`` after cycle start (the
    demo machine homed to its switches first, at most 2 minutes)."""
    controller = window.context.controller
    started = time.monotonic()

    def shoot() -> None:
        save_screenshot(window, options.screenshot_path)
        print(f"screenshot written to {options.screenshot_path}")
        app.quit()

    def wait_ready() -> None:
        ready = not options.demo or (controller.bus_status.connected and controller.program_info is not None)
        if not ready and time.monotonic() - started < 5.0:
            QTimer.singleShot(100, wait_ready)
        elif options.run_for_s > 0 and ready:
            if not all(controller.homed):      # the demo machine homes to its switches first
                controller.home_all()
                QTimer.singleShot(200, wait_homed)
                return
            controller.cycle_start()
            QTimer.singleShot(round(options.run_for_s * 1000), shoot)
        else:
            QTimer.singleShot(200, shoot)

    def wait_homed() -> None:
        if all(controller.homed) and controller.state is MachineState.IDLE:
            controller.cycle_start()
            QTimer.singleShot(round(options.run_for_s * 1000), shoot)
        elif time.monotonic() - started < 120.0 and controller.state is MachineState.HOMING:
            QTimer.singleShot(200, wait_homed)
        else:                                   # homing refused or failed: the panel says why
            QTimer.singleShot(200, shoot)

    QTimer.singleShot(300, wait_ready)
