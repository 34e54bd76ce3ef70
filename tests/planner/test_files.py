"""The one output writer keeps what it writes to as it was: a device stays a device, a FIFO
a FIFO, a link a link, a file keeps its permissions; a regular file is replaced atomically
(a writer killed in the middle leaves the old or the new file, never a torn one), and the
temporaries such a killed writer leaves are removed by the next write."""

from __future__ import annotations

import os
import signal
import stat
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

from cli.plan import main as cnc_plan
from planner.core.files import remove_stale_temporaries, write_output, write_text

ROOT = Path(__file__).resolve().parents[2]


def test_a_character_device_stays_a_device(tmp_path: Path) -> None:
    before = os.stat("/dev/null")
    write_text("/dev/null", "discarded\n")
    after = os.stat("/dev/null")
    assert stat.S_ISCHR(after.st_mode) and after.st_rdev == before.st_rdev


def test_cnc_plan_canon_to_dev_null_leaves_dev_null_alone(tmp_path: Path) -> None:
    prog = tmp_path / "p.nc"
    prog.write_text("G1 X10 F600\nG2 X20 R5\nM30\n")
    assert cnc_plan([str(prog), "--canon", "/dev/null", "--samples", "/dev/null"]) == 0
    assert stat.S_ISCHR(os.stat("/dev/null").st_mode)


def test_a_fifo_is_written_into_and_stays_a_fifo(tmp_path: Path) -> None:
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    got: list[bytes] = []
    reader = threading.Thread(target=lambda: got.append(fifo.read_bytes()))
    reader.start()
    write_text(fifo, "through the pipe\n")
    reader.join(timeout=10)
    assert got == [b"through the pipe\n"]
    assert stat.S_ISFIFO(os.stat(fifo).st_mode)


def test_a_symlink_is_written_through_and_stays_a_link(tmp_path: Path) -> None:
    target = tmp_path / "real" / "machine.toml"
    target.parent.mkdir()
    target.write_text("old\n")
    link = tmp_path / "machine.toml"
    link.symlink_to(target)
    write_text(link, "new\n")
    assert link.is_symlink() and os.readlink(link) == str(target)
    assert target.read_text() == "new\n"


@pytest.mark.parametrize("mode", [0o644, 0o755, 0o600])
def test_a_regular_file_keeps_its_permissions(tmp_path: Path, mode: int) -> None:
    f = tmp_path / "p.nc"
    f.write_text("old\n")
    os.chmod(f, mode)
    write_text(f, "new\n")
    assert stat.S_IMODE(os.stat(f).st_mode) == mode and f.read_text() == "new\n"


def test_a_new_file_gets_the_umask_permissions_not_0600(tmp_path: Path) -> None:
    old = os.umask(0o022)
    try:
        write_text(tmp_path / "new.nc", "x\n")
    finally:
        os.umask(old)
    assert stat.S_IMODE(os.stat(tmp_path / "new.nc").st_mode) == 0o644


def test_dash_is_standard_output(capfdbinary: pytest.CaptureFixture[bytes]) -> None:
    write_output("-", lambda fh: fh.write(b"to stdout\n"))
    assert capfdbinary.readouterr().out == b"to stdout\n"


def test_temporary_names_are_random_and_left_nothing(tmp_path: Path) -> None:
    f = tmp_path / "a.txt"
    seen: set[str] = set()
    real = os.replace

    def spy(src: str | os.PathLike[str], dst: str | os.PathLike[str]) -> None:
        seen.add(Path(src).name)
        real(src, dst)

    os.replace = spy  # type: ignore[assignment]
    try:
        for k in range(5):
            write_text(f, f"{k}\n")
    finally:
        os.replace = real  # type: ignore[assignment]
    assert len(seen) == 5
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.txt"]


_WRITER = """
import sys, time
from planner.core.files import write_output
path, = sys.argv[1:]

def slow(fh, digit):
    for _ in range(4):                 # 4 MB in four pieces, a pause between them
        fh.write(digit * 1_000_000)
        time.sleep(0.02)

k = 0
while True:
    write_output(path, lambda fh: slow(fh, str(k % 10).encode()))
    if k == 0:
        print("writing", flush=True)
    k += 1
"""


def test_kill_9_during_saves_leaves_a_whole_file_and_the_next_write_cleans_up(tmp_path: Path) -> None:
    f = tmp_path / "big.dat"
    write_output(f, lambda fh: fh.write(b"0" * 4_000_000))
    # killed at three moments at least, and on until one kill lands inside a save (a save is
    # nearly all of the writer's time, but on a loaded machine the kill can land between two,
    # while the finished one is renamed and synced; each writer removes the temporaries of
    # writers killed before it, so only the last kill's can be left)
    leftovers: list[Path] = []
    for attempt, delay in enumerate((0.05, 0.13, 0.31) * 8):
        proc = subprocess.Popen([sys.executable, "-c", _WRITER, str(f)], cwd=ROOT, stdout=subprocess.PIPE,
                                text=True)
        try:
            assert proc.stdout is not None and proc.stdout.readline() == "writing\n"
            time.sleep(delay)                        # inside a save most of the time (pauses)
        finally:
            proc.send_signal(signal.SIGKILL)
            proc.wait(timeout=10)
        data = f.read_bytes()
        assert len(data) == 4_000_000 and data == data[:1] * len(data), "torn file"
        leftovers = [p for p in tmp_path.iterdir() if p.name != "big.dat"]
        if attempt >= 2 and leftovers:
            break
    assert leftovers, "a writer killed mid-save leaves its temporary (the test must see one)"
    removed = remove_stale_temporaries(f)
    assert sorted(removed) == sorted(leftovers)
    write_text(tmp_path / "other.txt", "x")           # a write to another name leaves those alone
    write_output(f, lambda fh: fh.write(b"1" * 10))
    assert sorted(p.name for p in tmp_path.iterdir()) == ["big.dat", "other.txt"]


def test_the_state_folder_is_cleaned_of_stale_temporaries_at_start(tmp_path: Path) -> None:
    from app.machine.infra.persist import StateStore

    state = tmp_path / "state"
    state.mkdir()
    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True,
                          text=True).stdout.strip()
    stale = state / f".state.json.{dead}.0123456789ab.tmp"
    stale.write_text("{half")
    stale.chmod(0o600)                             # as a writer makes its temporary
    mine = state / f".alarms.json.{os.getpid()}.0123456789ab.tmp"   # a live writer's: kept
    mine.write_text("{")
    StateStore(state)
    assert not stale.exists() and mine.exists()
