"""Touch file picker: folders and G-code files in a large, flickable list (no small native dialog)."""

from __future__ import annotations

from pathlib import Path

from PySide6.QtWidgets import QDialog, QHBoxLayout, QLabel, QListWidget, QPushButton, QVBoxLayout, QWidget

from app.i18n import tr
from app.widgets.touch import touch_rows

GCODE_SUFFIXES = (".nc", ".ngc", ".gcode", ".tap", ".txt", ".cnc")


class FilePicker(QDialog):
    def __init__(self, title: str, directory: Path, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setWindowTitle(title)
        self.setModal(True)
        self.resize(900, 640)
        self.directory = Path(directory).resolve()
        self.selected: Path | None = None
        layout = QVBoxLayout(self)
        row = QHBoxLayout()
        self.up_button = QPushButton("⬆ ..")
        self.up_button.clicked.connect(lambda: self.show_directory(self.directory.parent))
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

    def entries(self) -> list[str]:
        try:
            children = sorted(self.directory.iterdir(), key=lambda p: (not p.is_dir(), p.name.lower()))
        except OSError:
            return []
        return [p.name + "/" if p.is_dir() else p.name for p in children
                if not p.name.startswith(".") and (p.is_dir() or p.suffix.lower() in GCODE_SUFFIXES)]

    def show_directory(self, directory: Path) -> None:
        self.directory = Path(directory).resolve()
        self.where.setText(str(self.directory))
        self.list.clear()
        self.list.addItems(self.entries())

    def choose(self, name: str) -> None:
        if name.endswith("/"):
            self.show_directory(self.directory / name.rstrip("/"))
        else:
            self.selected = self.directory / name
            self.accept()
