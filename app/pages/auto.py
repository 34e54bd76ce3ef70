"""Auto: run the loaded program: cycle start, hold, stop, reset, single block, optional stop,
run from line, feed and rapid override, current line kept in view, progress and path speed."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from PySide6.QtCore import Qt, QTimer
from PySide6.QtWidgets import (
    QGridLayout,
    QHBoxLayout,
    QLabel,
    QProgressBar,
    QPushButton,
    QVBoxLayout,
    QWidget,
)

from app import deferred
from app.context import PanelContext
from app.controller_text import localize
from app.format import format_duration, format_speed, tool_text
from app.i18n import N_, tr
from app.machine.model import RestartPreview, SpindleState
from app.widgets.elided_label import ElidedLabel
from app.widgets.override_control import OverrideControl
from app.widgets.preview_plot import PreviewPlot, usable_planes
from app.widgets.program_view import ProgramView
from app.widgets.touch import enable_kinetic_scrolling
from planner.core.tools import ToolTable

BUTTONS = (  # (key, label, object name, controller action for refusal())
    ("start", N_("Cycle start"), "cycleStart", "cycle_start"),
    ("hold", N_("Feed hold"), "feedHold", "feed_hold"),
    ("stop", N_("Stop"), "stopButton", "stop"),
    ("reset", N_("Reset"), "resetButton", "reset"),
)


class AutoPage(QWidget):
    def __init__(self, context: PanelContext, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("autoPage")
        self.ctx = context
        c = context.controller
        i18n = context.i18n
        layout = QHBoxLayout(self)
        left = QVBoxLayout()
        self.program_label = ElidedLabel()
        self.program_label.setObjectName("programName")
        title = QHBoxLayout()
        self._title_row = title
        title.addWidget(self.program_label)
        # the modal codes in force at the current line (cut at the end where the row is short)
        self.modal_label = ElidedLabel(min_chars=4, mode=Qt.TextElideMode.ElideRight)
        self.modal_label.setObjectName("modalCodes")
        title.addWidget(self.modal_label, 1)
        left.addLayout(title)
        self.loading_note = QLabel()  # "Checking NAME …" while the controller checks a program
        self.loading_note.setObjectName("loadingNote")
        self.loading_bar = QProgressBar()  # busy indicator (keeps moving: the panel is responsive)
        self.loading_bar.setRange(0, 0)
        self.loading_bar.setTextVisible(False)
        self.loading_bar.setMaximumHeight(8)
        self.loading_note.hide()
        self.loading_bar.hide()
        self._loading_timer = QTimer(self)  # the bar shows how far the check is, once known
        self._loading_timer.setInterval(deferred.LOAD_PROGRESS_MS)
        self._loading_timer.timeout.connect(self._show_loading_progress)
        left.addWidget(self.loading_note)
        left.addWidget(self.loading_bar)
        # the program's file was saved with other text than the program loaded: said, with a
        # reload at hand (the machine runs what was loaded, not what the editor shows)
        stale = QHBoxLayout()
        self.stale_note = QLabel()
        self.stale_note.setObjectName("staleNote")
        self.stale_note.setWordWrap(True)
        self.reload_button = QPushButton()
        self.reload_button.setObjectName("reloadButton")
        self.reload_button.setMinimumHeight(48)
        i18n.bind(self.reload_button, N_("Reload"))
        self.reload_button.clicked.connect(self.reload_saved)
        stale.addWidget(self.stale_note, 1)
        stale.addWidget(self.reload_button)
        self.stale_note.hide()
        self.reload_button.hide()
        left.addLayout(stale)
        # a view over the loaded text, not a copy of it in a text widget: millions of lines
        # show at once
        self.editor = ProgramView()
        enable_kinetic_scrolling(self.editor)
        left.addWidget(self.editor, 3)
        # the backplot: the path (XY, work coordinates), what has been cut, where the tool is
        self.backplot = PreviewPlot()
        self.backplot.setObjectName("autoBackplot")
        self.backplot.set_plane((usable_planes(context.controller.axes) or ["XY"])[0])   # YZ on Y-Z-C-A
        self.backplot.setMinimumHeight(160)
        left.addWidget(self.backplot, 2)
        layout.addLayout(left, 3)

        right = QVBoxLayout()
        grid = QGridLayout()
        self.buttons: dict[str, QPushButton] = {}
        for i, (key, label, obj, _action) in enumerate(BUTTONS):
            button = QPushButton()
            button.setObjectName(obj)
            button.setMinimumHeight(64)
            i18n.bind(button, label)
            grid.addWidget(button, i // 2, i % 2)
            self.buttons[key] = button
        self.buttons["start"].clicked.connect(self.cycle_start)
        self.buttons["hold"].clicked.connect(lambda: c.feed_hold())
        self.buttons["stop"].clicked.connect(lambda: c.stop())
        self.buttons["reset"].clicked.connect(lambda: c.reset())
        self.single_block = QPushButton()
        self.single_block.setCheckable(True)
        i18n.bind(self.single_block, N_("Single block"))
        self.single_block.clicked.connect(lambda on: c.set_single_block(on))
        self.optional_stop = QPushButton()
        self.optional_stop.setCheckable(True)
        i18n.bind(self.optional_stop, N_("Optional stop"))
        self.optional_stop.clicked.connect(lambda on: c.set_optional_stop(on))
        grid.addWidget(self.single_block, 2, 0)
        grid.addWidget(self.optional_stop, 2, 1)
        self._block_delete = False   # switched on the Program page, beside the lines it skips
        self.run_from = QPushButton()
        i18n.bind(self.run_from, N_("Run from line…"))
        self.run_from.clicked.connect(self.run_from_line)
        # beside the program (it starts at an editor line), never narrower than its text in the
        # language shown (a long program name is cut instead)
        self._title_row.addWidget(self.run_from)
        self._keep_run_from_whole()
        i18n.languageChanged.connect(lambda _l: self._keep_run_from_whole())
        right.addLayout(grid)

        self.feed = OverrideControl("")
        i18n.bind(self.feed.title, N_("Feed override"))
        self.feed.changed.connect(lambda v: c.set_feed_override(v))
        self.rapid = OverrideControl("", maximum=100)
        i18n.bind(self.rapid.title, N_("Rapid override"))
        self.rapid.changed.connect(lambda v: c.set_rapid_override(v))
        self.spindle_override = OverrideControl("", maximum=150, minimum=50)
        i18n.bind(self.spindle_override.title, N_("Spindle override"))
        self.spindle_override.changed.connect(lambda v: c.set_spindle_override(v))
        right.addWidget(self.feed)
        right.addWidget(self.rapid)
        right.addWidget(self.spindle_override)
        self.progress = QProgressBar()
        self.progress.setRange(0, 1000)
        self.progress.setTextVisible(False)
        self.progress.setFixedHeight(16)
        right.addWidget(self.progress)
        # the two labels below hold a few lines each, their heights fixed: a longer text (a
        # refusal, the end of a run) never moves the buttons above them
        self.info_label = QLabel()
        self.info_label.setObjectName("runInfo")
        self.info_label.setWordWrap(True)
        self.info_label.ensurePolished()         # its font is the style sheet's
        self.info_label.setFixedHeight(self.info_label.fontMetrics().lineSpacing() * 3 + 4)
        right.addWidget(self.info_label)
        # what the machine does and is set to: spindle, feed, tool, the modal codes in force
        self.machine_label = QLabel()
        self.machine_label.setObjectName("machineInfo")
        self.machine_label.setWordWrap(True)
        self.machine_label.ensurePolished()
        self.machine_label.setFixedHeight(self.machine_label.fontMetrics().lineSpacing() * 2 + 4)
        right.addWidget(self.machine_label)
        # what a program stop asks of the operator (tool change, M0), in words
        self.prompt_label = QLabel()
        self.prompt_label.setObjectName("promptLabel")
        self.prompt_label.setWordWrap(True)
        self.prompt_label.setStyleSheet("background: #a86b00; color: white; font-weight: 700; padding: 6px;")
        self.prompt_label.hide()
        left.insertWidget(1, self.prompt_label)   # under the title: the editor gives it room
        right.addStretch(1)
        layout.addLayout(right, 2)

        self._fraction, self._remaining, self._speed, self._line = 0.0, float("nan"), 0.0, 0
        self._feed_pct = 100.0
        self._refused = ""
        self._finished = ""
        self._why_start = ""        # why Cycle start is disabled ("" when it is not)
        self._spindle = c.spindle
        self._tools, self._tool = c.tool_table, c.tool_in_spindle
        c.programLoaded.connect(self._on_loaded)
        if hasattr(c, "loadingChanged"):
            c.loadingChanged.connect(self._on_loading)
        c.lineChanged.connect(self._on_line)
        c.progressChanged.connect(self._on_progress)
        c.speedChanged.connect(self._on_speed)
        c.overridesChanged.connect(self._on_overrides)
        c.feedOverrideNote.connect(self.feed.set_note)
        c.modesChanged.connect(self._on_modes)
        c.spindleChanged.connect(self._on_spindle)
        c.toolsChanged.connect(self._on_tools)
        c.stateChanged.connect(self._on_state)
        c.programFinished.connect(self._on_finished)
        c.positionChanged.connect(lambda _machine, work: self.backplot.set_tool_position(work))
        context.program.changed.connect(lambda: self.backplot.set_toolpath(context.program.toolpath))
        c.programErrors.connect(self._on_errors)
        for signal in (c.stateChanged, c.homedChanged, c.programErrors, c.alarmsChanged):
            signal.connect(lambda *_: self._update_buttons())
        context.program.changed.connect(self._on_program_model)
        context.program.changed.connect(self.show_stale)
        i18n.languageChanged.connect(lambda _l: self._update_info())
        self._on_overrides(c.feed_override_pct, c.rapid_override_pct)
        self._on_modes(c.single_block, c.optional_stop, c.block_delete)
        self.backplot.set_toolpath(context.program.toolpath)
        if c.program_info is not None:
            self._on_loaded(c.program_info)
        if getattr(c, "loading", False):
            self._on_loading(True, str(getattr(c, "loading_name", "")))
        self._update_buttons()
        self._update_info()

    # --- commands ------------------------------------------------------------------------
    def cycle_start(self) -> None:
        c = self.ctx.controller
        if str(getattr(c.state, "value", "")) == "hold":
            c.resume()
        elif self.ctx.program.errors:  # the program shown was refused: never run an older one
            self._refused = tr("Cycle start refused: the program has errors (line {0})").format(
                min(self.ctx.program.errors))
            self._update_info()
        elif c.resume_line > 0:
            self._restart_choice()
        elif self._warnings_confirmed():
            c.cycle_start()

    def _warnings_confirmed(self) -> bool:
        """What the check found for the operator to confirm before a run from the beginning
        (a feed move with the spindle stopped after M6): asked, the lines named."""
        info = self.ctx.controller.program_info
        warnings = getattr(info, "warnings", ()) if info is not None else ()
        if not warnings:
            return True
        text = "\n".join(tr("Line {0}: {1}").format(w.line, localize(w.message)) for w in warnings[:5])
        question = text + "\n\n" + tr("Run the program anyway?")
        return self.ctx.dialogs.confirm(self, tr("Cycle start"), question)

    def _restart_choice(self) -> None:
        """The program stopped part-way (Stop, E-stop and reset, an alarm): never again from
        line 1 by default. The operator chooses: resume where it stopped (the way drawn) or
        start from the beginning."""
        c = self.ctx.controller
        stopped = c.resume_line
        preview = c.restart_preview(0)
        beginning = tr("Start from the beginning")
        if isinstance(preview, str):
            text = tr("The program stopped at line {0} and cannot resume there: {1}").format(
                stopped, localize(preview))
            if self.ctx.dialogs.choose(self, tr("Cycle start"), text, [beginning, tr("Cancel")]) == 0:
                c.cycle_start(from_start=True)
            return
        text = (tr("The program stopped at line {0} ({1}).").format(preview.line, localize(preview.cause))
                + "\n\n" + self._restart_text(preview) + "\n\n"
                + tr("Or start it again from line 1, from where the tool stands now."))
        self._show_way(preview.path)
        try:
            choice = self.ctx.dialogs.choose(self, tr("Cycle start"), text,
                                             [tr("Resume at line {0}").format(preview.line), beginning,
                                              tr("Cancel")])
        finally:
            self._show_way(None)
        if choice == 0:
            c.resume()
        elif choice == 1 and self._warnings_confirmed():
            c.cycle_start(from_start=True)

    def _restart_text(self, preview: RestartPreview) -> str:
        """The way a restart goes, in words: clearance, spindle, tool."""
        if np.isfinite(preview.clearance_mm):
            way = tr("The machine goes up to Z{0:.3f} (machine), across, then down to it the way drawn"
                     ).format(preview.clearance_mm)
        else:
            way = tr("The machine goes there the way drawn")
        rpm = preview.spindle_rpm
        spindle = (tr("the spindle stays off") if rpm == 0 else
                   tr("the spindle starts at {0:.0f} rpm {1} before it goes down").format(
                       abs(rpm), tr("CW") if rpm > 0 else tr("CCW")))
        tool = tr("tool {0}").format(tool_text(self._tools, preview.tool))
        return f"{way}; {spindle}; {tool}."

    def _show_way(self, path: np.ndarray | None) -> None:
        """The way a restart takes, drawn on the backplot in work coordinates (None: hidden)."""
        if path is None:
            self.backplot.set_approach(None)
            return
        c = self.ctx.controller
        frame = c.snapshot().frame
        way = np.asarray(path, float)
        self.backplot.set_approach(frame.to_program(way) if frame is not None else way)

    def _keep_run_from_whole(self) -> None:
        self.run_from.setMinimumWidth(self.run_from.sizeHint().width())

    def run_from_line(self) -> None:
        ctx = self.ctx
        c = ctx.controller
        info = c.program_info
        if info is None:
            return
        # where the program stopped (or was cut by a power loss), when it did; else the line
        # the editor shows
        cut = c.interrupted
        cut_line = cut[1] if cut is not None and cut[0] in (info.path, info.name) else 0
        default = c.resume_line or cut_line or max(1, self.editor.current_line())
        line = ctx.dialogs.ask_number(self, tr("Run from line"), float(default), 1, float(info.line_count), 0)
        if line is None:
            return
        preview = c.restart_preview(int(line))
        if isinstance(preview, str):
            self._refused = tr("Run from line refused: {0}").format(localize(preview))
            self._update_info()
            return
        self._show_way(preview.path)
        try:
            if ctx.dialogs.confirm(self, tr("Run from line"),
                                   tr("Run the program from line {0}?").format(int(line)) + "\n\n"
                                   + self._restart_text(preview)):
                c.run_from_line(int(line))
        finally:
            self._show_way(None)

    # --- controller signals --------------------------------------------------------------
    def _on_loading(self, loading: bool, name: str) -> None:
        """The controller is checking a program (parse, soft limits, plan) in its worker thread."""
        self.loading_note.setText(tr("Checking {0} …").format(name) if loading else "")
        self.loading_note.setVisible(loading)
        self.loading_bar.setRange(0, 0)  # busy until the controller tells how far it is
        self.loading_bar.setVisible(loading)
        if loading:
            self._loading_timer.start()
        else:
            self._loading_timer.stop()
        self._update_buttons()

    def _show_loading_progress(self) -> None:
        fraction = float(getattr(self.ctx.controller, "loading_progress", 0.0) or 0.0)
        if fraction > 0.0:
            self.loading_bar.setRange(0, 100)
            self.loading_bar.setValue(int(100 * fraction))

    def _on_loaded(self, info: object) -> None:
        self.program_label.setText(str(getattr(info, "name", "")))
        self._remaining = float(getattr(info, "cycle_time_s", float("nan")))
        self._fraction = 0.0
        self._finished = ""
        self.progress.setValue(0)
        self._update_info()
        self._update_buttons()
        if deferred.is_big(info):  # 35,000 lines take ~0.1 s: in an event-loop turn of their own
            deferred.run_soon("auto-editor", lambda: self._show_text(info))
        else:
            self._show_text(info)

    def _show_text(self, info: object) -> None:
        if self.ctx.controller.program_info is not info:
            return  # superseded or refused meanwhile
        text = str(getattr(info, "text", ""))
        if self.editor.toPlainText() is not text:
            self.editor.load_text(text, starts=getattr(info, "line_starts", None))

    def _on_program_model(self) -> None:
        model = self.ctx.program
        self._refused = ""
        if model.info is None and model.name != self.program_label.text():
            # another program is being checked: nothing of the one before stays as if it were it
            self._line, self._fraction, self._remaining, self._finished = 0, 0.0, float("nan"), ""
            self.progress.setValue(0)
            self.editor.set_run_line(0)
        self._update_info()       # the feed and modal codes come from the loaded program
        if model.info is None and self.editor.toPlainText() != model.text:
            self.editor.load_text(model.text)   # a refused program's text, or none: one let go
            self.program_label.setText(model.name)
        self.editor.set_errors(model.errors)
        self._update_buttons()

    def _on_line(self, line: int) -> None:
        self._line = line
        self.editor.set_run_line(line)
        if line > 0 and self.ctx.program.toolpath is not None:
            self.backplot.set_executed(self.ctx.program.move_at_line(line),
                                       self.ctx.controller.run_first_move)
        self._update_info()

    def _on_progress(self, fraction: float, remaining_s: float) -> None:
        self._fraction, self._remaining = fraction, remaining_s
        self.progress.setValue(round(1000 * fraction))
        self._update_info()

    def _on_speed(self, speed: float) -> None:
        self._speed = speed
        self._update_info()

    def _on_overrides(self, feed: float, rapid: float) -> None:
        self.feed.set_value(feed)
        self.rapid.set_value(rapid)
        self._feed_pct = float(feed)
        self._update_info()

    def _on_modes(self, single_block: bool, optional_stop: bool, block_delete: bool) -> None:
        self.single_block.setChecked(single_block)
        self.optional_stop.setChecked(optional_stop)
        self._block_delete = block_delete
        self._update_info()

    def _on_spindle(self, spindle: SpindleState) -> None:
        self._spindle = spindle
        self.spindle_override.set_value(float(spindle.override_pct))
        self._update_info()

    def _on_tools(self, table: ToolTable, in_spindle: int) -> None:
        self._tools, self._tool = table, int(in_spindle)
        self._update_info()

    def _on_state(self, _state: object, _reason: str) -> None:
        prompt = getattr(self.ctx.controller, "prompt", None)
        text = localize(str(getattr(prompt, "text", ""))) if prompt is not None else ""
        self.prompt_label.setText(text[:1].upper() + text[1:])
        self.prompt_label.setVisible(bool(text))
        if str(getattr(_state, "value", "")) == "running":
            self._finished = ""
            self._update_info()

    def _on_finished(self, summary: object) -> None:
        if getattr(summary, "completed", False):
            self._finished = tr("Program finished in {0}").format(
                format_duration(float(getattr(summary, "cycle_time_s", float("nan")))))
            self._fraction, self._remaining = 1.0, 0.0
            self.progress.setValue(1000)
        else:
            self._finished = tr("Program stopped at line {0}: {1}").format(
                int(getattr(summary, "last_line", 0)), localize(str(getattr(summary, "reason", ""))))
        self._update_info()

    def _on_errors(self, _issues: object) -> None:
        """A refused load: the previous program's progress is not this program's."""
        self._fraction, self._remaining, self._line, self._finished = 0.0, float("nan"), 0, ""
        self.progress.setValue(0)
        self._update_info()

    def showEvent(self, event) -> None:  # noqa: N802 - Qt override
        super().showEvent(event)
        self.show_stale()        # the Program page may have saved the file meanwhile

    def saved_differs(self) -> bool:
        """The loaded program's file was saved from the editor with other text since it was
        loaded."""
        doc, model = self.ctx.document, self.ctx.program
        if doc is None or doc.path is None or not model.path or model.info is None:
            return False
        return Path(model.path).resolve() == doc.path and doc.saved_text != model.text

    def show_stale(self) -> None:
        stale = self.saved_differs()
        if stale:
            self.stale_note.setText(tr("{0} was saved with changes since it was loaded: the machine runs "
                                       "the program as loaded.").format(self.ctx.program.name))
        self.stale_note.setVisible(stale)
        self.reload_button.setVisible(stale)

    def reload_saved(self) -> None:
        doc = self.ctx.document
        if doc is not None and doc.path is not None:
            self.ctx.controller.load_program(doc.path)

    def _programmed_feed_and_modal(self) -> tuple[float, str]:
        """F (mm/min) and the modal codes of the move at the current line (0, "" if none)."""
        model = self.ctx.program
        program = model.program
        if program is None or not program.moves:
            return 0.0, ""
        i = min(model.move_at_line(max(self._line, 1)), len(program.moves) - 1)
        move = program.moves[i]
        feed = float(move.feed_mm_s) * 60.0 if np.isfinite(move.feed_mm_s) else 0.0
        return feed, program.modal_at_move(i)

    def _update_info(self) -> None:
        text = tr("Line {0}   Progress {1:.0f} %\nRemaining {2}   Path speed {3}").format(
            self._line, 100 * self._fraction,
            # at 0 % nothing moves: no time is left to count until the override is raised
            format_duration(float("nan") if self._feed_pct == 0.0 else self._remaining),
            format_speed(self._speed))
        # the end of a run or a refusal takes the second line's place: the page never grows
        if self._block_delete:       # what runs is not every line shown
            first, second = text.split("\n", 1)
            text = first + "   " + tr("/ lines skipped") + "\n" + second
        note = self._refused or self._finished or self._why_start
        if note:
            text = text.split("\n")[0] + "\n" + note
        self.info_label.setText(text)
        sp = self._spindle
        direction = int(getattr(sp, "direction", 0))
        rpm = float(getattr(sp, "commanded_rpm", 0.0))
        spindle = (tr("Spindle off") if direction == 0 else
                   tr("Spindle {0} {1:.0f} rpm").format(tr("CW") if direction > 0 else tr("CCW"), rpm))
        feed, modal = self._programmed_feed_and_modal()
        lines = [spindle + "   " + tr("Tool {0}").format(tool_text(self._tools, self._tool)),
                 tr("Feed F{0:.0f} programmed, {1} now").format(feed, format_speed(self._speed))]
        self.modal_label.setText(modal)
        self.machine_label.setText("\n".join(lines))

    def _update_buttons(self) -> None:
        """Each button enabled when its command would be taken; a disabled one says why (its
        tooltip, and Cycle start's reason on the info line)."""
        c = self.ctx.controller
        why_start = ""
        for key, label, _obj, action in BUTTONS:
            reason = c.refusal(action)
            if key == "start" and str(getattr(c.state, "value", "")) == "hold":
                reason = c.refusal("resume")
            elif key == "start" and self.ctx.program.errors:
                reason = "program has errors"
            button = self.buttons[key]
            button.setEnabled(not reason)
            button.setToolTip(tr("{0}: {1}").format(tr(label), localize(reason)) if reason else "")
            if key == "start" and reason and str(getattr(c.state, "value", "")) not in ("running", "hold"):
                # while it runs or holds the other buttons are the ones to use: no note then
                why_start = tr("{0}: {1}").format(tr(label), localize(reason))
        reason = c.refusal("run_from_line")
        self.run_from.setEnabled(not reason)
        self.run_from.setToolTip(tr("Run from line: {0}").format(localize(reason)) if reason else "")
        if why_start != self._why_start:
            self._why_start = why_start
            self._update_info()


def create_page(context: PanelContext) -> QWidget:
    return AutoPage(context)
