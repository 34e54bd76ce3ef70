"""Where the operator may open and save programs.

The operator's Open and Save as reach only the program folders: the panel's own
``<state dir>/programs`` (writable), the shipped samples (read only), folders given with
``cnc-panel --programs DIR`` (writable), and removable media mounted under ``/media`` or
``/run/media`` (writable). Nothing else: not the state files (positions, homed flags,
settings, the service password), not the machine configuration, not the rest of the file
system. A name typed for Save as is a plain file name (no folder part, no NUL, not hidden)
with a G-code suffix, so it can never name one of those files; the configuration is changed
on the service pages or by the integrator outside the panel. Pure Python, no Qt.
"""

from __future__ import annotations

import os
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path

from resources import PROGRAMS

__all__ = ["GCODE_SUFFIXES", "REMOVABLE_MEDIA", "ProgramFolders"]

GCODE_SUFFIXES = (".nc", ".ngc", ".gcode", ".tap", ".txt", ".cnc")
REMOVABLE_MEDIA = (Path("/media"), Path("/run/media"))


@dataclass(frozen=True)
class Root:
    path: Path
    writable: bool


class ProgramFolders:
    def __init__(self, state_dir: Path, extra: Iterable[Path] = (), media: Iterable[Path] = REMOVABLE_MEDIA,
                 samples: Path = PROGRAMS) -> None:
        own = Path(state_dir) / "programs"
        own.mkdir(parents=True, exist_ok=True)
        roots = [Root(own.resolve(), True), Root(Path(samples).resolve(), False)]
        roots += [Root(Path(p).resolve(), True) for p in extra]
        roots += [Root(Path(m).resolve(), True) for m in media if Path(m).is_dir()]
        self.roots = tuple(roots)
        self.state_dir = Path(state_dir).resolve()

    @property
    def default(self) -> Path:
        """Where Open and Save as start."""
        return self.roots[0].path

    def root_of(self, path: str | os.PathLike[str]) -> Root | None:
        """The program folder that holds ``path`` (links followed), None when none does."""
        real = Path(os.path.realpath(path))
        for root in self.roots:
            if real == root.path or root.path in real.parents:
                return root
        return None

    def may_browse(self, folder: str | os.PathLike[str]) -> bool:
        return Path(folder).is_dir() and self.root_of(folder) is not None

    def check_open(self, path: str | os.PathLike[str]) -> str:
        """"" when the operator may open ``path``, else why not."""
        if "\0" in os.fspath(path):
            return "a file name cannot contain a NUL character"
        if self.root_of(path) is None:
            return f"{path} is outside the program folders"
        if Path(path).suffix.lower() not in GCODE_SUFFIXES:
            return f"{Path(path).name} is not a G-code program ({', '.join(GCODE_SUFFIXES)})"
        return ""

    def resolve_save(self, folder: str | os.PathLike[str], name: str) -> Path | str:
        """The file to save to for a typed ``name`` in ``folder`` (.nc added when there is no
        suffix), or why not."""
        name = name.strip()
        if not name:
            return "no file name"
        if "\0" in name:
            return "a file name cannot contain a NUL character"
        if "/" in name or "\\" in name or name in (".", ".."):
            return "a file name only, without a folder (no / or \\)"
        if name.startswith("."):
            return "a file name cannot start with a dot"
        path = Path(folder) / name
        if not path.suffix:
            path = path.with_suffix(".nc")
        if path.suffix.lower() not in GCODE_SUFFIXES:
            return f"programs end in {', '.join(GCODE_SUFFIXES)}"
        root = self.root_of(path.parent)
        real = Path(os.path.realpath(path.parent))
        inside_state = real == self.state_dir or self.state_dir in real.parents
        if root is None or (inside_state and root.path != self.roots[0].path):
            return f"{path.parent} is outside the program folders"
        if not root.writable:
            return f"{root.path} holds the shipped samples (read only): save in {self.default}"
        return path
