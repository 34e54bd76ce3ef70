"""Modal questions the pages ask the operator, behind one object so tests can script answers.

Every dangerous action (run from a line, homing, parameter changes, discarding edits)
goes through ``confirm``; numbers through the on-screen keypad; text through a dialog
with the on-screen keyboard.
"""

from __future__ import annotations

from pathlib import Path

from PySide6.QtWidgets import QMessageBox, QPushButton, QWidget

from app.i18n import tr
from app.program_folders import GCODE_SUFFIXES, ProgramFolders
from app.widgets.file_picker import FilePicker
from app.widgets.keypad import ask_number
from app.widgets.text_dialog import TextDialog


class Dialogs:
    def confirm(self, parent: QWidget | None, title: str, text: str) -> bool:
        box, yes = confirm_box(parent, title, text)
        box.exec()
        return box.clickedButton() is yes

    def choose(self, parent: QWidget | None, title: str, text: str, options: list[str]) -> int:
        """Index of the chosen option, -1 when cancelled (e.g. Save / Discard / Cancel)."""
        box, buttons = choice_box(parent, title, text, options)
        box.exec()
        clicked = box.clickedButton()
        return buttons.index(clicked) if clicked in buttons else -1

    def ask_number(self, parent: QWidget | None, title: str, value: float, minimum: float = -1e9,
                   maximum: float = 1e9, decimals: int = 3) -> float | None:
        return ask_number(parent, title, value, minimum, maximum, decimals)

    def ask_text(self, parent: QWidget | None, title: str, label: str, password: bool = False,
                 text: str = "") -> str | None:
        dialog = TextDialog(title, label, password, text, parent)  # with the on-screen keyboard
        return dialog.text() if dialog.exec() == TextDialog.DialogCode.Accepted else None

    def ask_open_file(self, parent: QWidget | None, directory: str,
                      folders: ProgramFolders | None = None,
                      suffixes: tuple[str, ...] = GCODE_SUFFIXES) -> str | None:
        picker = file_picker(parent, directory, folders, suffixes)
        if picker.exec() == FilePicker.DialogCode.Accepted and picker.selected is not None:
            return str(picker.selected)
        return None

    def ask_save_file(self, parent: QWidget | None, directory: str) -> str | None:
        """A file name typed with the on-screen keyboard, to save in ``directory`` (the caller
        checks it: ``ProgramFolders.resolve_save``)."""
        name = self.ask_text(parent, tr("Save program as"), tr("File name in {0}:").format(directory))
        return name.strip() if name and name.strip() else None

    def inform(self, parent: QWidget | None, title: str, text: str) -> None:
        inform_box(parent, title, text).exec()


def file_picker(parent: QWidget | None, directory: str, folders: ProgramFolders | None = None,
                suffixes: tuple[str, ...] = GCODE_SUFFIXES) -> FilePicker:
    """The file picker of ``ask_open_file``, titled for programs or for any file."""
    title = tr("Open program") if suffixes == GCODE_SUFFIXES else tr("Open file")
    return FilePicker(title, Path(directory), parent, folders, suffixes)


def confirm_box(parent: QWidget | None, title: str, text: str) -> tuple[QMessageBox, QPushButton]:
    """A yes/no question and its "Yes" button; "No" the default and the escape (the safe answer
    to a dangerous action). The buttons are the panel's own, in its language: Qt's standard
    buttons would be named again in Qt's words at a language change."""
    box = QMessageBox(QMessageBox.Icon.Warning, title, text, QMessageBox.StandardButton.NoButton, parent)
    yes = box.addButton(tr("Yes"), QMessageBox.ButtonRole.YesRole)
    no = box.addButton(tr("No"), QMessageBox.ButtonRole.NoRole)
    box.setDefaultButton(no)
    box.setEscapeButton(no)
    return box, yes


def inform_box(parent: QWidget | None, title: str, text: str) -> QMessageBox:
    """A message to read, closed with OK in the panel's language."""
    box = QMessageBox(QMessageBox.Icon.Information, title, text, QMessageBox.StandardButton.NoButton, parent)
    box.setEscapeButton(box.addButton(tr("OK"), QMessageBox.ButtonRole.AcceptRole))
    return box


def choice_box(parent: QWidget | None, title: str, text: str,
               options: list[str]) -> tuple[QMessageBox, list[QPushButton]]:
    """The question with a button per option, each as wide as its text needs: the box grows to
    them (squeezed to the box's width, "Resume at line 12" read "esume at line 1")."""
    box = QMessageBox(QMessageBox.Icon.Question, title, text, QMessageBox.StandardButton.NoButton, parent)
    buttons = [box.addButton(o, QMessageBox.ButtonRole.ActionRole) for o in options]
    for button in buttons:
        button.setMinimumWidth(button.sizeHint().width())
    return box, buttons


def connect_or_disconnect(parent: QWidget | None, dialogs: Dialogs, controller: object,
                          connected: bool) -> None:
    """The operator's Connect / Disconnect (the header's bus status, the Diagnostics page's
    button): asked first, since it enables or disables the drives."""
    if connected:
        if dialogs.confirm(parent, tr("Disconnect"), tr("Stop and disable the drives?")):
            controller.disconnect_bus()  # type: ignore[attr-defined]
    elif dialogs.confirm(parent, tr("Connect"), tr("Connect to the drives and enable them?")):
        controller.connect_bus()  # type: ignore[attr-defined]
