"""Open and Save as reach only the program folders: never the state files (homed flags,
positions, the service password), never the machine configuration, never the rest of the
file system; a typed name is a plain G-code file name."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from app.program_folders import ProgramFolders
from resources import PROGRAMS


@pytest.fixture
def folders(tmp_path: Path) -> ProgramFolders:
    return ProgramFolders(tmp_path / "state", extra=[tmp_path / "shop"], media=[])


@pytest.mark.parametrize("name, why", [
    ("../machine.toml", "without a folder"),
    ("../state.json", "without a folder"),
    ("/etc/passwd", "without a folder"),
    ("sub\\\\x.nc", "without a folder"),
    ("panel.json", "programs end in"),
    ("machine.toml", "programs end in"),
    ("a\0b.nc", "NUL"),
    (".hidden.nc", "cannot start with a dot"),
    ("..", "without a folder"),
    ("   ", "no file name"),
])
def test_save_as_refuses_names_that_leave_the_folder_or_are_not_programs(folders: ProgramFolders,
                                                                         name: str, why: str) -> None:
    result = folders.resolve_save(folders.default, name)
    assert isinstance(result, str) and why in result


def test_save_as_adds_nc_and_stays_in_writable_program_folders(folders: ProgramFolders,
                                                               tmp_path: Path) -> None:
    assert folders.resolve_save(folders.default, "part") == folders.default / "part.nc"
    assert folders.resolve_save(tmp_path / "shop", "P1.ngc") == (tmp_path / "shop" / "P1.ngc")
    assert "read only" in folders.resolve_save(PROGRAMS, "x.nc")
    assert "outside the program folders" in folders.resolve_save(tmp_path / "state", "x.nc")
    assert "outside the program folders" in folders.resolve_save(Path("/tmp"), "x.nc")


def test_a_link_out_of_a_program_folder_is_outside(folders: ProgramFolders, tmp_path: Path) -> None:
    (folders.default / "escape").symlink_to(tmp_path / "state")
    assert "outside the program folders" in folders.resolve_save(folders.default / "escape", "x.nc")
    (tmp_path / "state" / "state.nc").write_text("G0 X0\n")
    assert "outside" in folders.check_open(folders.default / "escape" / "state.nc")


def test_open_is_confined_too(folders: ProgramFolders, tmp_path: Path) -> None:
    assert folders.check_open(PROGRAMS / "pocket.nc") == ""
    assert "outside the program folders" in folders.check_open(tmp_path / "state" / "panel.json")
    assert "outside the program folders" in folders.check_open("/etc/passwd")
    assert "not a G-code program" in folders.check_open(folders.default / "notes.pdf")


def test_the_program_page_save_as_cannot_reach_the_state_files(fake_window, dialogs, tmp_path: Path) -> None:
    page = fake_window.page("program")
    state = fake_window.context.state_dir
    page.set_text("G0 X0\n")
    before = {p.name: p.read_bytes() for p in state.iterdir() if p.is_file()}
    for name in ("../panel.json", "../state.json", "machine.toml", "/tmp/x.nc", "a\0b"):
        dialogs.answers.append(name)
        assert not page.save_as()
        assert dialogs.asked[-1][0] == "inform"
    after = {p.name: p.read_bytes() for p in state.iterdir() if p.is_file()}
    assert after == before
    dialogs.answers.append("part")
    assert page.save_as()
    assert (state / "programs" / "part.nc").read_text() == "G0 X0\n"


def test_the_file_picker_stays_in_the_program_folders(qtbot, folders: ProgramFolders, tmp_path: Path) -> None:
    from app.widgets.file_picker import FilePicker

    (folders.default / "sub").mkdir()
    picker = FilePicker("Open", folders.default / "sub", folders=folders)
    qtbot.addWidget(picker)
    picker.go_up()
    assert picker.directory == folders.default
    picker.go_up()                                     # the top of a program folder: no further
    assert picker.directory == folders.default and not picker.up_button.isEnabled()
    assert str(PROGRAMS.resolve()) + "/" in picker.entries()     # the other folders are offered
    outside = FilePicker("Open", Path(os.sep), folders=folders)
    qtbot.addWidget(outside)
    assert outside.directory == folders.default
