"""Touch file picker: folders and G-code files in a large, flickable list (no small native dialog)."""

from __future__ import annotations

from pathlib import Path

from PySide6.QtWidgets import QDialog, QHBoxLayout, QLabel, QListWidget, QPushButton, QVBoxLayout, QWidget

from app.i18n import tr
from app.program_folders import GCODE_SUFFIXES, ProgramFolders
from app.widgets.touch import touch_rows


class FilePicker(QDialog):
    """Folders and programs, confined to the program folders when given: ``..`` stops at a
    folder's top, where the list offers the other program folders instead."""

    def __init__(self, title: str, directory: Path, parent: QWidget | None = None,
                 folders: ProgramFolders | None = None, suffixes: tuple[str, ...] = GCODE_SUFFIXES) -> None:
        super().__init__(parent)
        self.folders = folders
        self.suffixes = tuple(suffixes)
        self.setWindowTitle(title)
        self.setModal(True)
        self.resize(900, 640)
        self.directory = Path(directory).resolve()
        self.selected: Path | None = None
        layout = QVBoxLayout(self)
        row = QHBoxLayout()
        self.up_button = QPushButton("⬆ ..")
        self.up_button.clicked.connect(self.go_up)
        self.where = QLabel()
        self.where.setWordWrap(True)
        row.addWidget(self.up_button)
        row.addWidget(self.where, 1)
        layout.addLayout(row)
        self.list = QListWidget()
        touch_rows(self.list, 56)
        self.list.itemClicked.connect(lambda item: self.choose(item.text()))
        layout.addWidget(self.list, 1)
        cancel = QPushButton(tr("Cancel"))
        cancel.clicked.connect(self.reject)
        layout.addWidget(cancel)
        self.show_directory(self.directory)

    def go_up(self) -> None:
        if self.folders is not None and self.folders.root_of(self.directory.parent) is None:
            return
        self.show_directory(self.directory.parent)

    def entries(self) -> list[str]:
        try:
            children = sorted(self.directory.iterdir(), key=lambda p: (not p.is_dir(), p.name.lower()))
        except OSError:
            children = []
        here = [p.name + "/" if p.is_dir() else p.name for p in children
                if not p.name.startswith(".") and (p.is_dir() or p.suffix.lower() in self.suffixes)]
        folders = self.folders
        if folders is None or not any(r.path == self.directory for r in folders.roots):
            return here
        # at the top of a program folder: the other program folders, by their full path
        return [str(r.path) + "/" for r in folders.roots if r.path != self.directory] + here

    def show_directory(self, directory: Path) -> None:
        directory = Path(directory).resolve()
        if self.folders is not None and not self.folders.may_browse(directory):
            directory = self.folders.default
        self.directory = directory
        if self.folders is not None:
            self.up_button.setEnabled(self.folders.root_of(directory.parent) is not None)
        self.where.setText(str(self.directory))
        self.list.clear()
        self.list.addItems(self.entries())

    def choose(self, name: str) -> None:
        if name.endswith("/"):
            self.show_directory(self.directory / name.rstrip("/"))
        else:
            self.selected = self.directory / name
            self.accept()
