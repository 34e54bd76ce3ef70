"""The controller's sentences shown in Turkish: every template translated with its values in
place, real sentences from the controller and the worker matched, English left as it is."""

from __future__ import annotations

import re

import pytest

from app.controller_text import TEMPLATES, localize
from app.i18n import tr
from app.message_text import CONTROLLER_TEMPLATES, GCODE_TEMPLATES
from planner.core.errors import ProgramError
from planner.gcode.interpreter import parse_program
from tools.i18n_catalog import MESSAGE_TEXT, controller_templates, current_message_text, interpreter_templates


@pytest.fixture
def turkish(qapp):
    """The Turkish translator installed (the panel's own I18n), English again afterwards."""
    from app.i18n import I18n

    i18n = I18n()
    i18n.set_language("tr")
    yield i18n
    i18n.set_language("en")


def _sample(template: str) -> tuple[str, list[str]]:
    n = len(set(re.findall(r"\{(\d+)\}", template)))
    values = [f"V{k}x" for k in range(n)]
    return template.format(*values), values


@pytest.mark.parametrize("template", sorted({*TEMPLATES, *CONTROLLER_TEMPLATES, *GCODE_TEMPLATES}))
def test_every_template_is_translated_with_its_values(turkish, template: str) -> None:
    english, values = _sample(template)
    turkish_text = localize(english)
    assert turkish_text == tr(template).format(*values)
    # "alarm" is the same word; the joiners read the same and say their parts in Turkish
    assert turkish_text != english or template in ("alarm", "{0}, {1}", "{0}: {1}", "{0} ({1})")
    for v in values:
        assert v in turkish_text


def test_english_stays_english(qapp) -> None:
    text = ("following error on axis X: +1.2000 exceeds window 1 for more than 3 cycles: "
            "quick stop of all axes")
    assert localize(text) == text
    assert localize("something the templates do not know") == "something the templates do not know"


def test_values_that_are_sentences_are_translated_too(turkish) -> None:
    assert localize("machine is running") == "makine çalışıyor durumunda"
    assert localize("the machine moved since it was loaded: pocket.nc is being checked again; it starts "
                     "when ready") == ("makine, program yüklendiğinden beri hareket etti: pocket.nc yeniden "
                                       "denetleniyor; hazır olunca başlayacak")


def test_a_joiner_says_each_of_its_parts_in_the_panels_language(turkish) -> None:
    """A list, a cause after its source and a reason in brackets: the parts the templates know
    are said in Turkish, the rest stays as it is."""
    assert localize("operator: E-stop pressed") == f"{tr('operator')}: {tr('E-stop pressed')}"
    assert localize("machine is hold (feed hold)") == tr("machine is {0}").format(
        f"{tr('hold')} ({tr('feed hold')})")
    assert localize("homing X searching the switch, Y latching the switch edge") == tr("homing {0}").format(
        tr("{0} searching the switch").format("X") + ", " + tr("{0} latching the switch edge").format("Y"))
    assert localize("pocket.nc (copy): x") == "pocket.nc (copy): x"


def test_the_real_sentences_match(turkish) -> None:
    """The controller's and the worker's own texts, not copies: a change there that the
    templates no longer match fails here."""
    from ethercat.worker import DriveSpec, WorkerConfig
    from ethercat.worker.messages import alarm_message
    from ethercat.worker.types import AlarmCode

    config = WorkerConfig(drives=(DriveSpec(position=0, axis_name="X", counts_per_unit=1000.0, direction=1,
                                            following_error_window=1.0),), ts_s=0.001, bus_kind="sim")
    for code, args in ((AlarmCode.FOLLOWING_ERROR, (0, 0, 1.25)), (AlarmCode.DRIVE_FAULT, (0x7500, 0, 0.0)),
                       (AlarmCode.WORKING_COUNTER, (4, 0b10, 6.0)), (AlarmCode.HOMING_ERROR, (1, 0, 0.0))):
        english = alarm_message(config, code, "X", 0, *args)
        assert localize(english) != english, english


def test_the_gathered_catalogue_is_current() -> None:
    """Every message the interpreter raises and the controller refuses, alarms or says with is in
    app/message_text.py (so in the .ts): a new or changed message fails here until
    ``python -m tools.i18n_catalog`` is run and translated."""
    assert len(interpreter_templates()) > 200
    assert len(controller_templates()) > 60
    assert MESSAGE_TEXT.read_text(encoding="utf-8") == current_message_text()


# programs the interpreter refuses, one message family each (values of every kind in them)
BAD_PROGRAMS = (
    "G1 X10",                       # feed rate is zero
    "G99 X1",                       # unknown G code
    "M123",                         # user M-code not defined
    "G0 X1 X2",                     # two X words
    "G2 X10 F100",                  # arc without centre
    "G1 F-5 X1",                    # negative feed
    "G81 X1 Y1 F100",               # canned cycle needs R
    "(unclosed",                    # comment
    "G0 B5",                        # axis not on this machine
    "G10 L7 P1",                    # unknown G10
    "o100 call",                    # no sub
    "G41 D1 G0 X1\nG83 X1 Y1 Z-1 R1 F10",  # canned cycle with cutter comp
    "G0 G1 X1 F1",                  # same modal group
    "M3 M4 S100",                   # same modal group (M)
    "T1.5 M6",                      # tool number
    "G4",                           # dwell needs P
    "G43.2",                        # H or axis words
)


@pytest.mark.parametrize("program", BAD_PROGRAMS)
def test_the_interpreters_errors_are_said_in_turkish(turkish, program: str) -> None:
    """A program's errors as the interpreter writes them, not copies of its templates: each
    is translated, its values kept, and the file:line:col in front stays."""
    with pytest.raises(ProgramError) as caught:
        parse_program(program + "\nM2\n", "bad.ngc")
    english = str(caught.value)
    for line in english.splitlines():
        where, message = line.split(": error: ", 1)
        said_where, said_message = localize(line).split(": hata: ", 1)
        assert said_where == where
        assert said_message != message and said_message == localize(message), message
        for value in re.findall(r"\b[A-Z]\d+(?:\.\d+)?\b", message):
            assert value in said_message, (value, said_message)


def test_the_planner_choices_and_the_plot_are_said_in_turkish(qtbot, fake_window) -> None:
    """The Parameters page's planner modes and interpolations and the speed plot's rapid
    line, switched to Turkish at run time and back."""
    from app.pages.diagnostics import DiagnosticsPage
    from app.pages.parameters import ParametersPage

    window = fake_window
    params = window.findChild(ParametersPage)
    diagnostics = window.findChild(DiagnosticsPage)
    rapid = diagnostics.profile_plots.limit_lines["v"][0].label
    assert params.mode_buttons["lookahead"].text() == "Look-ahead"
    assert rapid.format == "rapid"
    window.context.i18n.set_language("tr")
    try:
        assert params.mode_buttons["lookahead"].text() == "İleriye bakış"
        assert params.interp_buttons["classic"].text() == "Klasik"
        assert rapid.format == "hızlı"
    finally:
        window.context.i18n.set_language("en")
    assert params.interp_buttons["exact"].text() == "Exact"


def test_a_soft_limit_an_e_stop_by_the_operator_and_the_alarm_banner_are_said_in_turkish(
        qtbot, turkish, fake_window, fake_controller) -> None:
    """Sentences the planner and the controller make of parts: a path beyond the travel (read
    from a program), the run log's "E-stop: operator", and the banner's source."""
    from app.machine.model import Alarm, AlarmState, BusStatus, Severity
    from planner.core.machine import MachineSpec
    from planner.pipeline import SoftLimitError, load

    with pytest.raises(SoftLimitError) as caught:
        load("G0 X5000\n", "far.nc", MachineSpec.default(), lambda p: p)
    said = localize(f"soft limit: {str(caught.value.violations[0]).split(': ', 1)[1]}")
    assert "reaches" not in said and "beyond" not in said and "end point" not in said, said
    assert "X ekseni 5000.0000 değerine ulaşıyor (bitiş noktası), yazılım sınırının ötesinde: üst" in said
    assert localize("E-stop: operator") == "Acil stop: operatör"
    fake_window.context.i18n.set_language("tr")
    try:
        fake_controller.alarmsChanged.emit((Alarm(1, 0.0, "operator", "E-stop pressed", Severity.ESTOP,
                                                  AlarmState.ACTIVE, "estop"),))
        banner = fake_window.header.alarm_banner.text()
        assert "operatör" in banner and "operator" not in banner, banner
        bus = fake_window.page("diagnostics").bus
        bus.set_state(BusStatus(kind="sim", state="enabled", connected=True), fake_controller.config)
        assert "(etkin)" in bus.summary.text() and "enabled" not in bus.summary.text(), bus.summary.text()
        plot = bus.histogram.getPlotItem()
        assert [plot.getAxis(side).labelText for side in ("bottom", "left")] == [
            "başlangıç sapması (µs)", "çevrim"]
    finally:
        fake_window.context.i18n.set_language("en")
