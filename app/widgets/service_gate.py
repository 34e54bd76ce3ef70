"""Service-level pages sit behind this gate: a lock screen until the password is entered."""

from __future__ import annotations

from PySide6.QtCore import Qt, Signal
from PySide6.QtWidgets import QLabel, QPushButton, QStackedWidget, QVBoxLayout, QWidget

from app.i18n import N_, I18n


class ServiceGate(QStackedWidget):
    unlockRequested = Signal()

    def __init__(self, page: QWidget, i18n: I18n, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.page = page
        self.lock_screen = QWidget()
        layout = QVBoxLayout(self.lock_screen)
        layout.addStretch(1)
        title = QLabel()
        title.setObjectName("pageTitle")
        title.setAlignment(Qt.AlignmentFlag.AlignCenter)
        i18n.bind(title, N_("Service level"))
        note = QLabel()
        note.setObjectName("placeholderNote")
        note.setAlignment(Qt.AlignmentFlag.AlignCenter)
        note.setWordWrap(True)
        i18n.bind(note, N_("This page changes the machine configuration. Enter the service password."))
        self.unlock_button = QPushButton()
        self.unlock_button.setMinimumHeight(64)
        i18n.bind(self.unlock_button, N_("Unlock"))
        self.unlock_button.clicked.connect(self.unlockRequested.emit)
        layout.addWidget(title)
        layout.addWidget(note)
        layout.addWidget(self.unlock_button, 0, Qt.AlignmentFlag.AlignHCenter)
        layout.addStretch(1)
        self.addWidget(self.lock_screen)
        self.addWidget(page)
        self.set_locked(True)

    def set_locked(self, locked: bool) -> None:
        self.setCurrentWidget(self.lock_screen if locked else self.page)

    @property
    def locked(self) -> bool:
        return self.currentWidget() is self.lock_screen
