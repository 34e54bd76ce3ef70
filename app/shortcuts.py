"""Keys of a keyboard at the panel, as LinuxCNC's panels have them, configurable.

By default F1 toggles the E-stop (releasing asks to confirm, as the E-STOP button does), Esc
stops whatever moves, and - only while no text field has the focus, so typing G-code never
moves the machine - the arrows jog X and Y and Page Up / Page Down jog Z while held (released:
the jog stops). Auto-repeat is ignored: holding a key is one jog, not a hundred.

The bindings are the panel's settings (``shortcuts`` in ``panel.json``: action -> key name as
Qt writes it, e.g. ``"jog_z_plus": "Home"``). A name that is not a key or an action that does
not exist is reported and that action keeps its default key; ``""`` unbinds an action.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass

from PySide6.QtCore import QEvent, Qt
from PySide6.QtGui import QKeyEvent, QKeySequence
from PySide6.QtWidgets import QAbstractSpinBox, QApplication, QLineEdit, QPlainTextEdit, QTextEdit

from app.machine.model import MachineState

__all__ = ["DEFAULT_SHORTCUTS", "Bindings", "Shortcuts", "parse_bindings"]

#: action -> key name (QKeySequence text)
DEFAULT_SHORTCUTS: dict[str, str] = {
    "estop_toggle": "F1", "stop": "Esc",
    "jog_x_plus": "Right", "jog_x_minus": "Left",
    "jog_y_plus": "Up", "jog_y_minus": "Down",
    "jog_z_plus": "PgUp", "jog_z_minus": "PgDown",
}
_TEXT_WIDGETS = (QLineEdit, QPlainTextEdit, QTextEdit, QAbstractSpinBox)


@dataclass(frozen=True, slots=True)
class Bindings:
    """Key code -> action, and what was wrong in the settings (one message per bad entry)."""

    keys: Mapping[int, str]
    problems: tuple[str, ...] = ()


def _key_code(name: str) -> int | None:
    seq = QKeySequence(name)
    if seq.count() != 1:
        return None
    combo = seq[0]  # type: ignore[index]  # QKeySequence[i] is a QKeyCombination (not in the stubs)
    if combo.keyboardModifiers() != Qt.KeyboardModifier.NoModifier:
        return None  # a jog key that needs Ctrl held is a chord, not a jog key
    code = int(combo.key().value)
    return None if code == int(Qt.Key.Key_unknown.value) else code


def parse_bindings(overrides: Mapping[str, str] | None = None) -> Bindings:
    """The defaults with ``overrides`` applied; bad entries are named and keep the default."""
    names = dict(DEFAULT_SHORTCUTS)
    problems: list[str] = []
    for action, key in (overrides or {}).items():
        if action not in DEFAULT_SHORTCUTS:
            problems.append(f"shortcut {action!r}: no such action (known: {', '.join(DEFAULT_SHORTCUTS)})")
        elif not isinstance(key, str):
            problems.append(f"shortcut {action!r}: the key must be a name like \"F2\", got {key!r}")
        elif key == "":
            names[action] = ""
        elif _key_code(key) is None:
            problems.append(f"shortcut {action!r}: {key!r} is not a single key without modifiers; "
                            f"{DEFAULT_SHORTCUTS[action]} kept")
        else:
            names[action] = key
    keys: dict[int, str] = {}
    for action, key in names.items():
        if not key:
            continue
        code = _key_code(key)
        assert code is not None
        if code in keys:
            problems.append(f"shortcut {action!r}: {key} is already {keys[code]!r}; {action!r} is unbound")
            continue
        keys[code] = action
    return Bindings(keys, tuple(problems))


class Shortcuts:
    def __init__(self, controller: object, release_estop: Callable[[], None],
                 bindings: Bindings | None = None) -> None:
        self.c = controller
        self.release_estop = release_estop
        self.bindings = bindings or parse_bindings()
        self.jogging: str = ""

    def handle(self, event: QEvent) -> bool:
        """True when the key was the panel's (the event is then consumed)."""
        if event.type() not in (QEvent.Type.KeyPress, QEvent.Type.KeyRelease):
            return False
        assert isinstance(event, QKeyEvent)
        action = self.bindings.keys.get(int(event.key()))
        if action is None:
            return False
        press = event.type() == QEvent.Type.KeyPress
        c = self.c
        if action == "estop_toggle":
            if press and not event.isAutoRepeat():
                if c.state is MachineState.ESTOP:  # type: ignore[attr-defined]
                    self.release_estop()
                else:
                    c.estop("E-stop key")  # type: ignore[attr-defined]
            return True
        if action == "stop":
            if press and not event.isAutoRepeat():
                if self.jogging:
                    c.jog_stop(None)  # type: ignore[attr-defined]
                    self.jogging = ""
                elif c.state in (MachineState.RUNNING, MachineState.HOLD):  # type: ignore[attr-defined]
                    c.stop()  # type: ignore[attr-defined]
            return True
        # a jog key: never while a text field has the focus (typing must not move the machine)
        if isinstance(QApplication.focusWidget(), _TEXT_WIDGETS):
            return False
        axis, direction = action[4].upper(), (1 if action.endswith("plus") else -1)
        if axis not in getattr(c, "axes", ()):
            return False
        if event.isAutoRepeat():
            return True
        if press and not self.jogging:
            if c.jog_start(axis, direction):  # type: ignore[attr-defined]
                self.jogging = axis
        elif not press and self.jogging == axis:
            c.jog_stop(axis)  # type: ignore[attr-defined]
            self.jogging = ""
        return True
