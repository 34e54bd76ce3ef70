"""The controller's sentences shown in Turkish: every template translated with its values in
place, real sentences from the controller and the worker matched, English left as it is."""

from __future__ import annotations

import re

import pytest

from app.controller_text import TEMPLATES, localize
from app.i18n import tr


@pytest.fixture
def turkish(qapp):
    """The Turkish translator installed (the panel's own I18n), English again afterwards."""
    from app.i18n import I18n

    i18n = I18n()
    i18n.set_language("tr")
    yield i18n
    i18n.set_language("en")


def _sample(template: str) -> tuple[str, list[str]]:
    n = len(set(re.findall(r"\{(\d)\}", template)))
    values = [f"V{k}x" for k in range(n)]
    return template.format(*values), values


@pytest.mark.parametrize("template", TEMPLATES)
def test_every_template_is_translated_with_its_values(turkish, template: str) -> None:
    english, values = _sample(template)
    turkish_text = localize(english)
    assert turkish_text == tr(template).format(*values)
    assert turkish_text != english or template in ("alarm",)   # "alarm" is the same word
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
