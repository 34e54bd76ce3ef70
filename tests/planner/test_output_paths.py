"""An output never destroys an input: ``cnc-plan`` and ``cnc-run`` refuse, before anything is
read or written, an output path that names the program, the configuration, the tool table, a
subroutine, a script or another output (through links, by inode), an empty path, or a file in a
missing folder; the program is left byte for byte."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from cli.plan import main as plan_main

PROGRAM = "G21 G90\nG0 X1 Y1\nG1 X5 F600\nM30\n"


@pytest.fixture
def files(tmp_path: Path) -> dict[str, Path]:
    program = tmp_path / "P.ngc"
    program.write_text(PROGRAM)
    tools = tmp_path / "tools.tbl"
    tools.write_text("T1 P1 Z10 D6\n")
    link = tmp_path / "link.ngc"
    link.symlink_to(program)
    hard = tmp_path / "hard.ngc"
    os.link(program, hard)
    return {"program": program, "tools": tools, "link": link, "hard": hard}


@pytest.mark.parametrize("option", ["--canon", "--samples", "--csv", "--plot"])
@pytest.mark.parametrize("name", ["program", "link", "hard", "tools"])
def test_cnc_plan_refuses_an_output_that_is_an_input(files: dict[str, Path], option: str, name: str,
                                                     capsys: pytest.CaptureFixture[str]) -> None:
    before = {k: p.read_bytes() for k, p in files.items()}
    code = plan_main([str(files["program"]), "--tools", str(files["tools"]), option, str(files[name])])
    assert code == 2
    err = capsys.readouterr().err
    what = "--tools" if name == "tools" else "the program"
    assert f"{option} {files[name]}: the same file as {what} (an input)" in err
    assert {k: p.read_bytes() for k, p in files.items()} == before


def test_cnc_plan_refuses_two_outputs_in_one_file_an_empty_path_and_a_missing_folder(
        files: dict[str, Path], tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "out.bin"
    assert plan_main([str(files["program"]), "--canon", str(out), "--samples", str(out)]) == 2
    assert f"--canon {out}: the same file as --samples (another output)" in capsys.readouterr().err
    assert not out.exists()
    assert plan_main([str(files["program"]), "--canon", ""]) == 2
    assert "--canon: an empty path" in capsys.readouterr().err
    missing = tmp_path / "no" / "such" / "x.jsonl"
    assert plan_main([str(files["program"]), "--canon", str(missing)]) == 2
    assert f"the folder {missing.parent} does not exist (--mkdir creates it)" in capsys.readouterr().err
    assert not missing.parent.exists()
    assert plan_main([str(files["program"]), "--canon", str(missing), "--mkdir"]) == 0
    assert missing.read_text().strip()
    assert plan_main([str(files["program"]), "--samples", "-", "--json"]) == 2
    assert "standard output is already --samples's" in capsys.readouterr().err


def test_cnc_plan_refuses_to_write_over_a_subroutine(tmp_path: Path,
                                                     capsys: pytest.CaptureFixture[str]) -> None:
    from app.machine.config import MachineConfig, config_to_toml

    subs = tmp_path / "subs"
    subs.mkdir()
    sub = subs / "drill.ngc"
    sub.write_text("o<drill> sub\nG0 X0\no<drill> endsub\n")
    text = config_to_toml(MachineConfig.default()).replace(
        'blend_tolerance_mm', f'subroutine_dirs = ["{subs}"]\nblend_tolerance_mm', 1)
    config = tmp_path / "machine.toml"
    config.write_text(text)
    program = tmp_path / "P.ngc"
    program.write_text("o<drill> call\nM30\n")
    assert plan_main([str(program), "--config", str(config), "--canon", str(sub)]) == 2
    assert "a file in the subroutine folder" in capsys.readouterr().err
    assert sub.read_text().startswith("o<drill> sub")


def test_cnc_run_refuses_a_trace_over_its_program_or_its_script(qapp: object, files: dict[str, Path],
                                                                tmp_path: Path,
                                                                capsys: pytest.CaptureFixture[str]) -> None:
    from app.run_cli import main as run_main

    script = tmp_path / "ops.jsonl"
    script.write_text('{"at": 0.1, "op": "feed_hold"}\n')
    cases = ((files["program"], "the program"), (files["link"], "the program"), (script, "--script"))
    for target, what in cases:
        before = target.read_bytes()
        code = run_main([str(files["program"]), "--sim", "--worker", "manual", "--script", str(script),
                         "--trace", str(target), "--json"])
        assert code == 2
        assert f"the same file as {what} (an input)" in capsys.readouterr().err
        assert target.read_bytes() == before


def _subroutine_machine(tmp_path: Path, relative: bool) -> tuple[Path, Path, Path]:
    """A configuration whose subroutine folder is named relative to it (or absolute), its
    subroutine, and a program that calls it."""
    from app.machine.config import MachineConfig, config_to_toml

    subs = tmp_path / "subs"
    subs.mkdir()
    sub = subs / "sub1.ngc"
    sub.write_text("o<sub1> sub\nG0 X0\no<sub1> endsub\n")
    name = "subs" if relative else str(subs)
    text = config_to_toml(MachineConfig.default()).replace(
        'blend_tolerance_mm', f'subroutine_dirs = ["{name}"]\nblend_tolerance_mm', 1)
    config = tmp_path / "machine.toml"
    config.write_text(text)
    program = tmp_path / "prog.ngc"
    program.write_text("o<sub1> call\nM30\n")
    return config, program, sub


def test_a_subroutine_folder_named_relative_to_the_configuration_is_kept_from_any_folder(
        tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch) -> None:
    config, program, sub = _subroutine_machine(tmp_path, relative=True)
    before = sub.read_bytes()
    monkeypatch.chdir("/")                                  # run from elsewhere than the configuration
    assert plan_main([str(program), "--config", str(config), "--csv", str(sub)]) == 2
    assert "a file in the subroutine folder" in capsys.readouterr().err
    assert sub.read_bytes() == before


def test_cnc_run_keeps_its_trace_out_of_the_subroutine_folders_through_a_link_too(
        qapp: object, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from app.run_cli import main as run_main

    config, program, sub = _subroutine_machine(tmp_path, relative=True)
    before = sub.read_bytes()
    link = tmp_path / "trace.npz"
    link.symlink_to(sub)
    for target in (sub, link):
        code = run_main([str(program), "--config", str(config), "--sim", "--worker", "manual",
                         "--trace", str(target), "--json"])
        assert code == 2
        assert "a file in the subroutine folder" in capsys.readouterr().err
        assert sub.read_bytes() == before


def test_a_shipped_subroutine_is_found_by_cnc_plan_as_by_cnc_run(tmp_path: Path,
                                                                 capsys: pytest.CaptureFixture[str]) -> None:
    from app.machine.config import MachineConfig, config_to_toml

    config = tmp_path / "machine.toml"
    config.write_text(config_to_toml(MachineConfig.default()))
    program = tmp_path / "probe.ngc"
    program.write_text("G21 G90\nG0 Z10\no<probe_move> call [2] [-5] [100]\nM30\n")
    for args in ([str(program), "--config", str(config), "--canon", "-"], [str(program), "--canon", "-"]):
        code = plan_main(args)
        captured = capsys.readouterr()
        assert code == 0, captured.err
        assert "\"straight_probe\"" in captured.out


def test_standard_output_named_by_its_path_is_one_output_too(
        files: dict[str, Path], tmp_path: Path) -> None:
    """``--json`` with ``--csv /dev/stdout`` while standard output is redirected to a file: the
    report would be lost in the CSV. Run as a user runs it, with the shell's redirection."""
    import subprocess
    import sys

    out = tmp_path / "report.txt"
    for name in ("/dev/stdout", "/proc/self/fd/1", str(out)):
        with out.open("w") as fh:
            proc = subprocess.run([sys.executable, "-m", "cli.plan", str(files["program"]), "--json",
                                   "--csv", name], stdout=fh, stderr=subprocess.PIPE, text=True,
                                  cwd=Path(__file__).resolve().parents[2])
        assert proc.returncode == 2, proc.stderr
        assert "--json -: standard output is already --csv's" in proc.stderr


def test_a_program_named_like_a_temporary_is_never_taken_for_one(tmp_path: Path,
                                                                 monkeypatch: pytest.MonkeyPatch) -> None:
    """``.out.csv.999999.abcdefabcdef.tmp`` has the name of a temporary of out.csv left by a
    writer (pid 999999) that is gone: as the program read, or as a user's file beside the
    output, it stays; a real leftover (0600, this user's) is cleaned up."""
    monkeypatch.chdir(tmp_path)
    program = tmp_path / ".out.csv.999999.abcdefabcdef.tmp"
    program.write_text("G0 X1\nM2\n")
    program.chmod(0o600)                   # even with a temporary's mode: it is the input
    assert plan_main([program.name, "--csv", "out.csv"]) == 0
    assert program.read_text() == "G0 X1\nM2\n" and (tmp_path / "out.csv").is_file()
    # beside the output, not an input of this run: a user's file (0644) stays; a leftover goes
    mine = tmp_path / ".out.csv.999998.abcdefabcdef.tmp"
    mine.write_text("a user's notes\n")
    mine.chmod(0o644)
    left = tmp_path / ".out.csv.999997.0123456789ab.tmp"
    left.write_text("half a CSV")
    left.chmod(0o600)
    other = tmp_path / "P.ngc"
    other.write_text(PROGRAM)
    assert plan_main([str(other), "--csv", "out.csv"]) == 0
    assert mine.read_text() == "a user's notes\n" and not left.exists()


@settings(max_examples=40)
@given(picks=st.lists(st.sampled_from(["program", "link", "hard", "tools", "new1", "new2", "-", ""]),
                      min_size=1, max_size=4),
       options=st.permutations(["--canon", "--samples", "--csv", "--plot"]))
def test_fuzz_output_paths_drawn_among_the_inputs_never_touch_an_input(
        tmp_path_factory: pytest.TempPathFactory, picks: list[str], options: list[str]) -> None:
    root = tmp_path_factory.mktemp("fuzz")
    program = root / "P.ngc"
    program.write_text(PROGRAM)
    tools = root / "tools.tbl"
    tools.write_text("T1 P1 Z10 D6\n")
    (root / "link.ngc").symlink_to(program)
    os.link(program, root / "hard.ngc")
    names = {"program": str(program), "link": str(root / "link.ngc"), "hard": str(root / "hard.ngc"),
             "tools": str(tools), "new1": str(root / "a.out"), "new2": str(root / "b.out"), "-": "-", "": ""}
    argv = [str(program), "--tools", str(tools)]
    for option, pick in zip(options, picks):
        argv += [option, names[pick]]
    clash = (any(p in ("program", "link", "hard", "tools", "") for p in picks)
             or len([p for p in picks if p not in ("-",)]) != len({p for p in picks if p not in ("-",)})
             or picks.count("-") > 1)
    code = plan_main(argv)
    assert program.read_text() == PROGRAM and tools.read_text() == "T1 P1 Z10 D6\n"
    assert (code == 2) == clash, (argv, code)


ROOT = Path(__file__).resolve().parents[2]


def test_mkdir_where_a_file_stands_is_refused_by_both_commands(qapp: object, files: dict[str, Path],
                                                                tmp_path: Path,
                                                                capsys: pytest.CaptureFixture[str]) -> None:
    from app.run_cli import main as run_main

    blocker = tmp_path / "afile"
    blocker.write_text("a file, not a folder\n")
    out = blocker / "sub" / "out.csv"
    assert plan_main([str(files["program"]), "--csv", str(out), "--mkdir"]) == 2
    assert f"cannot make the folder {blocker / 'sub'}: Not a directory" in capsys.readouterr().err
    assert run_main([str(files["program"]), "--sim", "--worker", "manual", "--trace", str(out),
                     "--mkdir"]) == 2
    assert f"cannot make the folder {blocker / 'sub'}: Not a directory" in capsys.readouterr().err
    assert blocker.read_text() == "a file, not a folder\n"


def test_a_plot_goes_to_a_device_or_a_pipe_as_a_png(files: dict[str, Path], tmp_path: Path) -> None:
    import subprocess
    import sys

    assert plan_main([str(files["program"]), "--plot", "/dev/null"]) == 0
    proc = subprocess.run([sys.executable, "-m", "cli.plan", str(files["program"]), "--plot", "-"],
                          capture_output=True, cwd=ROOT, timeout=120)
    assert proc.returncode == 0 and proc.stdout.startswith(b"\x89PNG\r\n"), proc.stderr
    bare = tmp_path / "plot"                         # no suffix to tell the format: PNG all the same
    assert plan_main([str(files["program"]), "--plot", str(bare)]) == 0
    assert bare.read_bytes().startswith(b"\x89PNG\r\n")


def test_a_reader_that_stops_early_ends_the_command_in_one_line(tmp_path: Path) -> None:
    """``cnc-plan long.ngc --json | head -c 10``: the rest is not wanted; no traceback."""
    import subprocess
    import sys

    program = tmp_path / "long.ngc"
    lines = "".join(f"G1 X{i % 50} Y{i % 7}\n" for i in range(20_000))
    program.write_text("G21 G90 F1000\n" + lines + "M2\n")
    for args in (["--json"], ["--canon", "-"]):
        proc = subprocess.Popen([sys.executable, "-m", "cli.plan", str(program), *args], cwd=ROOT,
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        assert proc.stdout is not None and proc.stderr is not None
        assert proc.stdout.read(10)
        proc.stdout.close()                          # as head does once it has its bytes
        err = proc.stderr.read().decode()
        assert proc.wait(timeout=120) == 1
        assert "Traceback" not in err and len(err.strip().splitlines()) == 1, err


def test_a_trace_that_cannot_be_written_after_the_run_is_said_and_the_run_reported(
        qapp: object, files: dict[str, Path], capsys: pytest.CaptureFixture[str]) -> None:
    import json

    from app.run_cli import main as run_main

    assert run_main([str(files["program"]), "--sim", "--worker", "manual", "--trace", "/dev/full",
                     "--json"]) == 1
    captured = capsys.readouterr()
    assert "cnc-run: cannot write the trace /dev/full: No space left on device" in captured.err
    assert json.loads(captured.out)["completed"] is True


@pytest.mark.parametrize("text", ["G21\nM98 P[10**308*10]\nM2\n", "G21\nG92\nM2\n", "\0\0\0",
                                  "G21\no1 repeat [10**308*10]\no1 endrepeat\nM2\n",
                                  "G21\nG1 X[1/0] F100\nM2\n"])
def test_no_traceback_reaches_a_user_of_cnc_plan(tmp_path: Path, text: str) -> None:
    import subprocess
    import sys

    program = tmp_path / "bad.ngc"
    program.write_text(text)
    proc = subprocess.run([sys.executable, "-m", "cli.plan", str(program), "--json"], capture_output=True,
                          text=True, cwd=ROOT, timeout=120)
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr and str(program) in proc.stderr, proc.stderr


def test_an_unexpected_error_is_one_line_naming_the_input(monkeypatch: pytest.MonkeyPatch,
                                                          capsys: pytest.CaptureFixture[str]) -> None:
    import cli.plan as plan

    def broken(argv: list[str] | None = None) -> int:
        raise OverflowError("cannot convert float infinity to integer\n(and more)")

    monkeypatch.setattr(plan, "main", broken)
    monkeypatch.setattr("sys.argv", ["cnc-plan", "prog.ngc", "--json"])
    assert plan.command() == 2
    err = capsys.readouterr().err
    assert err == ("cnc-plan: prog.ngc: internal error, OverflowError: cannot convert float infinity to "
                   "integer (and more)\n")


def test_an_output_fifo_no_one_reads_is_given_up(qapp: object, files: dict[str, Path], tmp_path: Path,
                                                 capsys: pytest.CaptureFixture[str],
                                                 monkeypatch: pytest.MonkeyPatch) -> None:
    import time

    from app.run_cli import main as run_main
    from planner.core import reading

    monkeypatch.setattr(reading, "SILENT_PIPE_S", 0.5)
    fifo = tmp_path / "out.fifo"
    os.mkfifo(fifo)
    started = time.monotonic()
    assert plan_main([str(files["program"]), "--csv", str(fifo)]) == 1
    assert f"no one read the pipe {fifo} for 0.5 s" in capsys.readouterr().err
    assert run_main([str(files["program"]), "--sim", "--worker", "manual", "--trace", str(fifo)]) == 1
    assert f"cannot write the trace {fifo}: no one read the pipe" in capsys.readouterr().err
    assert time.monotonic() - started < 30
    assert fifo.is_fifo()                                  # still the FIFO, never replaced by a file
