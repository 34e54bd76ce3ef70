"""Every text of the panel fits where it is shown and is in the operator's language.

- Every page and every tab of it, in English and Turkish, at 1280x800 and 1920x1080: no button,
  label or tab shows its text cut (wider than its room, or a wrapped label lower than its lines
  need), and no control or text moves between the states idle, running, feed hold, M0, M1, tool
  change, 0 % feed override, E-stop and alarm.
- Every dialog the pages ask (each button of each page and tab pressed, every question rendered
  as the operator sees it): nothing cut, nothing beyond the 1280x800 screen, no English word in
  Turkish.
- A shift in Turkish on the demo machine (homing, a run, feed hold, stop and the restart question,
  E-stop, the door, refusals, probing with a cutter, the alarm log): no English word on any page,
  in the status line or the alarm banner, apart from G-code, file names and the machine's own
  data (tool descriptions, terminal names from the configuration).
"""

from __future__ import annotations

import html
import re
from collections.abc import Iterator
from pathlib import Path

import pytest
from PySide6.QtCore import QRect
from PySide6.QtWidgets import (
    QAbstractButton,
    QApplication,
    QCheckBox,
    QDialog,
    QGroupBox,
    QLabel,
    QPushButton,
    QRadioButton,
    QStyle,
    QStyleOptionButton,
    QTabBar,
    QTableWidget,
    QTabWidget,
    QToolButton,
    QWidget,
)

from app import dialogs as dlg
from app.machine.model import HoldKind, MachineState
from app.widgets.elided_label import ElidedLabel
from app.widgets.keypad import NumericKeypad
from app.widgets.text_dialog import TextDialog
from machine_status import Prompt
from tests.app.conftest import ScriptedDialogs, make_window

ROOT = Path(__file__).resolve().parents[2]


# ------------------------------------------------------------------------------ what is cut
def cut_texts(root: QWidget) -> list[str]:
    """Texts shown cut: a button's or a one-line label's text wider than its room, a wrapped
    label lower than its lines, a tab's text wider than its tab."""
    cut = []
    for w in root.findChildren(QWidget):
        if not w.isVisibleTo(root):
            continue
        if isinstance(w, QAbstractButton) and w.text():
            fm = w.fontMetrics()
            wide = max(fm.horizontalAdvance(line) for line in w.text().replace("&&", "&").split("\n"))
            room = w.width() - (24 if isinstance(w, (QCheckBox, QRadioButton)) else 4)
            if isinstance(w, QPushButton):      # within its border and the style sheet's padding
                opt = QStyleOptionButton()
                w.initStyleOption(opt)
                room = w.style().subElementRect(QStyle.SubElement.SE_PushButtonContents, opt, w).width()
            if wide > room:
                cut.append(f"{type(w).__name__} {w.text()!r}: {wide} px in {room} px")
        elif isinstance(w, QLabel) and not isinstance(w, ElidedLabel) and w.text() and w.pixmap().isNull():
            if w.wordWrap():
                if w.heightForWidth(w.width()) > w.height():
                    need = w.heightForWidth(w.width())
                    cut.append(f"QLabel {w.text()[:60]!r}: {need} px high in {w.height()}")
            elif not w.text().lstrip().startswith("<"):
                wide = max(w.fontMetrics().horizontalAdvance(line) for line in w.text().split("\n"))
                room = w.contentsRect().width() - 2 * w.margin()
                if wide > room:
                    cut.append(f"QLabel {w.text()!r}: {wide} px in {room} px")
        elif isinstance(w, QTabBar):
            for i in range(w.count()):
                wide = w.fontMetrics().horizontalAdvance(w.tabText(i))
                if wide > w.tabRect(i).width() - 8:
                    cut.append(f"tab {w.tabText(i)!r}: {wide} px in {w.tabRect(i).width()} px")
    return cut


#: the views that resize with what they show (the editor and plots give room to a prompt)
_CONTENT = ("ProgramView", "PreviewPlot", "QWidget")


def places(window: QWidget) -> dict[tuple[str, str, int], tuple[QRect, str]]:
    """Where each visible control and text sits in the window."""
    out = {}
    for w in window.findChildren(QWidget):
        if not w.isVisibleTo(window) or type(w).__name__ in _CONTENT or type(w).__name__.endswith("Page"):
            continue
        if isinstance(w, (QAbstractButton, QLabel, QTabBar)) or w.objectName():
            text = w.text() if isinstance(w, (QAbstractButton, QLabel)) else ""
            out[(type(w).__name__, w.objectName(), id(w))] = (
                QRect(w.mapTo(window, w.rect().topLeft()), w.size()), text)
    return out


def views(window, qtbot) -> Iterator[str]:
    """Show every page, then every tab of each of its tab widgets in turn; yields the view's name."""
    for name in list(window._pages):
        window.show_page(name, ask_password=False)
        page = window.page(name)
        yield name
        for tabs in page.findChildren(QTabWidget):
            parent = tabs.parentWidget()
            while parent is not None and parent is not page:        # the tabs holding these ones
                if isinstance(parent, QTabWidget):
                    for i in range(parent.count()):
                        if parent.widget(i).isAncestorOf(tabs):
                            parent.setCurrentIndex(i)
                parent = parent.parentWidget()
            for i in range(tabs.count()):
                if tabs.isTabEnabled(i) and tabs.isTabVisible(i):
                    tabs.setCurrentIndex(i)
                    qtbot.wait(10)
                    yield f"{name}/{tabs.tabText(i)}"
            tabs.setCurrentIndex(0)


# ------------------------------------------------------------------------------ English words
_TS = (ROOT / "resources" / "translations" / "cnc_tr.ts").read_text(encoding="utf-8")
_WORD = r"[A-Za-zÇĞİÖŞÜçğıöşü]{3,}"
_KEYS = re.compile(r"\[\w+\] \w+")                 # "[probe] tool": a key of the configuration
_CODE = re.compile(r"[._/\\\[\]=\"{}]")        # file names, paths, configuration keys, placeholders


def _words(texts: list[str]) -> set[str]:
    """The words of ``texts``, lower case, outside names of files, keys and placeholders."""
    return {w.lower() for t in texts for token in _KEYS.sub(" ", html.unescape(t)).split()
            if not _CODE.search(token) for w in re.findall(_WORD, token)}


#: the words of the catalogue's English that its Turkish never uses
ENGLISH = (_words(re.findall(r"<source>(.*?)</source>", _TS, re.S))
           - _words(re.findall(r"<translation>(.*?)</translation>", _TS, re.S)))


def shown_texts(root: QWidget) -> list[tuple[str, str]]:
    """(where, text) of every visible label, button, tab, group title and table cell; a label
    cut with "…" by its width is read whole from its tooltip."""
    out = []
    for w in root.findChildren(QWidget):
        if not w.isVisibleTo(root):
            continue
        name = f"{type(w).__name__}:{w.objectName()}"
        if isinstance(w, (QLabel, QAbstractButton)):
            text = w.text()
            if text.endswith("…") and w.toolTip():
                text = w.toolTip()
            out.append((name, text))
        elif isinstance(w, QTabBar):
            out += [(name, w.tabText(i)) for i in range(w.count())]
        elif isinstance(w, QGroupBox):
            out.append((name, w.title()))
        elif isinstance(w, QTableWidget):
            for c in range(w.columnCount()):
                header = w.horizontalHeaderItem(c)
                if header is not None:
                    out.append((name, header.text()))
            for r in range(w.rowCount()):
                for c in range(w.columnCount()):
                    item = w.item(r, c)
                    if item is not None:
                        out.append((f"{name}[{c}]", item.text()))
    return out


def english_words(text: str, data: set[str]) -> list[str]:
    """The English words in ``text``: file names, paths and the machine's own data aside."""
    for d in data:
        text = text.replace(d, " ")
    text = _KEYS.sub(" ", text)
    found = []
    for token in text.split():
        if not _CODE.search(token):
            found += [w for w in re.findall(_WORD, token) if w.lower() in ENGLISH]
    return found


def machine_data(controller) -> set[str]:
    """Texts the integrator and the shop wrote (tool descriptions, terminal names)."""
    data = {t.description for t in controller.tool_table.tools.values() if t.description}
    return data | {t.name for t in controller.config.wiring.terminals if t.name}


def test_the_english_word_list_knows_the_panels_words() -> None:
    """The detector's list holds the words it must catch and not the Turkish ones."""
    assert {"spindle", "feed", "homing", "output", "rpm", "enter"} <= ENGLISH
    assert english_words("İş mili durdu   Takım T1 (6 mm flat end mill)", {"6 mm flat end mill"}) == []
    assert english_words("Tool: T1 spindle off", set()) == ["Tool", "spindle", "off"]


# ------------------------------------------------------------------------------ the pages
STATES = (
    ("running", lambda fc: fc._set_state(MachineState.RUNNING, "program")),
    ("feed hold", lambda fc: fc._set_state(MachineState.HOLD, "feed hold", HoldKind.FEED_HOLD)),
    ("M0", lambda fc: (setattr(fc, "prompt", Prompt(HoldKind.PROGRAM_STOP, 12, 0, "M00 at line 12: program "
                                                    "stop; press cycle start to go on")),
                       fc._set_state(MachineState.HOLD, "M00", HoldKind.PROGRAM_STOP))),
    ("M1", lambda fc: (setattr(fc, "prompt", Prompt(HoldKind.OPTIONAL_STOP, 14, 0, "M01 at line 14: optional "
                                                    "stop; press cycle start to go on")),
                       fc._set_state(MachineState.HOLD, "M01", HoldKind.OPTIONAL_STOP))),
    ("tool change", lambda fc: (setattr(fc, "prompt", Prompt(HoldKind.TOOL_CHANGE, 20, 2,
                                                             "M06 at line 20: put T2 in the spindle")),
                                fc._set_state(MachineState.HOLD, "tool change", HoldKind.TOOL_CHANGE))),
    ("0 % override", lambda fc: (fc._set_state(MachineState.RUNNING, "program"), fc.set_feed_override(0.0))),
    ("E-stop", lambda fc: (fc.set_feed_override(100.0), fc._set_state(MachineState.ESTOP, "operator"))),
    ("alarm", lambda fc: fc._set_state(MachineState.ALARM, "following error")),
)


@pytest.mark.parametrize("size", [(1280, 800), (1920, 1080)])
@pytest.mark.parametrize("language", ["en", "tr"])
def test_no_text_is_cut_and_nothing_moves_on_any_page_or_tab_in_any_state(
        fake_window, fake_controller, qtbot, tmp_path, size, language) -> None:
    fc = fake_controller
    # a long program name: it is cut with "…", never squeezing the buttons beside it
    long = tmp_path / "a_rather_long_program_name_for_the_mould_cavity_roughing_pass_03.ngc"
    long.write_text("G21 G90\nG0 X0 Y0\nG1 X10 F300\nM0\nM30\n")
    assert fc.load_program(long)
    fake_window.context.i18n.set_language(language)
    fake_window.resize(*size)
    problems: list[str] = []
    seen: list[str] = []
    for view in views(fake_window, qtbot):
        seen.append(view)
        qtbot.wait(20)
        idle = places(fake_window)
        problems += [f"{view}, idle: {c}" for c in cut_texts(fake_window)]
        if (fake_window.width(), fake_window.height()) != size:
            problems.append(f"{view}: the window grew to {fake_window.width()}x{fake_window.height()}")
            fake_window.resize(*size)
        for state, set_state in STATES:
            set_state(fc)
            qtbot.wait(20)
            now = places(fake_window)
            problems += [f"{view}, {state}: {k[0]} {k[1]!r} {text[:30]!r} moved {idle[k][0].getRect()} -> "
                         f"{rect.getRect()}" for k, (rect, text) in now.items()
                         if k in idle and idle[k][0] != rect]
            problems += [f"{view}, {state}: {c}" for c in cut_texts(fake_window)]
            if (fake_window.width(), fake_window.height()) != size:
                problems.append(f"{view}, {state}: the window grew to {fake_window.width()}x"
                                f"{fake_window.height()}")
                fake_window.resize(*size)
            fc._set_state(MachineState.IDLE, "ready")
            qtbot.wait(10)
    assert len(seen) == 19, seen           # 11 pages and the tabs of Part zero and Diagnostics
    assert not problems, "\n".join(problems[:40])
    assert (fake_window.width(), fake_window.height()) == size


# ------------------------------------------------------------------------------ the dialogs
class RenderingDialogs(ScriptedDialogs):
    """Each question built as the operator sees it (the panel's own dialog classes), shown,
    measured and read, then answered as scripted (by default: no, cancel)."""

    def __init__(self, qtbot, language: str, data: set[str]) -> None:
        super().__init__()
        self.qtbot, self.language, self.data = qtbot, language, data
        self.default_confirm = False
        self.problems: list[str] = []
        self.shown: list[str] = []

    def _render(self, kind: str, box: QDialog) -> None:
        box.show()
        self.qtbot.wait(20)
        title = box.windowTitle()
        self.shown.append(f"{kind}: {title}")
        self.problems += [f"{kind} {title!r}: {c}" for c in cut_texts(box)]
        screen = QRect(0, 0, 1280, 800)
        if box.width() > screen.width() or box.height() > screen.height():
            self.problems.append(f"{kind} {title!r}: {box.width()}x{box.height()} px, beyond the screen")
        if self.language == "tr":
            for where, text in [*shown_texts(box), ("title", title)]:
                words = english_words(text, self.data)
                if words:
                    self.problems.append(f"{kind} {title!r} {where}: {words} in {text[:90]!r}")
        box.close()

    def confirm(self, parent, title, text) -> bool:  # type: ignore[override]
        self._render("confirm", dlg.confirm_box(parent, title, text)[0])
        return super().confirm(parent, title, text)

    def choose(self, parent, title, text, options) -> int:  # type: ignore[override]
        self._render("choose", dlg.choice_box(parent, title, text, options)[0])
        return super().choose(parent, title, text, options)

    def ask_number(self, parent, title, value, minimum=-1e9, maximum=1e9, decimals=3):  # type: ignore[override]
        self._render("number", NumericKeypad(title, value, minimum, maximum, decimals, parent))
        return super().ask_number(parent, title, value, minimum, maximum, decimals)

    def ask_text(self, parent, title, label, password=False, text=""):  # type: ignore[override]
        self._render("text", TextDialog(title, label, password, text, parent))
        return super().ask_text(parent, title, label, password, text)

    def ask_open_file(self, parent, directory, folders=None, suffixes=None):  # type: ignore[override]
        self._render("open", dlg.file_picker(parent, directory, folders, suffixes or dlg.GCODE_SUFFIXES))
        return super().ask_open_file(parent, directory, folders, suffixes)

    def inform(self, parent, title, text) -> None:  # type: ignore[override]
        self._render("inform", dlg.inform_box(parent, title, text))
        super().inform(parent, title, text)


#: buttons the walk does not press: they change page or language, or move the machine
_NOT_PRESSED = {"cycleStart", "navButton", "estopButton", "jogButton", "languageButton"}


@pytest.mark.parametrize("language", ["en", "tr"])
def test_every_dialog_the_pages_ask_fits_and_is_in_the_panels_language(qtbot, qapp, state_dir,
                                                                       real_controller, language) -> None:
    from app.context import PanelOptions

    c = real_controller
    asked = RenderingDialogs(qtbot, language, set())
    window = make_window(qtbot, qapp, PanelOptions(demo=True, state_dir=state_dir), asked, c)
    qtbot.waitUntil(lambda: c.program_info is not None, timeout=20000)
    assert c.set_machine_zero_here()
    asked.data |= machine_data(c)
    window.context.i18n.set_language(language)
    try:
        for _view in views(window, qtbot):
            buttons = [b for b in [*window.findChildren(QPushButton), *window.findChildren(QToolButton)]
                       if b.isVisibleTo(window) and b.objectName() not in _NOT_PRESSED
                       and not b.isCheckable()]
            for b in buttons:
                if b.isVisibleTo(window) and b.isEnabled():
                    b.click()
                    qtbot.wait(5)
                    for w in QApplication.topLevelWidgets():
                        if isinstance(w, QDialog) and w.isVisible():
                            w.close()
    finally:
        window.context.i18n.set_language("en")
    kinds = {s.split(":")[0] for s in asked.shown}
    assert {"confirm", "number", "text", "open", "inform"} <= kinds, asked.shown
    assert len(set(asked.shown)) >= 15, asked.shown
    assert not asked.problems, "\n".join(asked.problems[:40])


# ------------------------------------------------------------------------------ a shift in Turkish
def test_a_shift_in_turkish_shows_no_english_word(qtbot, qapp, state_dir, real_controller) -> None:
    """The demo machine in Turkish from its start: unhomed, homing to its switches, a run, feed
    hold, stop and the restart question, E-stop and its release, the door opened during a run,
    refusals (a move beyond the travel, an MDI M6), probing with the end mill in the spindle and
    the alarm log. At each step every visible text (and a disabled button's reason) of the
    window, and every page and tab at the start and after the alarms, is read for English."""
    from app.context import PanelOptions

    c = real_controller
    asked = RenderingDialogs(qtbot, "tr", set())
    asked.default_confirm = True                      # the shift answers its questions with yes
    window = make_window(qtbot, qapp, PanelOptions(demo=True, state_dir=state_dir), asked, c)
    window.context.i18n.set_language("tr")
    try:
        qtbot.waitUntil(lambda: c.program_info is not None, timeout=20000)
        data = asked.data = machine_data(c)
        problems: list[str] = []
        steps: list[str] = []

        def look(step: str, every_view: bool = False) -> None:
            qtbot.wait(30)
            steps.append(step)
            for view in views(window, qtbot) if every_view else [window.current_page_name]:
                for where, text in shown_texts(window):
                    problems.extend(f"{step} ({view}) {where}: {w} in {text[:100]!r}"
                                    for w in english_words(text, data))
                for b in window.findChildren(QAbstractButton):
                    if b.isVisibleTo(window) and not b.isEnabled() and b.toolTip():
                        problems.extend(f"{step} ({view}) tooltip of {b.text()!r}: {w} in "
                                        f"{b.toolTip()[:100]!r}" for w in english_words(b.toolTip(), data))

        look("the start, unhomed", every_view=True)
        window.show_page("machine_zero")
        window.page("machine_zero").home_all_button.click()
        c.advance(0.5)
        look("homing")
        assert c.run_until(lambda: c.state is MachineState.IDLE and all(c.homed), 120)
        window.show_page("auto")
        auto = window.page("auto")
        auto.buttons["start"].click()
        c.advance(1.0)
        look("running")
        auto.buttons["hold"].click()
        c.advance(1.5)
        look("feed hold")
        auto.buttons["stop"].click()
        assert c.run_until(lambda: c.state is MachineState.IDLE, 10)
        look("stopped")
        asked.answers.append(-1)                      # the restart question: cancelled
        auto.buttons["start"].click()
        look("the restart question")
        window.header.estop_button.click()
        c.advance(0.2)
        look("E-stop", every_view=True)
        assert c.estop_release()
        c.advance(0.2)
        auto.buttons["reset"].click()
        c.advance(0.2)
        look("released")
        window.show_page("auto")
        asked.answers.append(1)                       # the restart question, if asked: from the start
        auto.buttons["start"].click()
        asked.answers.clear()
        c.advance(0.5)
        c.simulate_input("door_closed", False)
        c.advance(1.0)
        look("the door open in a run")
        auto.buttons["start"].click()
        look("cycle start with the door open")
        c.simulate_input("door_closed", None)
        auto.buttons["stop"].click()
        c.run_until(lambda: c.state is MachineState.IDLE, 10)
        c.mdi("G53 G0 X1000")
        look("a move beyond the travel")
        c.mdi("M6 T2")
        look("M6 from MDI")
        window.show_page("part_zero")
        part_zero = window.page("part_zero")
        part_zero.tabs.setCurrentWidget(part_zero.probing)
        part_zero.probing.run_button.click()
        look("probing with the end mill in the spindle")
        look("the alarm log", every_view=True)
    finally:
        window.context.i18n.set_language("en")
    assert len(steps) == 14 and len(asked.shown) >= 2, (steps, asked.shown)
    assert not asked.problems, "\n".join(asked.problems[:40])
    assert not problems, "\n".join(sorted(set(problems))[:60])
