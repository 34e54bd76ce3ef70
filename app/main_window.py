"""Main window: navigation column, page stack, status bar."""

from __future__ import annotations

import importlib

from PySide6.QtCore import Signal
from PySide6.QtWidgets import (
    QButtonGroup,
    QHBoxLayout,
    QLabel,
    QMainWindow,
    QPushButton,
    QStackedWidget,
    QVBoxLayout,
    QWidget,
)

from app.context import PanelOptions
from app.pages import PAGES, PageInfo, page_info
from app.pages.placeholder import PlaceholderPage


def build_page(info: PageInfo, context: object) -> QWidget:
    """The page's own module if it exists, else a placeholder that says it is not built yet."""
    try:
        module = importlib.import_module(f"app.pages.{info.module}")
    except ModuleNotFoundError as exc:
        if exc.name != f"app.pages.{info.module}":
            raise
        return PlaceholderPage(info.label)
    return module.create_page(context)


class MainWindow(QMainWindow):
    pageChanged = Signal(str)

    def __init__(self, options: PanelOptions, context: object | None = None) -> None:
        super().__init__()
        self.options = options
        self.context = context
        self.setWindowTitle("CNC panel")
        central = QWidget()
        root = QHBoxLayout(central)
        root.setContentsMargins(4, 4, 4, 4)

        nav = QVBoxLayout()
        self._nav_group = QButtonGroup(self)
        self._nav_group.setExclusive(True)
        self._buttons: dict[str, QPushButton] = {}
        self._stack = QStackedWidget()
        self._pages: dict[str, QWidget] = {}
        for info in PAGES:
            button = QPushButton(info.label)
            button.setObjectName("navButton")
            button.setCheckable(True)
            button.setMinimumHeight(56)
            button.setMinimumWidth(170)
            button.clicked.connect(lambda _=False, name=info.name: self.show_page(name))
            self._nav_group.addButton(button)
            nav.addWidget(button)
            self._buttons[info.name] = button
            page = build_page(info, context if context is not None else options)
            self._pages[info.name] = page
            self._stack.addWidget(page)
        nav.addStretch(1)
        root.addLayout(nav)
        root.addWidget(self._stack, 1)
        self.setCentralWidget(central)

        self._state_label = QLabel("state: demo" if options.demo else "state: disconnected")
        self.statusBar().addPermanentWidget(self._state_label)
        self.show_page(options.page)

    def show_page(self, name: str) -> None:
        info = page_info(name)
        self._stack.setCurrentWidget(self._pages[info.name])
        self._buttons[info.name].setChecked(True)
        self.statusBar().showMessage(info.label)
        self.pageChanged.emit(info.name)

    def page(self, name: str) -> QWidget:
        return self._pages[page_info(name).name]

    @property
    def current_page_name(self) -> str:
        current = self._stack.currentWidget()
        return next(n for n, w in self._pages.items() if w is current)
