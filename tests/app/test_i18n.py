"""English and Turkish: every marked string translated, .ts compiles to .qm, runtime switch."""

from __future__ import annotations

import json
import subprocess
from pathlib import Path

import pytest
from PySide6.QtCore import QTranslator

from app.i18n import TRANSLATIONS, is_stale, lrelease_path
from tools.i18n_catalog import extract_strings, read_ts


def test_every_marked_string_has_a_turkish_translation() -> None:
    strings = extract_strings()
    assert len(strings) > 150
    translations = read_ts(TRANSLATIONS / "cnc_tr.ts")
    missing = sorted(s for s in strings if s not in translations)
    assert not missing, f"untranslated (run python -m tools.i18n_catalog): {missing}"
    # placeholders survive translation
    for source, target in translations.items():
        for k in range(8):
            assert (f"{{{k}" in source) == (f"{{{k}" in target), (source, target)


def test_ts_compiles_to_a_loadable_qm(tmp_path: Path) -> None:
    tool = lrelease_path()
    if tool is None:
        pytest.skip("pyside6-lrelease not installed")
    qm = tmp_path / "cnc_tr.qm"
    subprocess.run([str(tool), "-silent", str(TRANSLATIONS / "cnc_tr.ts"), "-qm", str(qm)], check=True)
    translator = QTranslator()
    assert translator.load(str(qm))
    assert translator.translate("cnc", "Cycle start") == "Çevrim başlat"
    shipped = TRANSLATIONS / "cnc_tr.qm"
    assert shipped.read_bytes() == qm.read_bytes(), "shipped cnc_tr.qm is out of date: run the panel once"
    assert not is_stale(TRANSLATIONS / "cnc_tr.ts")


def test_switch_language_at_run_time(fake_window, state_dir) -> None:
    window = fake_window
    auto = window.page("auto")
    assert window._buttons["auto"].text() == "Auto"
    assert auto.buttons["start"].text() == "Cycle start"
    window.toggle_language()
    assert window.context.i18n.language == "tr"
    assert window._buttons["auto"].text() == "Otomatik"
    assert auto.buttons["start"].text() == "Çevrim başlat"
    assert window.header.state_label.text() == "Hazır"
    assert window.page("diagnostics").tabs.tabText(0) == "Yol v / a / j"
    assert "Satır" in auto.info_label.text()
    assert json.loads((state_dir / "panel.json").read_text())["language"] == "tr"
    window.toggle_language()
    assert window._buttons["auto"].text() == "Auto" and auto.buttons["start"].text() == "Cycle start"
