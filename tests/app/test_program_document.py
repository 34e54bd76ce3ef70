"""Program files: atomic save, modified flag, autosave and recovery after a crash."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from app.program_document import ProgramDocument
from planner.core.files import write_text


def test_save_is_atomic_and_clears_modified(tmp_path: Path) -> None:
    doc = ProgramDocument(tmp_path / "state")
    target = tmp_path / "p.nc"
    target.write_text("G00 X0\n")
    doc.open(target)
    doc.text = "G00 X1\n"
    assert doc.modified
    doc.save()
    assert target.read_text() == "G00 X1\n" and not doc.modified
    assert [p.name for p in tmp_path.iterdir() if p.name.endswith(".tmp")] == []


def test_failed_write_keeps_the_old_file(tmp_path: Path, monkeypatch) -> None:
    target = tmp_path / "p.nc"
    target.write_text("old\n")

    def boom(src, dst):
        raise OSError("disk full")

    monkeypatch.setattr(os, "replace", boom)
    with pytest.raises(OSError):
        write_text(target, "new\n")
    assert target.read_text() == "old\n"
    assert not [p for p in tmp_path.iterdir() if p.name.endswith(".tmp")]


def test_autosave_and_recovery(tmp_path: Path) -> None:
    target = tmp_path / "p.nc"
    target.write_text("G00 X0\n")
    doc = ProgramDocument(tmp_path / "state")
    doc.open(target)
    assert doc.autosave() is None  # nothing to save
    doc.text = "G00 X0\nG01 X5 F100\n"
    saved = doc.autosave()
    assert saved is not None and saved.exists()
    # "crash": a new session opens the same file and is offered the autosave
    again = ProgramDocument(tmp_path / "state")
    assert again.recovery_text(target) == "G00 X0\nG01 X5 F100\n"
    again.open(target)
    again.discard_autosave()
    assert again.recovery_text(target) is None
