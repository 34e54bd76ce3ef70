"""Find / go-to-line bar for the editor (text field opens the on-screen keyboard target)."""

from __future__ import annotations

from PySide6.QtCore import Signal
from PySide6.QtWidgets import QHBoxLayout, QLineEdit, QPushButton, QWidget

from app.i18n import N_, I18n


class FindBar(QWidget):
    findNext = Signal(str, bool)  # text, backward

    def __init__(self, i18n: I18n, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        layout = QHBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        self.field = QLineEdit()
        self.field.setMinimumHeight(48)
        i18n.bind(self.field, N_("Find…"), self.field.setPlaceholderText)
        self.prev_button = QPushButton("▲")
        self.next_button = QPushButton("▼")
        self.close_button = QPushButton("✕")
        layout.addWidget(self.field, 1)
        for b in (self.prev_button, self.next_button, self.close_button):
            b.setMinimumWidth(56)
            layout.addWidget(b)
        self.next_button.clicked.connect(lambda: self.findNext.emit(self.field.text(), False))
        self.prev_button.clicked.connect(lambda: self.findNext.emit(self.field.text(), True))
        self.field.returnPressed.connect(lambda: self.findNext.emit(self.field.text(), False))
        self.close_button.clicked.connect(self.hide)
