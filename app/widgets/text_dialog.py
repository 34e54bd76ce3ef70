"""Text entry for touch: a line (optionally hidden, for passwords) with the on-screen keyboard."""

from __future__ import annotations

from PySide6.QtWidgets import QDialog, QHBoxLayout, QLabel, QLineEdit, QPushButton, QVBoxLayout, QWidget

from app.i18n import tr
from app.widgets.keyboard import OnScreenKeyboard


class TextDialog(QDialog):
    def __init__(self, title: str, label: str, password: bool = False, text: str = "",
                 parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setWindowTitle(title)
        self.setModal(True)
        self.setMinimumWidth(900)
        layout = QVBoxLayout(self)
        layout.addWidget(QLabel(label))
        self.field = QLineEdit(text)
        self.field.setMinimumHeight(56)
        if password:
            self.field.setEchoMode(QLineEdit.EchoMode.Password)
        layout.addWidget(self.field)
        self.keyboard = OnScreenKeyboard()
        self.keyboard.set_target(self.field)
        layout.addWidget(self.keyboard)
        row = QHBoxLayout()
        row.addStretch(1)
        cancel, ok = QPushButton(tr("Cancel")), QPushButton(tr("OK"))
        cancel.setMinimumWidth(160)
        ok.setMinimumWidth(160)
        cancel.clicked.connect(self.reject)
        ok.clicked.connect(self.accept)
        self.field.returnPressed.connect(self.accept)
        row.addWidget(cancel)
        row.addWidget(ok)
        layout.addLayout(row)
        self.field.setFocus()

    def text(self) -> str:
        return self.field.text()
