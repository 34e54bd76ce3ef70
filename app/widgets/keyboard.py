"""On-screen keyboard for the program editor and MDI: letters, digits and G-code symbols.

Keys are sent as key events to the target widget, so undo, selection and highlighting work
as with a real keyboard. Buttons never take focus away from the target.
"""

from __future__ import annotations

from PySide6.QtCore import QCoreApplication, QEvent, Qt
from PySide6.QtGui import QKeyEvent
from PySide6.QtWidgets import QGridLayout, QPushButton, QSizePolicy, QWidget

from app.i18n import N_, tr

ROWS: tuple[tuple[str, ...], ...] = (
    ("1", "2", "3", "4", "5", "6", "7", "8", "9", "0", "-", ".", "⌫"),
    ("G", "M", "X", "Y", "Z", "A", "C", "I", "J", "K", "R", "F", "S"),
    ("Q", "W", "E", "T", "U", "O", "P", "D", "H", "L", "N", "B", "V"),
    ("Aa", "(", ")", ";", "%", "/", "=", "#", "←", "→", "_", "Space", "Enter"),
)
SPECIAL: dict[str, tuple[int, str]] = {
    "⌫": (Qt.Key.Key_Backspace, ""),
    "←": (Qt.Key.Key_Left, ""),
    "→": (Qt.Key.Key_Right, ""),
    "Space": (Qt.Key.Key_Space, " "),
    "Enter": (Qt.Key.Key_Return, "\r"),
}
#: the keys named in words, in the panel's language
KEY_TEXT = {"Space": N_("Space"), "Enter": N_("Enter")}


class OnScreenKeyboard(QWidget):
    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("onScreenKeyboard")
        self._target: QWidget | None = None
        self.lower_case = False  # "Aa" switches the letters to lower case (passwords, file names)
        # keys without the theme's wide padding: 13 keys a row fit beside the navigation in
        # 1280 px (with it the keyboard asked for 1600 px and pushed E-STOP off the screen)
        self.setStyleSheet("QPushButton { padding: 0px 2px; min-width: 48px; }")
        grid = QGridLayout(self)
        grid.setSpacing(4)
        grid.setContentsMargins(0, 0, 0, 0)
        self.buttons: dict[str, QPushButton] = {}
        for r, row in enumerate(ROWS):
            for c, key in enumerate(row):
                button = QPushButton(tr(KEY_TEXT[key]) if key in KEY_TEXT else key)
                button.setFocusPolicy(Qt.FocusPolicy.NoFocus)
                button.setMinimumSize(48, 48)
                button.setSizePolicy(QSizePolicy.Policy.Expanding, QSizePolicy.Policy.Fixed)
                button.setAutoRepeat(key in ("⌫", "←", "→"))
                button.clicked.connect(lambda _=False, k=key: self.press(k))
                grid.addWidget(button, r, c)
                self.buttons[key] = button

    def changeEvent(self, event: QEvent) -> None:  # noqa: N802 - Qt override
        if event.type() == QEvent.Type.LanguageChange:
            for key, text in KEY_TEXT.items():
                self.buttons[key].setText(tr(text))
        super().changeEvent(event)

    def set_target(self, widget: QWidget | None) -> None:
        self._target = widget

    def press(self, key: str) -> None:
        if key == "Aa":
            self.lower_case = not self.lower_case
            for k, button in self.buttons.items():
                if len(k) == 1 and k.isalpha():
                    button.setText(k.lower() if self.lower_case else k)
            return
        target = self._target
        if target is None:
            return
        if len(key) == 1 and key.isalpha() and self.lower_case:
            key = key.lower()
        code, text = SPECIAL.get(key, (0, key))
        if not code:
            code = ord(key.upper()) if len(key) == 1 else 0
        for kind in (QKeyEvent.Type.KeyPress, QKeyEvent.Type.KeyRelease):
            event = QKeyEvent(kind, code, Qt.KeyboardModifier.NoModifier, text)
            QCoreApplication.sendEvent(target, event)
