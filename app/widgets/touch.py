"""Touch helpers: kinetic scrolling on scroll areas (QScroller), touch-sized item views."""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import TypeVar

from PySide6.QtWidgets import (
    QAbstractButton,
    QAbstractItemView,
    QAbstractScrollArea,
    QBoxLayout,
    QButtonGroup,
    QScroller,
    QWidget,
)

K = TypeVar("K")
B = TypeVar("B", bound=QAbstractButton)


def enable_kinetic_scrolling(area: QAbstractScrollArea, mouse: bool = True) -> None:
    """Flick to scroll with a finger; ``mouse``: also by dragging with the left mouse button
    (lists, tables, forms). Text editors keep mouse drags for selecting text (touch only)."""
    kind = (QScroller.ScrollerGestureType.LeftMouseButtonGesture if mouse
            else QScroller.ScrollerGestureType.TouchGesture)
    QScroller.grabGesture(area.viewport(), kind)
    if isinstance(area, QAbstractItemView):
        area.setVerticalScrollMode(QAbstractItemView.ScrollMode.ScrollPerPixel)
        area.setHorizontalScrollMode(QAbstractItemView.ScrollMode.ScrollPerPixel)


def touch_rows(view: QAbstractItemView, height_px: int = 48) -> None:
    """Rows at least one touch target high; kinetic scrolling."""
    header = getattr(view, "verticalHeader", None)
    if header is not None:
        header().setDefaultSectionSize(height_px)
        header().setMinimumSectionSize(height_px)
    else:              # a list: its rows, as a table's
        view.setStyleSheet(view.styleSheet() + f" QListView::item {{ min-height: {height_px}px; }}")
    enable_kinetic_scrolling(view)

def exclusive_buttons(
    owner: QWidget,
    layout: QBoxLayout,
    choices: Iterable[tuple[K, B]],
    on_choose: Callable[[K], object] | None = None,
) -> tuple[QButtonGroup, dict[K, B]]:
    """A row of checkable buttons of which one is checked at a time: the touch form of a
    radio group (plane, work offset, jog increment). Returns the group and the buttons by key."""
    group = QButtonGroup(owner)
    buttons: dict[K, B] = {}
    for key, button in choices:
        button.setCheckable(True)
        if on_choose is not None:
            button.clicked.connect(lambda _=False, k=key: on_choose(k))
        group.addButton(button)
        layout.addWidget(button)
        buttons[key] = button
    return group, buttons
