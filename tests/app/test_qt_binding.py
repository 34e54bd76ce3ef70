"""The Qt binding must not leak or drop references to Python's singletons.

PySide6-Essentials 6.12.0 on Python 3.11 takes one reference off ``None`` on every call of a
method that returns nothing (QPointF.setX, QPainterPath.moveTo, ...). A live pyqtgraph plot makes
dozens of such calls per frame, so the panel aborted with "Fatal Python error: none_dealloc"
after a few minutes. pyproject.toml excludes that release; this test catches a regression on
upgrade before an operator does."""

from __future__ import annotations

import sys

from PySide6.QtCore import QPointF, QRectF
from PySide6.QtGui import QPainterPath


def test_void_and_bool_methods_keep_singleton_refcounts() -> None:
    point, rect, path = QPointF(0.5, 0.5), QRectF(0, 0, 1, 1), QPainterPath()
    before = {name: sys.getrefcount(obj) for name, obj in (("None", None), ("True", True),
                                                           ("False", False))}
    for _ in range(2000):
        point.setX(1.0)
        path.moveTo(1.0, 2.0)
        rect.contains(point)
        rect.isEmpty()
    after = {name: sys.getrefcount(obj) for name, obj in (("None", None), ("True", True),
                                                          ("False", False))}
    drift = {name: after[name] - before[name] for name in before}
    assert all(abs(d) < 100 for d in drift.values()), f"reference counts drifted: {drift}"


def test_signal_emit_keeps_singleton_refcounts() -> None:
    """6.12.0 also dropped a reference to True on every Python-side Signal.emit()."""
    from PySide6.QtCore import QCoreApplication, QObject, Signal

    class Source(QObject):
        changed = Signal(object, str)

    app = QCoreApplication.instance() or QCoreApplication([])
    assert app is not None
    source, received = Source(), []
    source.changed.connect(lambda value, text: received.append(value))
    before = sys.getrefcount(True), sys.getrefcount(None)
    for i in range(2000):
        source.changed.emit(i, "x")
    after = sys.getrefcount(True), sys.getrefcount(None)
    assert len(received) == 2000
    assert abs(after[0] - before[0]) < 100 and abs(after[1] - before[1]) < 100, (before, after)
