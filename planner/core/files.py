"""The one output writer: every file the project writes goes through ``write_output``.

What it does, by what the name points at:

* ``-``: standard output.
* A character or block device, a FIFO or a socket (``/dev/null``, a pipe to another
  program): opened and written directly. Never replaced by a regular file, which is what a
  rename over it would do (as root even ``/dev/null``).
* A symbolic link: written through to its target; the link stays a link.
* A regular file, or nothing yet: atomically. The data goes to a temporary file in the same
  folder with a random name (``.NAME.<pid>.<random>.tmp``), is flushed and fsync'ed, gets the
  permissions (and, when we may, the owner) of the file it replaces, or 0666 less the umask for
  a new file, and is renamed over the target; the folder is fsync'ed so the rename survives a
  power cut. The name always holds either the old or the new complete file. Temporaries left
  by an earlier writer that was killed (its process is gone) are removed.

Writers that need a file name rather than a stream (an image exporter choosing the format by
the suffix) use ``write_output_via_path``. Errors are ``OSError`` as from ``open``.
"""

from __future__ import annotations

import contextlib
import errno
import io
import os
import re
import secrets
import select
import shutil
import stat
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any, BinaryIO

from planner.core import reading

__all__ = ["OutputClash", "check_outputs", "protect_input", "remove_stale_temporaries", "write_output",
           "write_output_via_path", "write_text"]

STDOUT = "-"
_TMP_RE = re.compile(r"^\.(?P<name>.+)\.(?P<pid>\d+)\.[0-9a-f]{12}\.tmp(?P<suffix>\.\w+)?$")


class OutputClash(ValueError):
    """An output path that would destroy an input or another output, is empty, or lies in a
    folder that does not exist; the message names the option and the reason."""


def _identity(path: str) -> tuple[str, object]:
    """What a path names, through links: the file's device and inode when it exists, else the
    absolute path it would be created at."""
    try:
        st = os.stat(path)
        return ("inode", (st.st_dev, st.st_ino))
    except OSError:
        return ("path", os.path.realpath(path))


def _stdout_identity() -> tuple[str, object] | None:
    """What standard output is (a file, a pipe, a terminal), by device and inode."""
    try:
        st = os.fstat(sys.stdout.fileno())
    except (OSError, ValueError, AttributeError):
        return None
    return ("inode", (st.st_dev, st.st_ino))


def check_outputs(outputs: dict[str, str | None], inputs: dict[str, str | None], *,
                  input_dirs: tuple[str, ...] = (), make_dirs: bool = False) -> None:
    """Refuse, before anything is written, an output (``{option: path}``, None when not asked
    for) that is empty, that names the same file as an input (``{what: path}``) or as another
    output (through links, by device and inode), that is a file in one of ``input_dirs`` (the
    program's subroutine folders), or whose folder is missing (unless ``make_dirs``).
    Standard output may be one output only, however it is named (``-``, ``/dev/stdout``,
    ``/proc/self/fd/1``, or the file it is redirected to). The inputs are kept from the
    clean-up of stale temporaries for as long as the process runs. Raises ``OutputClash``."""
    seen: dict[tuple[str, object], tuple[str, str]] = {}   # identity: (name, "an input" or "another output")
    for what, path in inputs.items():
        if path:
            seen.setdefault(_identity(path), (what, "an input"))
            seen.setdefault(("path", os.path.realpath(path)), (what, "an input"))
            protect_input(path)
    folders = [os.path.realpath(d) for d in input_dirs if d]
    stdout = _stdout_identity()
    stdout_taken = ""
    for option, path in outputs.items():
        if path is None:
            continue
        if not path.strip():
            raise OutputClash(f"{option}: an empty path (name a file, or - for standard output)")
        if path == STDOUT or (stdout is not None and _identity(path) == stdout):
            if stdout_taken:
                raise OutputClash(f"{option} {path}: standard output is already {stdout_taken}'s")
            stdout_taken = option
            if path == STDOUT:
                continue
        if os.path.isdir(path):
            raise OutputClash(f"{option} {path}: is a folder, not a file")
        try:
            if stat.S_ISCHR(os.stat(path).st_mode):     # /dev/null and its kind: a sink, never a file lost
                continue
        except OSError:
            pass
        keys = (_identity(path), ("path", os.path.realpath(path)))
        for key in keys:
            if key in seen:
                other, kind = seen[key]
                raise OutputClash(f"{option} {path}: the same file as {other} ({kind}); it would be "
                                  "overwritten: give another name")
        real = os.path.realpath(path)
        for folder in folders:
            if os.path.dirname(real) == folder and os.path.exists(real):
                raise OutputClash(f"{option} {path}: a file in the subroutine folder {folder}; it would be "
                                  "overwritten: give another name")
        parent = os.path.dirname(os.path.abspath(path))
        if not os.path.isdir(parent):
            if not make_dirs:
                raise OutputClash(f"{option} {path}: the folder {parent} does not exist (--mkdir creates it)")
            try:
                os.makedirs(parent, exist_ok=True)
            except OSError as exc:          # a file where a folder should be, a read-only folder
                raise OutputClash(f"{option} {path}: cannot make the folder {parent}: "
                                  f"{exc.strerror or exc}") from None
        for key in keys:
            seen[key] = (option, "another output")


def write_text(path: str | os.PathLike[str], text: str, encoding: str = "utf-8") -> None:
    """``write_output`` of a text."""
    data = text.encode(encoding)
    write_output(path, lambda fh: fh.write(data))


def write_output(path: str | os.PathLike[str], write: Callable[[BinaryIO], object]) -> None:
    """Call ``write(binary_file)`` to produce the content of ``path`` (see the module docstring
    for what happens by kind of path)."""
    name = os.fspath(path)
    if name == STDOUT:
        out = sys.stdout.buffer
        write(out)
        out.flush()
        return
    target = Path(name)
    if target.is_symlink():
        target = Path(os.path.realpath(target))
    if _is_special(target):
        with io.BufferedWriter(_StallBounded(target), buffer_size=1 << 16) as fh:
            write(fh)
        return
    _atomic(target, lambda tmp: _write_file(tmp, write))


class _StallBounded(io.RawIOBase):
    """A FIFO, socket or device written to with a bound on how long it may stall: opened
    without waiting for a reader (a FIFO no one reads is given up after ``SILENT_PIPE_S``), and
    each write waits at most as long for the reader to take more."""

    def __init__(self, path: Path) -> None:
        self.path = path
        deadline = time.monotonic() + reading.SILENT_PIPE_S
        while True:
            try:
                self.fd = os.open(path, os.O_WRONLY | os.O_NONBLOCK)
                break
            except OSError as exc:
                if exc.errno != errno.ENXIO or time.monotonic() > deadline:   # ENXIO: no reader yet
                    if exc.errno == errno.ENXIO:
                        raise OSError(errno.ETIMEDOUT, f"no one read the pipe {path} for "
                                      f"{reading.SILENT_PIPE_S:g} s") from None
                    raise
                time.sleep(0.05)

    def writable(self) -> bool:
        return True

    def write(self, data: Any) -> int:
        view = memoryview(data).cast("B")
        _, ready, _ = select.select([], [self.fd], [], reading.SILENT_PIPE_S)
        if not ready:
            raise OSError(errno.ETIMEDOUT, f"nothing was read from {self.path} for "
                          f"{reading.SILENT_PIPE_S:g} s")
        try:
            return os.write(self.fd, view)
        except BlockingIOError:
            return 0

    def close(self) -> None:
        if not self.closed:
            os.close(self.fd)
        super().close()


def write_output_via_path(path: str | os.PathLike[str], produce: Callable[[str], object]) -> None:
    """Call ``produce(file_name)`` to write the content into a temporary file that has the
    same suffix as ``path``; the result then reaches ``path`` as ``write_output`` would put it."""
    name = os.fspath(path)
    target = Path(name)
    if name != STDOUT and target.is_symlink():
        target = Path(os.path.realpath(target))
    if name != STDOUT and not _is_special(target):
        _atomic(target, lambda tmp: produce(os.fspath(tmp)))
        return
    with tempfile.TemporaryDirectory() as scratch:
        tmp = os.path.join(scratch, "out" + (target.suffix if name != STDOUT else ""))
        produce(tmp)
        with open(tmp, "rb") as src:
            write_output(name if name == STDOUT else target, lambda fh: shutil.copyfileobj(src, fh))


def _is_special(path: Path) -> bool:
    try:
        mode = path.stat().st_mode
    except FileNotFoundError:
        return False
    return not stat.S_ISREG(mode) and not stat.S_ISDIR(mode)


def _write_file(tmp: Path, write: Callable[[BinaryIO], object]) -> None:
    with open(tmp, "wb") as fh:
        write(fh)


def _temporary_name(target: Path) -> Path:
    return target.with_name(f".{target.name}.{os.getpid()}.{secrets.token_hex(6)}.tmp{target.suffix}")


def _atomic(target: Path, produce: Callable[[Path], object]) -> None:
    if target.is_dir():
        raise IsADirectoryError(21, "Is a directory", str(target))
    target.parent.mkdir(parents=True, exist_ok=True)
    remove_stale_temporaries(target)
    tmp = _temporary_name(target)
    fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
    os.close(fd)
    try:
        produce(tmp)
        with open(tmp, "rb+") as fh:
            fh.flush()
            os.fsync(fh.fileno())
        _copy_metadata(target, tmp)
        os.replace(tmp, target)
    except BaseException:
        with contextlib.suppress(OSError):
            tmp.unlink()
        raise
    _fsync_dir(target.parent)


def _copy_metadata(target: Path, tmp: Path) -> None:
    try:
        st = target.stat()
    except FileNotFoundError:
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)
        return
    os.chmod(tmp, stat.S_IMODE(st.st_mode))
    if hasattr(os, "chown"):
        with contextlib.suppress(OSError):       # only root may give a file away
            os.chown(tmp, st.st_uid, st.st_gid)


def _fsync_dir(folder: Path) -> None:
    try:
        fd = os.open(folder, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)


def _alive(pid: int) -> bool:
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


#: the inputs of this process (device and inode): never taken for a stale temporary
_INPUTS: set[tuple[int, int]] = set()


def protect_input(path: str | os.PathLike[str]) -> None:
    """Keep ``path`` (a program, a configuration, a tool table the process reads) from the
    clean-up of stale temporaries, whatever its name."""
    with contextlib.suppress(OSError):
        st = os.stat(path)
        _INPUTS.add((st.st_dev, st.st_ino))


def _made_here(entry: Path) -> bool:
    """Whether ``entry`` is what a killed writer leaves: a regular file of this user with the
    0600 a temporary is made with (its own mode comes only just before the rename), and no
    input of this process."""
    try:
        st = entry.lstat()
    except OSError:
        return False
    return (stat.S_ISREG(st.st_mode) and stat.S_IMODE(st.st_mode) == 0o600
            and st.st_uid == os.getuid() and (st.st_dev, st.st_ino) not in _INPUTS)


def remove_stale_temporaries(target: str | os.PathLike[str], *, whole_folder: bool = False) -> list[Path]:
    """Remove the temporaries of ``target`` (with ``whole_folder``: of every file in its
    folder, ``target`` being the folder) left by writers whose process is gone (killed in the
    middle of a save); returns what was removed. A file is taken for one only when it has a
    temporary's name, the process named in it is gone, and it is what a writer makes (see
    ``_made_here``): a program that merely has such a name is left alone."""
    target = Path(target)
    folder = target if whole_folder else target.parent
    removed: list[Path] = []
    try:
        entries = list(folder.iterdir())
    except OSError:
        return removed
    for entry in entries:
        m = _TMP_RE.match(entry.name)
        if m is None or (not whole_folder and m.group("name") != target.name) or _alive(int(m.group("pid"))):
            continue
        if not _made_here(entry):
            continue
        with contextlib.suppress(OSError):
            entry.unlink()
            removed.append(entry)
    return removed
