"""Loading a program from the panel: checked in the controller's worker thread while the panel
shows it (Auto page note, status bar) and stays responsive; big programs reach the pages in
pieces (editor text in chunks, one page per event-loop turn)."""

from __future__ import annotations

from pathlib import Path

from tests.machine.test_program_load import big_program

SHORT = "G21 G90 G17\nG00 X1 Y1\nG01 X5 Y2 F1200\nG02 X7 Y4 R2\nM30\n"


def test_auto_page_and_status_bar_show_the_check(demo_window, real_controller, qtbot) -> None:
    c = real_controller
    auto = demo_window.page("auto")
    program = demo_window.page("program")
    program.set_text(SHORT)
    name = program.doc.name
    with qtbot.waitSignal(c.programLoaded, timeout=20_000):
        program.load_into_machine()
        assert c.loading
        assert auto.loading_note.isVisible() and name in auto.loading_note.text()
        assert auto.loading_bar.isVisible()
        assert not auto.buttons["start"].isEnabled()  # cycle start refused while checking
        assert "checking" in demo_window._program_label.text()
        assert name in demo_window._message.text()
    assert not auto.loading_note.isVisible() and not auto.loading_bar.isVisible()
    assert demo_window._program_label.text() == name
    assert auto.buttons["start"].isEnabled() and auto.program_label.text() == name


def test_big_program_reaches_every_page(demo_window, real_controller, qtbot) -> None:
    c = real_controller
    text = big_program(7000)
    with qtbot.waitSignal(c.programLoaded, timeout=60_000):
        assert c.load_program(text, name="big.nc")
    auto = demo_window.page("auto")
    program = demo_window.page("program")
    preview = demo_window.page("preview")
    qtbot.waitUntil(lambda: not auto.editor.loading and not program.editor.loading
                    and demo_window.context.program.info is c.program_info, timeout=20_000)
    assert auto.editor.toPlainText() == text and program.editor.toPlainText() == text
    assert program.doc.text == text and not program._autosave.isActive()  # pieces are no edits
    assert not program.editor.isReadOnly() and auto.editor.isReadOnly()
    assert not program.editor.errors
    assert preview.plot.path.all.count == c.program_info.move_count
    program.editor.undo()  # the chunks are not undo steps: the text stays
    assert program.editor.toPlainText() == text


def test_editor_chunked_load_is_superseded_by_a_newer_text(qapp, qtbot) -> None:
    from app.widgets.code_editor import CodeEditor

    editor = CodeEditor()
    qtbot.addWidget(editor)
    editor.load_text(big_program(7000), chunked=True)
    assert editor.loading and editor.isReadOnly()
    editor.load_text("G0 X1\n", chunked=True)  # small: at once, the big one is dropped
    assert not editor.loading and not editor.isReadOnly()
    qtbot.wait(100)
    assert editor.toPlainText() == "G0 X1\n"


def test_the_status_bar_says_when_corners_are_smoothed(demo_window, real_controller, qtbot) -> None:
    """Under G64 P the path is not exactly the programmed one: the operator reads how many
    corners were smoothed and by how much at most, when the program is loaded."""
    c = real_controller
    rise = 10.0 * 0.04366
    text = "G21 G90 G64 P0.02\nG0 X5 Y0\nG1 F1800\n" + "".join(
        f"X{5 + 10 * i} Y{rise * (i % 2):.4f}\n" for i in range(1, 8)) + "M30\n"
    with qtbot.waitSignal(c.programLoaded, timeout=20_000):
        assert c.load_program(text, name="zig.nc")
    info = c.program_info
    assert info.blends >= 5 and 0.0 < info.path_deviation_mm <= 0.02
    message = demo_window._message.text()
    assert "zig.nc" in message and f"{info.blends} corners smoothed" in message
    assert f"{info.path_deviation_mm:.3f} mm" in message
    with qtbot.waitSignal(c.programLoaded, timeout=20_000):
        assert c.load_program(text.replace("G64 P0.02", "G61.1"), name="sharp.nc")
    assert c.program_info.blends == 0 and "smoothed" not in demo_window._message.text()


def test_a_program_over_the_edit_limit_is_shown_read_only_through_a_view(
        demo_window, real_controller, qtbot, monkeypatch, tmp_path) -> None:
    """Over EDIT_MAX_LINES a program goes into no text widget: both pages show it through the
    loader's own text and line index, the Program page says why it cannot be edited there, the
    controller's errors are marked on it, and a small program is editable again."""
    import app.pages.program as program_page

    monkeypatch.setattr(program_page, "EDIT_MAX_LINES", 500)
    c = real_controller
    path = tmp_path / "big.nc"
    path.write_text(big_program(700), encoding="utf-8")
    program = demo_window.page("program")
    auto = demo_window.page("auto")
    with qtbot.waitSignal(c.programLoaded, timeout=60_000):
        assert c.load_program(path)
    qtbot.waitUntil(lambda: program.doc.path is not None and auto.editor.toPlainText() != "", timeout=20_000)
    info = c.program_info
    assert program.read_only and program.shown is program.viewer
    assert program.viewer.toPlainText() is info.text and auto.editor.toPlainText() is info.text
    assert program.doc.text is info.text and not program.doc.modified  # the file is not read again
    assert program.editor.toPlainText() == ""
    assert program.read_only_note.isVisibleTo(program) and "500" in program.read_only_note.text()
    assert not program.buttons["keyboard"].isEnabled()
    demo_window.context.program.lineRequested.emit(600)
    assert program.viewer.current_line() == 600
    program._on_program_errors([type("Issue", (), {"line": 640, "col": 0, "message": "radius"})()])
    assert program.viewer.errors == {640: "radius"} and not program.editor.errors
    program.set_text(SHORT)
    assert not program.read_only and program.editor.toPlainText() == SHORT
    assert not program.read_only_note.isVisibleTo(program) and program.buttons["keyboard"].isEnabled()


def test_a_big_file_opened_on_the_program_page_is_read_once_by_the_controller(
        demo_window, real_controller, qtbot, monkeypatch, dialogs) -> None:
    """Open on a big file: the page does not read it; the controller's worker does, and the
    page shows the text it read; the program shown before leaves the page at once. Refused,
    the file is shown with its errors on its lines."""
    import app.pages.program as program_page
    from app.program_document import ProgramDocument

    monkeypatch.setattr(program_page, "BIG_FILE_BYTES", 1000)
    monkeypatch.setattr(program_page, "EDIT_MAX_LINES", 500)
    reads: list[str] = []
    real_open = ProgramDocument.open

    def open_(self, path, text=None):
        if text is None:
            reads.append(str(path))
        return real_open(self, path, text)

    monkeypatch.setattr(ProgramDocument, "open", open_)
    c = real_controller
    program = demo_window.page("program")
    folder = Path(demo_window.context.folders.default)
    good = folder / "big.nc"
    good.write_text(big_program(700), encoding="utf-8")
    dialogs.answers.append(str(good))
    with qtbot.waitSignal(c.programLoaded, timeout=60_000):
        program.buttons["open"].click()
        assert c.loading and reads == []
    qtbot.waitUntil(lambda: program.doc.path is not None and program.doc.path.name == "big.nc",
                    timeout=20_000)
    assert reads == [] and program.viewer.toPlainText() is c.program_info.text
    bad = folder / "bad.nc"
    bad.write_text(big_program(700).replace("G1 Z0 F600", "G1 Z0 F600\nG2 X1 Y1 I0 J0 Q5"), encoding="utf-8")
    dialogs.answers.append(str(bad))
    with qtbot.waitSignal(c.programErrors, timeout=60_000):
        program.buttons["open"].click()
        # big.nc has left the page as bad.nc is read (never two big texts held at once)
        assert c.loading and program.doc.path is None and program.doc.text == ""
        assert program.viewer.toPlainText() == "" and program.editor.toPlainText() == ""
    assert reads == [str(bad)]  # read by the page only to show the refused file
    assert program.doc.path.name == "bad.nc" and "Q5" in program.viewer.line(4)
    assert 4 in program.viewer.errors
    assert demo_window.context.program.text == program.doc.text  # the Auto page shows it too


def test_a_big_program_shown_goes_as_soon_as_another_is_checked(demo_window, real_controller, qtbot,
                                                                   monkeypatch) -> None:
    """Two big programs are never held at once: when a load starts, the big program shown
    leaves every page and the preview's thinned copies at that moment, not at the outcome (a
    10,000,000-line program checked again after a touch-off took the panel to 1.4 GB). Checked
    again, its text stays on screen; a program the panel opens, even the same one, takes the
    text too. Another program takes a small one off the screen too (nothing of it is shown as the
    new one's); a small one checked again stays on screen until the outcome."""
    import gc
    import weakref
    from dataclasses import replace

    import app.path_lod as path_lod
    import app.program_model as program_model

    c = real_controller
    model = demo_window.context.program
    auto, preview = demo_window.page("auto"), demo_window.page("preview")
    monkeypatch.setattr(program_model, "LET_GO_MOVES", 5000)    # "big", scaled down
    monkeypatch.setattr(path_lod, "LOD_MIN_POINTS", 1000)       # thinned copies made
    text = big_program(7000)

    def shown_whole() -> None:
        # the detail drawn for the view is made off the GUI thread from the path: a job still
        # running holds it until it ends (then lets it go), so the test starts from rest
        qtbot.waitUntil(lambda: model.info is c.program_info and not preview.plot.detail_pending
                        and not auto.backplot.detail_pending and not auto.editor.loading, timeout=20_000)
        assert model.toolpath.move_count >= 5000 and path_lod._made is not None

    def held() -> list[weakref.ref]:
        """The tool path's own array, a thinned copy's and the program (slotted objects have no
        weak references)."""
        levels = path_lod._made[2][0]
        copy = next(copies for copies in levels.values() if copies)[0][1].points
        program = c.program_info.program
        return [weakref.ref(model.toolpath.point_kind), weakref.ref(copy), weakref.ref(program)]

    with qtbot.waitSignal(c.programLoaded, timeout=60_000):
        assert c.load_program(text, name="big.nc")
    shown_whole()
    refs = held()
    cfg = c.config
    slower = replace(cfg, machine=cfg.machine.with_limits(a_max_mm_s2=cfg.machine.limits.a_max_mm_s2 * 0.8))
    gc.disable()            # no collection may be what frees them
    try:
        with qtbot.waitSignal(c.programLoaded, timeout=20_000):
            assert c.update_config(slower)          # checked again: the same program
            assert c.loading
            assert model.info is None and model.toolpath is None
            assert preview.plot.path is None and auto.backplot.path is None
            assert path_lod._made is None
            assert [ref() for ref in refs] == [None, None, None]
            assert model.text is text and auto.editor.toPlainText() is text
    finally:
        gc.enable()
    shown_whole()
    with qtbot.waitSignal(c.programLoaded, timeout=60_000):
        model.expect("", "big.nc")       # the panel opens it again, as the Program page does
        assert c.load_program(text, name="big.nc")
        assert model.info is None and model.text == "" and auto.editor.toPlainText() == ""
    shown_whole()
    with qtbot.waitSignal(c.programLoaded, timeout=20_000):
        assert c.load_program(SHORT, name="next.nc")    # another program: the text goes too
        assert model.info is None and model.text == "" and auto.editor.toPlainText() == ""
    qtbot.waitUntil(lambda: model.info is c.program_info, timeout=20_000)
    small = model.toolpath
    assert small is not None and small.move_count < 5000
    with qtbot.waitSignal(c.programLoaded, timeout=20_000):
        assert c.update_config(cfg)                     # the same small program checked again
        assert c.loading and model.toolpath is small and preview.plot.path is small
    qtbot.waitUntil(lambda: model.info is c.program_info, timeout=20_000)
    with qtbot.waitSignal(c.programLoaded, timeout=20_000):
        assert c.load_program(SHORT, name="again.nc")   # another program, small: it goes too
        assert c.loading and model.toolpath is None and preview.plot.path is None
        assert model.name == "again.nc" and auto.editor.toPlainText() == ""


def test_a_configuration_change_leaves_a_big_program_to_the_controller_s_check(
        demo_window, real_controller, qtbot, monkeypatch) -> None:
    """After a configuration change the controller checks the loaded program again; a big
    one shown read-only is not read a second time by the Program page (a 10,000,000-line
    program was read twice at once). An editable one is checked there as it is typed."""
    from dataclasses import replace

    import app.pages.program as program_page
    import app.program_checker as checker

    monkeypatch.setattr(program_page, "EDIT_MAX_LINES", 500)
    read: list[int] = []
    real = checker.interpret

    def counting(text, name, machine):  # noqa: ANN001
        read.append(text.count("\n"))
        return real(text, name, machine)

    monkeypatch.setattr(checker, "interpret", counting)
    c = real_controller
    program = demo_window.page("program")

    def change_config() -> None:
        cfg = c.config
        limits = cfg.machine.limits
        slower = replace(cfg, machine=cfg.machine.with_limits(a_max_mm_s2=limits.a_max_mm_s2 * 0.9))
        with qtbot.waitSignal(c.programLoaded, timeout=60_000):
            assert c.update_config(slower)
        qtbot.wait(600)                     # past the checker's delay
        qtbot.waitUntil(lambda: not program.checker.busy, timeout=20_000)

    with qtbot.waitSignal(c.programLoaded, timeout=60_000):
        assert c.load_program(big_program(700), name="big.nc")
    qtbot.waitUntil(lambda: program.read_only and program.doc.text == c.program_info.text, timeout=20_000)
    read.clear()
    change_config()
    assert read == []
    program.set_text(SHORT)
    program.load_into_machine()
    qtbot.waitUntil(lambda: c.program_info is not None and c.program_info.text == SHORT, timeout=20_000)
    qtbot.waitUntil(lambda: not program.checker.busy, timeout=20_000)
    read.clear()
    change_config()
    assert read == [SHORT.count("\n")]


def test_a_big_program_shown_read_only_stays_the_page_s_document(demo_window, real_controller, qtbot,
                                                                 monkeypatch) -> None:
    """The Program page shows a big program read-only; its hidden editor, emptied, still says
    its text changed a turn later (its highlighter redoes the empty text). That is no edit:
    the document stays the program, unmodified, with nothing autosaved (an empty program was
    once taken for the operator's edit, autosaved, and written over the file on Save)."""
    import app.pages.program as program_page

    monkeypatch.setattr(program_page, "EDIT_MAX_LINES", 500)
    c = real_controller
    program = demo_window.page("program")
    path = Path(demo_window.context.folders.default) / "big.nc"
    path.write_text(big_program(700), encoding="utf-8")
    with qtbot.waitSignal(c.programLoaded, timeout=60_000):
        assert c.load_program(path)
    qtbot.waitUntil(lambda: program.read_only and program.doc.path == path.resolve(), timeout=20_000)
    assert program.doc.text == c.program_info.text and not program.doc.modified
    qtbot.wait(300)         # the turns in which the editor spoke
    assert program.doc.text == c.program_info.text and not program.doc.modified
    assert not program._autosave.isActive()
