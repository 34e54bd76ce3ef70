"""Reading is bounded and the answers come fast: a program over the size limit, a device that
goes on, a silent pipe, an endless loop and a program out of scale with its length are each
told at once, with the reason; a pipe that delivers is read."""

from __future__ import annotations

import json
import os
import threading
import time
from pathlib import Path

import pytest

import planner.core.reading as reading
from cli.plan import main as plan_main
from planner.core.errors import PlannerError
from planner.gcode.source import read_program, read_program_bytes

ROOT = Path(__file__).resolve().parents[2]
SHARED = ROOT.parent / "shared" / "gcode" / "linuxcnc-interp" / "good"


def test_a_file_over_the_limit_is_refused_before_it_is_read(tmp_path: Path) -> None:
    big = tmp_path / "big.ngc"
    big.write_bytes(b"G0 X1\n" * 200_000)                       # 1.2 MB
    with pytest.raises(PlannerError, match=r"more than 1 MB, the most a program may have"):
        read_program_bytes(big, limit=1 << 20)
    with pytest.raises(PlannerError, match=r"more than 1 MB"):
        read_program(big, limit=1 << 20)
    assert read_program(big, limit=2 << 20).count("\n") == 200_000


def test_dev_zero_is_binary_data_and_told_at_once() -> None:
    started = time.perf_counter()
    with pytest.raises(PlannerError, match=r"/dev/zero: binary data \(a NUL byte\), not a G-code program"):
        read_program_bytes("/dev/zero")
    assert time.perf_counter() - started < 5.0


def test_a_device_that_goes_on_is_refused_at_the_limit(tmp_path: Path) -> None:
    fifo = tmp_path / "endless"
    os.mkfifo(fifo)
    stop = threading.Event()

    def writer() -> None:
        try:
            with open(fifo, "wb") as f:
                while not stop.is_set():
                    f.write(b"G0 X1\n" * 10_000)
        except BrokenPipeError:       # the reader gave up: what is tested
            pass

    thread = threading.Thread(target=writer, daemon=True)
    thread.start()
    try:
        with pytest.raises(PlannerError, match=r"more than 2 MB"):
            read_program_bytes(fifo, limit=2 << 20)
    finally:
        stop.set()
        thread.join(10)


def test_a_silent_pipe_is_given_up_and_a_pipe_that_delivers_is_read(tmp_path: Path,
                                                                     monkeypatch: pytest.MonkeyPatch) -> None:
    fifo = tmp_path / "p.fifo"
    os.mkfifo(fifo)
    monkeypatch.setattr(reading, "SILENT_PIPE_S", 0.5)
    started = time.perf_counter()
    with pytest.raises(PlannerError, match=r"nothing came for 0.5 s \(a pipe with no writer\?\)"):
        read_program(fifo)
    assert time.perf_counter() - started < 5.0

    def writer() -> None:
        time.sleep(0.1)
        with open(fifo, "wb") as f:
            f.write(b"G0 X1\r\nM30\r\n")

    thread = threading.Thread(target=writer)
    thread.start()
    assert read_program(fifo) == "G0 X1\nM30\n"
    thread.join(10)


def test_a_folder_is_no_program(tmp_path: Path) -> None:
    with pytest.raises(PlannerError, match=r"is a folder, not a program"):
        read_program_bytes(tmp_path)


@pytest.mark.parametrize("text", ["o101 while [1]\no101 endwhile\nM30\n",
                                  "#1=0\no1 do\n#1=[#1+1]\no1 while [#1 gt -1]\nM30\n"])
def test_an_endless_loop_is_stopped_in_seconds(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                               text: str) -> None:
    program = tmp_path / "loop.ngc"
    program.write_text(text)
    started = time.process_time()
    assert plan_main([str(program), "--json"]) == 2
    spent = time.process_time() - started
    assert "524,288 blocks run without a move (an endless loop?)" in capsys.readouterr().err
    # the budget is a count of blocks: 10,000,000 of them, the other bound, took 39 s of the
    # processor; counted in this process's processor time, which other processes do not stretch
    assert spent < 30.0


def test_a_loop_that_moves_runs_to_its_end(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    program = tmp_path / "moves.ngc"
    program.write_text("#1=0\no1 while [#1 lt 2000]\nG1 X[1 + [#1 mod 2]] F6000\n#1=[#1+1]\n"
                       "o1 endwhile\nM30\n")
    assert plan_main([str(program), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["moves"] == 2000


@pytest.mark.skipif(not SHARED.is_dir(), reason="needs ../shared/gcode (LinuxCNC's test programs)")
def test_one_arc_of_fifteen_hours_is_told_its_cycle_time_at_once(capsys: pytest.CaptureFixture[str]) -> None:
    program = SHARED / "good-arc.big.imperial.center-format.ngc"
    started = time.perf_counter()
    assert plan_main([str(program), "--json"]) == 0
    assert time.perf_counter() - started < 20.0            # interpolating it took 64 s
    out = json.loads(capsys.readouterr().out)
    assert out["sampled"] is False and out["moves"] == 1
    assert out["cycle_time_s"] == pytest.approx(56_548.7, rel=1e-3)
    assert "--interpolate-long" in out["note"]


def test_a_long_move_is_sampled_when_asked(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    program = tmp_path / "slow.ngc"
    program.write_text("G1 X100 F1\nM30\n")                 # 100 min for one move
    assert plan_main([str(program), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["sampled"] is False
    assert plan_main([str(program), "--json", "--interpolate-long", "--ts", "0.05"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["ok"] is True and "sampled" not in out and out["cycle_time_s"] == pytest.approx(6000.0,
                                                                                               rel=1e-2)


def _deep_toml(path: Path) -> Path:
    path.write_text("a = " + "[" * 500 + "]" * 500 + "\n")
    return path


def _huge(path: Path) -> Path:
    with path.open("wb") as f:                     # a sparse file: 17 MB that take no disk
        f.truncate(17 << 20)
    return path


@pytest.mark.parametrize("option", ["--config", "--tools"])
@pytest.mark.parametrize("make", ["zero", "huge", "nul", "deep"])
def test_cnc_plan_reads_every_file_it_is_given_within_bounds(
        tmp_path: Path, capsys: pytest.CaptureFixture[str], option: str, make: str) -> None:
    program = tmp_path / "p.ngc"
    program.write_text("G21\nG1 X1 F100\nM2\n")
    named = {"zero": lambda: Path("/dev/zero"), "huge": lambda: _huge(tmp_path / "huge.txt"),
             "nul": lambda: _write(tmp_path / "nul.txt", b"[machine]\nname = \"a\"\n\0\n"),
             "deep": lambda: _deep_toml(tmp_path / "deep.toml")}[make]()
    started = time.perf_counter()
    assert plan_main([str(program), option, str(named)]) == 2
    assert time.perf_counter() - started < 30
    err = capsys.readouterr().err
    what = "a machine configuration" if option == "--config" else "a tool table"
    expected = {"zero": f"{named}: binary data (a NUL byte), not {what}",
                "huge": f"{named}: more than 16 MB, the most {what} may have",
                "nul": f"{named}:3: binary data (a NUL byte), not {what}",
                "deep": "nested too deeply to read" if option == "--config" else "deep.toml:1:"}[make]
    assert expected in err and "Traceback" not in err, err


def _write(path: Path, data: bytes) -> Path:
    path.write_bytes(data)
    return path


def test_a_fifo_with_no_writer_as_a_configuration_is_given_up(
        tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(reading, "SILENT_PIPE_S", 0.5)
    fifo = tmp_path / "machine.toml"
    os.mkfifo(fifo)
    program = tmp_path / "p.ngc"
    program.write_text("G21\nG1 X1 F100\nM2\n")
    assert plan_main([str(program), "--config", str(fifo)]) == 2
    assert "nothing came for 0.5 s (a pipe with no writer?)" in capsys.readouterr().err


@pytest.mark.parametrize("make", ["zero", "huge", "deep"])
def test_cnc_run_reads_its_configuration_and_script_within_bounds(qapp: object, tmp_path: Path, make: str,
                                                                  capsys: pytest.CaptureFixture[str]) -> None:
    from app.run_cli import main as run_main

    program = tmp_path / "p.ngc"
    program.write_text("G21\nG1 X1 F100\nM2\n")
    named = {"zero": lambda: Path("/dev/zero"), "huge": lambda: _huge(tmp_path / "huge.txt"),
             "deep": lambda: _deep_toml(tmp_path / "deep.toml")}[make]()
    assert run_main([str(program), "--sim", "--worker", "manual", "--config", str(named)]) == 2
    err = capsys.readouterr().err
    assert str(named) in err and "Traceback" not in err
    if make != "deep":                            # a script is JSON lines: its depth is its own
        assert run_main([str(program), "--sim", "--worker", "manual", "--script", str(named)]) == 2
        err = capsys.readouterr().err
        assert "a script of operator actions" in err and "Traceback" not in err


def test_a_script_number_too_large_for_a_float_is_refused_at_its_line(
        qapp: object, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from app.run_cli import main as run_main

    program = tmp_path / "p.ngc"
    program.write_text("G21\nG1 X1 F100\nM2\n")
    script = tmp_path / "ops.jsonl"
    script.write_text('{"after_s": 0.1, "op": "feed_hold"}\n{"at_line": 1' + "0" * 400 + ', "op": "stop"}\n')
    assert run_main([str(program), "--sim", "--worker", "manual", "--script", str(script)]) == 2
    err = capsys.readouterr().err
    assert f"{script}:2: at_line must be a whole number of at most 1e12, got 100000000000... (401 digits)" \
        in err


def test_a_long_comment_line_is_read_without_its_bytes_in_the_bulk_arrays() -> None:
    """A comment of 3,000,000 characters: its bytes left out of the bulk reader's per-byte and
    per-word arrays (each x was a word: 160 bytes of arrays per byte of the program)."""
    import tracemalloc

    from planner.gcode.interpreter import parse_program

    text = "G21 G90\n(" + "x" * 3_000_000 + ")\nG1 X1 F100\nM2\n"
    tracemalloc.start()
    try:
        program = parse_program(text)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert len(program.moves) == 1
    assert peak < 40 * len(text), peak / len(text)          # was 160 bytes a byte


def test_a_block_of_more_code_than_a_block_may_have_is_refused_at_once() -> None:
    from planner.core.errors import ProgramError
    from planner.gcode.interpreter import parse_program

    with pytest.raises(ProgramError) as info:
        parse_program("G21 G90 F100 G1 " + " ".join(f"X{i}" for i in range(500_000)) + "\nM2\n")
    assert "characters of code in one block (comments aside): more than 4,096" in info.value.errors[0].message
