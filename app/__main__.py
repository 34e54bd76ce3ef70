"""`cnc-panel`: start the operator panel.

cnc-panel [--demo] [--config FILE] [PROGRAM] [--screenshot FILE.png] [--page NAME]
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

from app.context import PanelOptions
from app.pages import PAGE_NAMES

NO_DISPLAY_HELP = """\
cnc-panel: no display found (neither DISPLAY nor WAYLAND_DISPLAY is set).
  To render the panel to a picture without a screen:
      QT_QPA_PLATFORM=offscreen cnc-panel --demo --screenshot panel.png
      (make demo ARGS="--screenshot panel.png" does the same)
  To run it interactively on a virtual screen:
      apt-get install xvfb && xvfb-run -s "-screen 0 1280x800x24" cnc-panel --demo
"""


def parse_args(argv: list[str] | None = None) -> PanelOptions:
    parser = argparse.ArgumentParser(prog="cnc-panel", description="Touchscreen CNC operator panel")
    parser.add_argument("program", nargs="?", type=Path, help="G-code program to load")
    parser.add_argument("--demo", action="store_true", help="simulated drives, sample program loaded")
    parser.add_argument("--config", type=Path, help="machine configuration TOML")
    parser.add_argument("--screenshot", type=Path, metavar="FILE.png",
                        help="render the panel to a PNG and exit")
    parser.add_argument("--page", default="auto", choices=PAGE_NAMES, help="page to show first")
    parser.add_argument("--lang", default=None, choices=("en", "tr"),
                        help="user interface language (default: the last one chosen, else en)")
    parser.add_argument("--size", default="1280x800", help="window size WIDTHxHEIGHT (default 1280x800)")
    parser.add_argument("--state-dir", type=Path,
                        help="where settings, alarms and positions persist "
                             "(default ~/.local/state/cnc-panel)")
    parser.add_argument("--run-for", type=float, default=0.0, metavar="SECONDS",
                        help="with --demo --screenshot: press cycle start and shoot SECONDS later")
    parser.add_argument("--programs", type=Path, action="append", default=[], metavar="DIR",
                        help="another folder the operator may open and save programs in (repeatable)")
    parser.add_argument("--reset-service-password", action="store_true",
                        help="integrator's recovery at the panel PC: set the service password back to "
                             "the default (1234) in the state folder, clear the lockout, and exit")
    parser.add_argument("--opcua-port", type=int, default=None, metavar="PORT",
                        help="serve the OPC UA model (OPC 40501) on PORT, with the configured [opcua] "
                             "security")
    parser.add_argument("--opcua-insecure", action="store_true",
                        help="the OPC UA server with security None and anonymous reading, on 127.0.0.1 only")
    ns = parser.parse_args(argv)
    if ns.opcua_port is not None and not 1 <= ns.opcua_port <= 65535:
        parser.error(f"--opcua-port {ns.opcua_port}: a TCP port is 1 to 65535")
    try:
        width, height = (int(v) for v in ns.size.lower().split("x"))
    except ValueError:
        parser.error(f"--size must look like 1280x800, got {ns.size!r}")
    return PanelOptions(demo=ns.demo, config_path=ns.config, program_path=ns.program,
                        screenshot_path=ns.screenshot, page=ns.page, language=ns.lang,
                        width_px=width, height_px=height, state_dir=ns.state_dir,
                        run_for_s=ns.run_for, reset_service_password=ns.reset_service_password,
                        program_dirs=tuple(ns.programs), opcua_port=ns.opcua_port,
                        opcua_insecure=ns.opcua_insecure)


def _has_display() -> bool:
    if os.environ.get("QT_QPA_PLATFORM"):
        return True
    if sys.platform != "linux":
        return True
    return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


def main(argv: list[str] | None = None) -> int:
    options = parse_args(argv)
    if options.reset_service_password:
        from app.panel_settings import SettingsStore
        from app.service_access import reset_service_password

        store = SettingsStore(options.effective_state_dir)
        reset_service_password(store)
        print(f"service password reset to the default in {store.path}; change it on the Parameters page")
        return 0
    if not _has_display():
        if options.screenshot_path is None:
            sys.stderr.write(NO_DISPLAY_HELP)
            return 2
        os.environ["QT_QPA_PLATFORM"] = "offscreen"
    from app.application import run  # Qt is imported only once we know it can start

    return run(options)


if __name__ == "__main__":
    sys.exit(main())
