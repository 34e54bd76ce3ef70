"""The program being edited: path, text, modified flag, atomic save, autosave and recovery.

No widgets here. Autosave files live in ``state_dir/autosave/`` and are named after the
program; one is left behind only if the panel stops with unsaved changes, and offered for
recovery when the same program is opened again.
"""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

from planner.core.files import write_text


class ProgramDocument:
    def __init__(self, state_dir: Path) -> None:
        self.autosave_dir = Path(state_dir) / "autosave"
        self.path: Path | None = None
        self.saved_text = ""
        self.text = ""

    @property
    def name(self) -> str:
        return self.path.name if self.path else "untitled.nc"

    @property
    def modified(self) -> bool:
        return self.text != self.saved_text

    def new(self) -> None:
        self.path, self.saved_text, self.text = None, "", ""

    def open(self, path: Path, text: str | None = None) -> str:
        """Open ``path``; ``text``: its text as just read by the controller's load (a program of
        millions of lines is then not read and held a second time)."""
        if text is None:
            text = Path(path).read_text(encoding="utf-8", errors="replace")
        self.path, self.saved_text, self.text = Path(path).resolve(), text, text
        return text

    def save(self, path: Path | None = None) -> Path:
        target = Path(path) if path is not None else self.path
        if target is None:
            raise ValueError("no file name: use Save as")
        write_text(target, self.text)
        self.discard_autosave()
        self.path, self.saved_text = target.resolve(), self.text
        return self.path

    # --- autosave ------------------------------------------------------------------------
    def autosave_path(self, path: Path | None = None) -> Path:
        key = str(path or self.path or Path("untitled.nc"))
        digest = hashlib.sha1(key.encode()).hexdigest()[:12]
        return self.autosave_dir / f"{Path(key).name}.{digest}.autosave"

    def autosave(self) -> Path | None:
        """Write the unsaved text next to a small header; nothing when there is no change."""
        target = self.autosave_path()
        if not self.modified:
            return None
        header = json.dumps({"path": str(self.path) if self.path else ""})
        write_text(target, header + "\n" + self.text)
        return target

    def recovery_text(self, path: Path) -> str | None:
        """The autosaved text for ``path`` if it differs from the file on disk."""
        auto = self.autosave_path(Path(path).resolve())
        if not auto.exists():
            return None
        _header, _, text = auto.read_text(encoding="utf-8").partition("\n")
        try:
            on_disk = Path(path).read_text(encoding="utf-8", errors="replace")
        except OSError:
            on_disk = None
        return None if text == on_disk else text

    def discard_autosave(self) -> None:
        self.autosave_path().unlink(missing_ok=True)
