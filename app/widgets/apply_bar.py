"""Apply / Revert bar for the service pages, with the validation message of the pending edit."""

from __future__ import annotations

from PySide6.QtWidgets import QHBoxLayout, QLabel, QPushButton, QWidget

from app.i18n import N_, I18n


class ApplyBar(QWidget):
    def __init__(self, i18n: I18n, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        layout = QHBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        self.message = QLabel()
        self.message.setObjectName("errorLine")
        self.message.setWordWrap(True)
        self.apply_button = QPushButton()
        self.apply_button.setObjectName("cycleStart")
        i18n.bind(self.apply_button, N_("Apply"))
        self.revert_button = QPushButton()
        i18n.bind(self.revert_button, N_("Revert"))
        layout.addWidget(self.message, 1)
        layout.addWidget(self.revert_button)
        layout.addWidget(self.apply_button)

    def set_state(self, dirty: bool, error: str) -> None:
        self.message.setText(error)
        self.apply_button.setEnabled(dirty and not error)
        self.revert_button.setEnabled(dirty)
