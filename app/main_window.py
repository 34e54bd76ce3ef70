"""Main window: status header (DRO, state, bus, E-stop, alarms), navigation, pages, status line."""

from __future__ import annotations

import importlib
from collections.abc import Callable
from pathlib import Path

from PySide6.QtCore import QEvent, QObject, QTimer, Signal
from PySide6.QtGui import QCloseEvent
from PySide6.QtWidgets import (
    QApplication,
    QButtonGroup,
    QHBoxLayout,
    QLabel,
    QMainWindow,
    QPushButton,
    QSizePolicy,
    QStackedWidget,
    QVBoxLayout,
    QWidget,
)

from app import deferred
from app.context import PanelContext, PanelOptions
from app.controller_text import localize
from app.i18n import LANGUAGES, tr
from app.machine.model import ProgramIssue
from app.pages import PAGES, PageInfo, page_info
from app.pages.placeholder import PlaceholderPage
from app.service_access import IDLE_LOCK_S
from app.shortcuts import Shortcuts, parse_bindings
from app.widgets.elided_label import ElidedLabel
from app.widgets.service_gate import ServiceGate
from app.widgets.status_header import StatusHeader
from ethercat.sim_part import Feature, SimPart
from resources import shipped_program

_INPUT_EVENTS = frozenset({QEvent.Type.MouseButtonPress, QEvent.Type.KeyPress, QEvent.Type.TouchBegin})


def build_page(info: PageInfo, context: PanelContext) -> QWidget:
    """The page's own module if it exists, else a placeholder that says it is not built yet."""
    try:
        module = importlib.import_module(f"app.pages.{info.module}")
    except ModuleNotFoundError as exc:
        if exc.name != f"app.pages.{info.module}":
            raise
        return PlaceholderPage(info.label)
    return module.create_page(context)


# the demo's workpiece (machine coordinates of the stylus' tip): a block 80 x 60 mm, its top at
# Z-60, a 24 mm bore through it and, beside it, nothing else to touch
DEMO_PART = SimPart(x_mm=60.0, y_mm=0.0, half_x_mm=40.0, half_y_mm=30.0, top_mm=-60.0, depth_mm=40.0,
                    feature=Feature.BORE, feature_x_mm=70.0, feature_y_mm=5.0, feature_radius_mm=12.0)


class MainWindow(QMainWindow):
    pageChanged = Signal(str)

    def __init__(self, options: PanelOptions, context: PanelContext | None = None) -> None:
        super().__init__()
        if context is None:
            from app.context_factory import build_context

            context = build_context(options)
        self.options = options
        self.context = context
        ctx = context
        self.setWindowTitle("CNC panel")
        language = options.language or ctx.settings.settings.language
        if language != "en":
            ctx.i18n.set_language(language)
        central = QWidget()
        outer = QVBoxLayout(central)
        outer.setContentsMargins(4, 4, 4, 0)
        outer.setSpacing(4)
        self.header = StatusHeader(ctx)
        outer.addWidget(self.header)
        body = QHBoxLayout()
        outer.addLayout(body, 1)

        nav = QVBoxLayout()
        nav.setSpacing(3)
        self._nav_group = QButtonGroup(self)
        self._nav_group.setExclusive(True)
        self._buttons: dict[str, QPushButton] = {}
        self._stack = QStackedWidget()
        self._pages: dict[str, QWidget] = {}
        for info in PAGES:
            button = QPushButton()
            ctx.i18n.bind(button, info.label)
            button.setObjectName("navButton")
            button.setCheckable(True)
            button.setMinimumHeight(48)
            button.setMinimumWidth(170)
            button.clicked.connect(lambda _=False, name=info.name: self.show_page(name))
            self._nav_group.addButton(button)
            nav.addWidget(button)
            self._buttons[info.name] = button
        nav.addStretch(1)
        self.language_button = QPushButton()
        self.language_button.setObjectName("languageButton")
        self.language_button.clicked.connect(self.toggle_language)
        nav.addWidget(self.language_button)
        body.addLayout(nav)
        body.addWidget(self._stack, 1)
        self.setCentralWidget(central)
        self._gates: dict[str, ServiceGate] = {}
        for info in PAGES:  # built after the navigation so a slow page never hides it
            page = build_page(info, ctx)
            self._pages[info.name] = page
            if info.service:
                gate = ServiceGate(page, ctx.i18n)
                gate.unlockRequested.connect(lambda name=info.name: self.show_page(name))
                self._gates[info.name] = gate
                self._stack.addWidget(gate)
            else:
                self._stack.addWidget(page)

        self._message = QLabel()
        # a long message wraps in its own share of the bar: it never squeezes the alarm banner
        self._message.setWordWrap(True)
        self._message.setSizePolicy(QSizePolicy.Policy.Ignored, QSizePolicy.Policy.Preferred)
        self._message_source: Callable[[], str] | None = None
        self.statusBar().setFixedHeight(52)
        self.statusBar().addWidget(self.header.alarm_banner, 2)
        self.statusBar().addWidget(self._message, 1)
        self._program_label = ElidedLabel(min_chars=16)
        self.statusBar().addPermanentWidget(self._program_label)
        # said again in the other language when the operator switches: the sentence, not its words
        ctx.controller.message.connect(lambda text: self.show_message(lambda: localize(text)))
        ctx.controller.commandRefused.connect(self._on_refused)
        self._refusal_shown = False
        # a refusal is not left standing once something was done since: a change of state,
        # activity, offsets, tools, homing, overrides, modes or the program loaded clears it
        c = ctx.controller
        for done in (c.stateChanged, c.activityChanged, c.offsetsChanged, c.toolsChanged, c.homedChanged,
                     c.overridesChanged, c.modesChanged, c.programLoaded):
            done.connect(lambda *_args: self._clear_refusal())
        ctx.controller.programLoaded.connect(self._on_program_loaded)
        ctx.controller.programErrors.connect(self._on_program_errors)
        ctx.controller.programReadAgain.connect(ctx.program.set_read_again)
        self._progress_timer = QTimer(self)
        self._progress_timer.setInterval(deferred.LOAD_PROGRESS_MS)
        self._progress_timer.timeout.connect(self._show_progress)
        if hasattr(ctx.controller, "loadingChanged"):
            ctx.controller.loadingChanged.connect(self._on_loading)
        ctx.program.lineRequested.connect(lambda _line: self.show_page("program"))
        self.header.alarm_banner.clicked.connect(lambda: self.show_page("alarms"))
        ctx.i18n.languageChanged.connect(self._on_language)
        self._on_language(ctx.i18n.language)
        self._current = ""
        self.show_page(options.page, ask_password=False)
        # the service level locks itself after minutes without input (see app.service_access)
        app = QApplication.instance()
        if app is not None:
            app.installEventFilter(self)
        bindings = parse_bindings(ctx.settings.settings.shortcuts)
        self.shortcuts = Shortcuts(ctx.controller, self.header._estop_clicked, bindings)
        self._idle_timer = QTimer(self)
        self._idle_timer.setInterval(5_000)
        self._idle_timer.timeout.connect(self._check_idle)
        self._idle_timer.start()
        if bindings.problems:
            self.show_message("; ".join(bindings.problems))
        if ctx.access is not None and ctx.access.damaged:
            self.show_message(ctx.access.unlock("").reason)
        QTimer.singleShot(0, self._start)

    # --- start-up ------------------------------------------------------------------------
    def _start(self) -> None:
        ctx = self.context
        c = ctx.controller
        unclean = any(a.code == "unclean_shutdown" for a in c.active_alarms)
        if self.options.demo:  # simulated drives: connect, and home by "set here" if needed
            c.connect_bus()
            # after a power loss or a kill the axes stay unhomed in demo too: homing "here"
            # by itself would show them homed at a made-up zero; the operator homes (one tap)
            if not all(c.homed) and c.config.homing.method == "set_here" and not unclean:
                c.home_all()
            if not len(ctx.controller.tool_table):   # a first demo: a few tools to look at
                ctx.controller.import_tool_table(str(shipped_program("demo_tools.tbl")))
                ctx.controller.set_tool_in_spindle(1)
            # a workpiece for the simulated probe (the probing wizards with T99 in the spindle)
            c.simulate_part(DEMO_PART)
        cut = c.interrupted
        if unclean and c.config.homing.method == "set_here":
            self.show_message(lambda: tr(
                "The control stopped without shutting down (power loss or killed), and this machine has "
                "no reference switches: where the axes stand is not known. Set machine zero, touch off "
                "the part zero again, then run the program from its start"))
        elif cut is not None:
            cut_name, cut_line = Path(cut[0]).name, cut[1]
            self.show_message(lambda: tr(
                "{0} was running at line {1} when the control stopped (power loss or killed): home the "
                "axes, open it and run from line {1}").format(cut_name, cut_line))
        elif unclean:
            self.show_message(lambda: tr(
                "The control did not shut down cleanly: home the axes (Machine zero, Home all) before "
                "running a program"))
        program = self.options.effective_program
        if self.options.demo and self.options.program_path is None and "X" not in c.axes:
            # the paper's Y-Z-C-A machine: its own sample (rotary and linear mixed, G93 blocks)
            program = shipped_program("tyre_mould.nc")
        if program is not None and ctx.program.info is None:
            ctx.controller.load_program(program)  # the Program page opens it when it is loaded

    def _on_loading(self, loading: bool, name: str) -> None:
        """The controller checks a program in its worker thread: say so in the status bar, with
        how far it is (a program of millions of lines takes seconds)."""
        checking = tr("Checking {0} …").format(name)
        if loading:
            if self.context.controller.program_info is None:  # let go: a load replaces it
                self.context.program.let_go(name)
            self._program_label.setText(tr("{0} (checking…)").format(name))
            self.show_message(checking)
            self._checking = (name, checking)
            self._progress_timer.start()
            return
        self._progress_timer.stop()
        checking = getattr(self, "_checking", ("", checking))[1]
        # done (loaded, refused, or a single-block plan made): no "checking" text may outlive it
        info = self.context.controller.program_info
        self._program_label.setText(str(getattr(info, "name", "")) if info is not None else "")
        if self._message.text() == checking:
            self.show_message("")

    def _show_progress(self) -> None:
        name, shown = getattr(self, "_checking", ("", ""))
        fraction = float(getattr(self.context.controller, "loading_progress", 0.0) or 0.0)
        if fraction > 0.0 and self._message.text() == shown:
            text = tr("Checking {0} … {1} %").format(name, int(100 * fraction))
            self.show_message(text)
            self._checking = (name, text)

    def _on_program_loaded(self, info: object) -> None:
        name = str(getattr(info, "name", ""))
        self._program_label.setText(name)
        blends = int(getattr(info, "blends", 0) or 0)
        if blends:
            # the operator sees that the path is not exactly the programmed one, and by how much
            deviation = float(getattr(info, "path_deviation_mm", 0.0))
            self.show_message(lambda: tr(
                "Program loaded: {0}; G64: {1} corners smoothed, at most {2:.3f} mm from the programmed "
                "path").format(name, blends, deviation))
        else:
            self.show_message(lambda: tr("Program loaded: {0}").format(name))
        if deferred.is_big(info):  # the tool path of a big program: in its own event-loop turn
            deferred.run_soon("program-model", lambda: self._apply_program(info))
        else:
            self._apply_program(info)

    def _apply_program(self, info: object) -> None:
        self.context.program.set_loaded(info, self.context.controller.config.machine)

    def _on_program_errors(self, issues: tuple[ProgramIssue, ...]) -> None:
        deferred.cancel("program-model")  # an older program not shown yet: never show it now
        self.context.program.set_errors(issues)
        n = len(issues)
        self.show_message(lambda: tr("Program refused: {0} error(s)").format(n))

    # --- navigation ----------------------------------------------------------------------
    def show_page(self, name: str, ask_password: bool = True) -> bool:
        """Show a page; a service page asks for the password first (its lock screen otherwise).

        Returns True when the page itself is shown (False: locked)."""
        info = page_info(name)
        unlocked = True
        if not info.service and self.context.service_unlocked:
            self.lock_service()     # leaving the service pages ends the service level
        if info.service:
            if not self.context.service_unlocked and ask_password:
                self.unlock_service()
            unlocked = self.context.service_unlocked
            for gate in self._gates.values():
                gate.set_locked(not unlocked)
        widget = self._gates.get(info.name, self._pages[info.name])
        self._stack.setCurrentWidget(widget)
        self._buttons[info.name].setChecked(True)
        self._current = info.name
        self.pageChanged.emit(info.name)
        return unlocked

    def unlock_service(self) -> bool:
        ctx = self.context
        access = ctx.access
        assert access is not None
        refused = access.damaged
        if refused:       # no point asking: say why and how to recover
            self.show_message(access.unlock("").reason)
            return False
        password = ctx.dialogs.ask_text(self, tr("Service level"), tr("Service password:"), password=True)
        if password is None:
            return False
        outcome = access.unlock(password)
        if not outcome:
            self.show_message(lambda: tr("Service level refused: {0}").format(outcome.reason))
            return False
        self.show_message(lambda: tr("Service level unlocked"))
        return True

    def lock_service(self) -> None:
        if self.context.access is not None:
            self.context.access.lock()
        for gate in self._gates.values():
            gate.set_locked(True)

    def eventFilter(self, watched: QObject, event: QEvent) -> bool:  # noqa: N802 - Qt override
        # any touch, click or key press restarts the service level's idle time
        if event.type() in _INPUT_EVENTS and self.context.access is not None:
            self.context.access.touch()
        # keys reach the panel's shortcuts only through this window (not a dialog in front)
        if isinstance(watched, QWidget) and watched.window() is self:
            return self.shortcuts.handle(event)
        return False

    def _check_idle(self) -> None:
        access = self.context.access
        if access is not None and access.lock_if_idle():
            self.lock_service()
            self.show_message(lambda: tr("Service level locked after {0} minutes without input").format(
                int(IDLE_LOCK_S // 60)))

    def page(self, name: str) -> QWidget:
        return self._pages[page_info(name).name]

    @property
    def current_page_name(self) -> str:
        current = self._stack.currentWidget()
        return next(n for n, w in self._pages.items() if w is current or self._gates.get(n) is current)

    # --- language, messages --------------------------------------------------------------
    def toggle_language(self) -> None:
        languages = list(LANGUAGES)
        current = self.context.i18n.language
        self.set_language(languages[(languages.index(current) + 1) % len(languages)])

    def set_language(self, language: str) -> None:
        self.context.i18n.set_language(language)
        self.context.settings.update(language=language)

    def _on_language(self, language: str) -> None:
        other = [lang for lang in LANGUAGES if lang != language][0]
        self.language_button.setText(f"{LANGUAGES[other]}")
        if self._message_source is not None:
            self._message.setText(self._message_source())

    def show_message(self, text: str | Callable[[], str]) -> None:
        """The status line: a text, or how to say it (said again when the language changes)."""
        self._refusal_shown = False
        self._message_source = text if callable(text) else None
        self._message.setText(text() if callable(text) else text)

    def _on_refused(self, _action: str, reason: str) -> None:
        self.show_message(lambda: tr("Refused: {0}").format(localize(reason)))
        self._refusal_shown = True

    def _clear_refusal(self) -> None:
        if self._refusal_shown:
            self.show_message("")

    def closeEvent(self, event: QCloseEvent) -> None:  # noqa: N802 - Qt override
        for page in self._pages.values():
            can_close = getattr(page, "can_close", None)
            if can_close is not None and not can_close():
                event.ignore()
                return
        self.context.controller.shutdown()
        app = QApplication.instance()
        if app is not None:      # a closed window no longer sees the application's events
            app.removeEventFilter(self)
        super().closeEvent(event)
