"""Program: edit G-code with line numbers, highlighting, find, go to line, errors marked as you
type; open / save / save as (atomic), autosave and recovery, on-screen keyboard; load the program
into the machine."""

from __future__ import annotations

from pathlib import Path

from PySide6.QtCore import QTimer
from PySide6.QtWidgets import QHBoxLayout, QLabel, QPushButton, QStackedWidget, QVBoxLayout, QWidget

from app import deferred
from app.context import PanelContext
from app.controller_text import localize
from app.format import with_column
from app.i18n import N_, tr
from app.machine.model import ProgramIssue
from app.program_checker import ProgramChecker
from app.widgets.code_editor import CodeEditor
from app.widgets.elided_label import ElidedLabel
from app.widgets.find_bar import FindBar
from app.widgets.keyboard import OnScreenKeyboard
from app.widgets.program_view import ProgramView
from app.widgets.touch import enable_kinetic_scrolling
from resources import PROGRAMS

AUTOSAVE_MS = 5000
# Above this many lines a program is shown read-only, through a view over its text: a text
# widget holds about 350 bytes a line and fills at ~100,000 lines a second in the GUI thread,
# so 2,000,000 lines took 700 MB and 20 s; such programs come from CAM and are edited there
EDIT_MAX_LINES = 100_000
# a file bigger than this (about 150,000 CAM lines) is opened by the controller's load: its
# worker reads and checks it, and the page shows the text it read; a page that read it first
# held the GUI thread a second at 10,000,000 lines
BIG_FILE_BYTES = 4 << 20
TOOLBAR = (
    ("new", N_("New")), ("open", N_("Open…")), ("save", N_("Save")), ("save_as", N_("Save as…")),
    ("find", N_("Find")), ("goto", N_("Go to line")), ("keyboard", N_("Keyboard")),
    ("load", N_("Load into machine")),
)


class ProgramPage(QWidget):
    def __init__(self, context: PanelContext, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("programPage")
        self.ctx = context
        self.doc = context.document
        i18n = context.i18n
        layout = QVBoxLayout(self)
        bar = QHBoxLayout()
        self.buttons: dict[str, QPushButton] = {}
        for key, label in TOOLBAR:
            button = QPushButton()
            i18n.bind(button, label)
            bar.addWidget(button)
            self.buttons[key] = button
        self.buttons["keyboard"].setCheckable(True)
        self.buttons["load"].setObjectName("cycleStart")
        layout.addLayout(bar)
        self.title = ElidedLabel()
        self.title.setObjectName("programName")
        title_row = QHBoxLayout()
        title_row.addWidget(self.title, 1)
        # the block delete switch beside the lines it skips ('/'): the program is checked
        # again with it; refused during a run (the controller says why, the button follows)
        self.block_delete = QPushButton()
        self.block_delete.setCheckable(True)
        i18n.bind(self.block_delete, N_("Block delete (/)"))
        self.block_delete.clicked.connect(lambda on: context.controller.set_block_delete(on))
        context.controller.modesChanged.connect(lambda _s, _o, on: self.block_delete.setChecked(on))
        self.block_delete.setChecked(context.controller.block_delete)
        title_row.addWidget(self.block_delete)
        layout.addLayout(title_row)
        self.find_bar = FindBar(i18n)
        self.find_bar.hide()
        layout.addWidget(self.find_bar)
        self.editor = CodeEditor()
        enable_kinetic_scrolling(self.editor, mouse=False)
        self.viewer = ProgramView()  # big programs, read-only
        enable_kinetic_scrolling(self.viewer)
        self._stack = QStackedWidget()
        self._stack.addWidget(self.editor)
        self._stack.addWidget(self.viewer)
        layout.addWidget(self._stack, 1)
        self.read_only_note = QLabel()
        self.read_only_note.setObjectName("readOnlyNote")
        self.read_only_note.setWordWrap(True)
        self.read_only_note.hide()
        layout.addWidget(self.read_only_note)
        self.error_label = QLabel()
        self.error_label.setObjectName("errorLine")
        self.error_label.setWordWrap(True)
        layout.addWidget(self.error_label)
        self.keyboard = OnScreenKeyboard()
        self.keyboard.set_target(self.editor)
        self.keyboard.hide()
        layout.addWidget(self.keyboard)

        self.checker = ProgramChecker(context.controller.config.machine)
        self.checker.checked.connect(self._on_checked)
        self._autosave = QTimer(self)
        self._autosave.setSingleShot(True)
        self._autosave.setInterval(AUTOSAVE_MS)
        self._autosave.timeout.connect(self.doc.autosave)
        self._loading = False
        self._opening: Path | None = None  # a big file being read by the controller, not shown yet

        self.buttons["new"].clicked.connect(self.new_program)
        self.buttons["open"].clicked.connect(self.open_dialog)
        self.buttons["save"].clicked.connect(self.save)
        self.buttons["save_as"].clicked.connect(self.save_as)
        self.buttons["find"].clicked.connect(self._show_find)
        self.buttons["goto"].clicked.connect(self.go_to_line_dialog)
        self.buttons["keyboard"].toggled.connect(self.keyboard.setVisible)
        self.buttons["load"].clicked.connect(self.load_into_machine)
        self.find_bar.findNext.connect(lambda text, back: self.shown.find_text(text, back))
        self.find_bar.field.installEventFilter(self)
        self.editor.textChanged.connect(self._on_text_changed)
        self.editor.lineActivated.connect(self._show_line_error)
        self.viewer.lineActivated.connect(self._show_line_error)
        context.program.lineRequested.connect(lambda line: self.shown.go_to_line(line))
        context.controller.configChanged.connect(self._on_config)
        context.controller.programLoaded.connect(self._on_program_loaded)
        context.controller.programErrors.connect(self._on_program_errors)
        self._update_title()

    # --- editing -------------------------------------------------------------------------
    @property
    def shown(self) -> CodeEditor | ProgramView:
        """The editor, or the read-only view of a program over ``EDIT_MAX_LINES`` lines."""
        return self.viewer if self._stack.currentWidget() is self.viewer else self.editor

    @property
    def read_only(self) -> bool:
        return self.shown is self.viewer

    def set_text(self, text: str, checked: bool = False, starts: object = None) -> None:
        """Show ``text``; ``checked``: the controller has just accepted exactly this text, so
        it has no errors (no second interpretation in the background). ``starts``: its line
        index when known (``ProgramInfo.line_starts``)."""
        self._loading = True
        lines = len(starts) - 1 if starts is not None else text.count("\n") + 1  # type: ignore[arg-type]
        big = lines > EDIT_MAX_LINES
        if big:
            self.editor.load_text("")  # the last small program's document goes
            self.viewer.load_text(text, starts=starts)  # type: ignore[arg-type]
            self._stack.setCurrentWidget(self.viewer)
            self.read_only_note.setText(tr(
                "{0} lines: shown read-only (edit programs of over {1} lines in CAM or on a PC)").format(
                self.viewer.line_count(), EDIT_MAX_LINES))
        else:
            self.viewer.load_text("")
            self._stack.setCurrentWidget(self.editor)
            self.editor.load_text(text, chunked=True)  # a big text in pieces (textChanged per piece)
        self.read_only_note.setVisible(big)
        self.buttons["keyboard"].setEnabled(not big)
        if big:
            self.buttons["keyboard"].setChecked(False)
        self._loading = False
        self.doc.text = text
        if checked:
            self.checker.cancel()
            self._on_checked({})
        elif big:  # the controller's check marks its errors (programErrors): not read twice
            self.checker.cancel()
        else:
            self.checker.check_now(text)
        self._update_title()

    def _on_text_changed(self) -> None:
        if self._loading or self.editor.loading or self.read_only:
            # not the operator's edit. Hidden behind a big program's read-only view, the emptied
            # editor still says its text changed (its highlighter redoes it a turn later): taken
            # for an edit, the program became "" with unsaved changes, autosaved so, and saved
            # so on the operator's Save
            return
        self.doc.text = self.editor.toPlainText()
        self.checker.request(self.doc.text)
        self._autosave.start()
        self._update_title()

    def _on_checked(self, errors: dict[int, str]) -> None:
        self.shown.set_errors(errors)
        self._show_line_error(self.shown.current_line())
        n = len(errors)
        if n and self.error_label.text() == "":
            first = min(errors)
            self.error_label.setText(tr("{0} error(s); first at line {1}: {2}").format(
                n, first, localize(errors[first])))

    def _show_line_error(self, line: int) -> None:
        errors = self.shown.errors
        if line in errors:
            self.error_label.setText(tr("Line {0}: {1}").format(line, localize(errors[line])))
        elif errors:
            first = min(errors)
            self.error_label.setText(tr("{0} error(s); first at line {1}: {2}").format(
                len(errors), first, localize(errors[first])))
        else:
            self.error_label.setText("")

    def _update_title(self) -> None:
        mark = " ●" if self.doc.modified else ""
        self.title.setText(f"{self.doc.name}{mark}")

    def _show_find(self) -> None:
        self.find_bar.show()
        self.find_bar.field.setFocus()
        self.keyboard.set_target(self.find_bar.field)

    def eventFilter(self, obj, event) -> bool:  # noqa: N802 - Qt override
        from PySide6.QtCore import QEvent

        if obj is self.find_bar.field and event.type() == QEvent.Type.FocusOut:
            self.keyboard.set_target(self.editor)
        return super().eventFilter(obj, event)

    def go_to_line_dialog(self) -> None:
        view = self.shown
        line = self.ctx.dialogs.ask_number(self, tr("Go to line"), float(view.current_line()), 1,
                                           float(max(1, view.blockCount())), 0)
        if line is not None:
            view.go_to_line(int(line))

    # --- files ---------------------------------------------------------------------------
    def can_close(self) -> bool:
        """Ask before unsaved changes are dropped: Save / Discard / Cancel."""
        if not self.doc.modified:
            return True
        choice = self.ctx.dialogs.choose(self, tr("Unsaved changes"),
                                         tr("{0} has unsaved changes.").format(self.doc.name),
                                         [tr("Save"), tr("Discard"), tr("Cancel")])
        if choice == 0:
            return self.save()
        if choice == 1:
            self.doc.discard_autosave()
            return True
        return False

    def new_program(self) -> None:
        if self.can_close():
            self.doc.new()
            self.set_text("")

    def open_dialog(self) -> None:
        if not self.can_close():
            return
        folders = self.ctx.folders
        assert folders is not None
        here = self.doc.path.parent if self.doc.path else None
        start = here if here is not None and folders.may_browse(here) else folders.default
        path = self.ctx.dialogs.ask_open_file(self, str(start), folders)
        if not path:
            return
        why = folders.check_open(path)
        if why:
            self.ctx.dialogs.inform(self, tr("Open program"), why)
            return
        self.open_program(Path(path))

    def open_program(self, path: Path) -> None:
        """Open ``path`` (chosen, allowed, and the program shown may go) and load it: a big
        file is read by the controller alone and shown once read."""
        try:
            big = path.stat().st_size > BIG_FILE_BYTES
        except OSError:
            big = False  # open_file says why it cannot be read
        if big:  # shown once the controller has read it (or refused it: then with its errors)
            self._opening = path
            # the program shown goes now (its changes are saved or dropped: asked above): held
            # while the next is read, a big one's text counted twice
            self.doc.new()
            self.set_text("")
            self.ctx.program.expect("", path.name)
            if not self.ctx.controller.load_program(path):
                self._open_refused()
            return
        self.open_file(path)
        # what the editor shows is what the machine has: opening a program loads it (the
        # controller checks it, or refuses while a program runs and says why)
        self.load_into_machine()

    def open_file(self, path: Path, checked_text: str | None = None, starts: object = None) -> None:
        """Open ``path``; ``checked_text``: the text the controller has just read from it and
        accepted (with its line index ``starts``)."""
        text = self.doc.open(path, checked_text)
        recovered = self.doc.recovery_text(path)
        if recovered is not None and self.ctx.dialogs.confirm(
                self, tr("Recover"), tr("An autosave of {0} with unsaved changes exists. Recover it?")
                .format(path.name)):
            self.set_text(recovered)
            self.doc.text = recovered
        else:
            self.doc.discard_autosave()
            self.set_text(text, checked=text == checked_text, starts=starts)
        self._update_title()

    def _save_with_errors(self) -> bool:
        """Whether to save a text with errors: asked, naming the first (True when it has none)."""
        errors = self.shown.errors
        if not errors:
            return True
        first = min(errors)
        return self.ctx.dialogs.confirm(
            self, tr("Save with errors?"),
            tr("{0} has {1} error(s), the first at line {2}: {3}. Save it anyway?").format(
                self.doc.name, len(errors), first, errors[first]))

    def save(self) -> bool:
        """Save to the file it came from; a new text, or a sample shipped with the control (kept as
        shipped, for every later start), asks for a name."""
        if self.doc.path is None or self.doc.path.resolve().is_relative_to(PROGRAMS.resolve()):
            return self.save_as()
        if not self._save_with_errors():
            return False
        try:
            self.doc.save()
        except OSError as exc:
            self.ctx.dialogs.inform(self, tr("Save failed"), str(exc))
            return False
        self._update_title()
        return True

    def save_as(self) -> bool:
        if not self._save_with_errors():
            return False
        folders = self.ctx.folders
        assert folders is not None
        here = self.doc.path.parent if self.doc.path else None
        folder = here if here is not None and folders.resolve_save(here, "x.nc") == here / "x.nc" \
            else folders.default
        name = self.ctx.dialogs.ask_save_file(self, str(folder))
        if not name:
            return False
        path = folders.resolve_save(folder, name)
        if isinstance(path, str):
            self.ctx.dialogs.inform(self, tr("Save failed"), path)
            return False
        try:
            self.doc.save(path)
        except OSError as exc:
            self.ctx.dialogs.inform(self, tr("Save failed"), str(exc))
            return False
        self._update_title()
        return True

    def load_into_machine(self) -> None:
        c = self.ctx.controller
        self.ctx.program.expect(self.doc.text, self.doc.name)
        if self.doc.path is not None and not self.doc.modified:
            c.load_program(self.doc.path)
        else:
            c.load_program(self.doc.text, name=self.doc.name)

    # --- controller ----------------------------------------------------------------------
    def _on_config(self, config: object) -> None:
        self.checker.machine = getattr(config, "machine", self.checker.machine)
        if not self.read_only:
            # a big program's errors come from the controller's own check again: read here as
            # well, a 10,000,000-line one was read twice at once (0.4 GB more)
            self.checker.request(self.doc.text)

    def _on_program_loaded(self, info: object) -> None:
        self._opening = None
        text = str(getattr(info, "text", ""))
        if self.doc.modified or text == self.doc.text:
            return
        if deferred.is_big(info):  # 35,000 lines take ~0.1 s: in an event-loop turn of their own
            deferred.run_soon("program-editor", lambda: self._show_loaded(info))
        else:
            self._show_loaded(info)

    def _show_loaded(self, info: object) -> None:
        if self.ctx.controller.program_info is not info or self.doc.modified:
            return  # superseded or refused meanwhile, or the operator started editing
        path = str(getattr(info, "path", "") or "")
        text = str(getattr(info, "text", ""))
        starts = getattr(info, "line_starts", None)
        if path:
            self.open_file(Path(path), checked_text=text, starts=starts)
        else:
            self.set_text(text, checked=True, starts=starts)

    def _open_refused(self) -> None:
        """A big file the controller refused: shown now, read here, so that its errors are
        marked on its own lines (the refusal is the rarer case)."""
        path, self._opening = self._opening, None
        if path is not None and path.is_file():
            self.open_file(path)
            self.ctx.program.expect(self.doc.text, self.doc.name)

    def _on_program_errors(self, issues: tuple[ProgramIssue, ...]) -> None:
        if self._opening is not None:
            self._open_refused()
            self.ctx.program.set_errors(issues, self.doc.text, self.doc.name)
        errors: dict[int, str] = {}
        for issue in issues:
            errors.setdefault(int(issue.line), with_column(int(issue.col), str(issue.message)))
        self.shown.set_errors(errors)
        self._show_line_error(self.shown.current_line())


def create_page(context: PanelContext) -> QWidget:
    return ProgramPage(context)
