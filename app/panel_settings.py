"""The panel's own settings (language, service password), persisted as JSON in the state dir.

Machine values (axes, limits, offsets) belong to the machine configuration the controller
writes; this file only holds what is the panel's.
"""

from __future__ import annotations

import hashlib
import json
from dataclasses import asdict, dataclass, replace
from pathlib import Path

from planner.files import write_text

DEFAULT_SERVICE_PASSWORD = "1234"   # documented in the README; change it on the Parameters page


def password_hash(password: str) -> str:
    return hashlib.sha256(("cnc-panel:" + password).encode()).hexdigest()


@dataclass(frozen=True, slots=True)
class PanelSettings:
    language: str = "en"
    service_password_sha256: str = password_hash(DEFAULT_SERVICE_PASSWORD)
    mdi_history: tuple[str, ...] = ()
    last_program: str = ""

    def with_changes(self, **changes: object) -> PanelSettings:
        return replace(self, **changes)  # type: ignore[arg-type]


class SettingsStore:
    """Loads and saves PanelSettings at ``state_dir/panel.json`` (atomic write)."""

    def __init__(self, state_dir: Path) -> None:
        self.path = Path(state_dir) / "panel.json"
        self.settings = self._load()

    def _load(self) -> PanelSettings:
        try:
            data = json.loads(self.path.read_text(encoding="utf-8"))
        except (OSError, ValueError):
            return PanelSettings()
        known = {k: v for k, v in data.items() if k in PanelSettings.__dataclass_fields__}
        if "mdi_history" in known:
            known["mdi_history"] = tuple(str(x) for x in known["mdi_history"])[-50:]
        try:
            return PanelSettings(**known)
        except TypeError:
            return PanelSettings()

    def update(self, **changes: object) -> PanelSettings:
        self.settings = self.settings.with_changes(**changes)
        data = asdict(self.settings)
        data["mdi_history"] = list(self.settings.mdi_history)
        write_text(self.path, json.dumps(data, indent=2))
        return self.settings

    def check_password(self, password: str) -> bool:
        return password_hash(password) == self.settings.service_password_sha256
