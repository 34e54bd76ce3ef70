"""The panel's own settings (language, service password and its counters, MDI history),
persisted as JSON in the state dir.

Machine values (axes, limits, offsets) belong to the machine configuration the controller
writes; this file only holds what is the panel's. A file that cannot be read is kept aside
(``panel.json.damaged-<time>``) and the service password counts as unknown, so the service
level stays locked until the integrator restores it (``app.service_access``): a damaged file
never means the default password.
"""

from __future__ import annotations

import hashlib
import json
import os
import time
from dataclasses import asdict, dataclass, field, replace
from pathlib import Path
from typing import Any

from planner.core.files import write_text

__all__ = ["DEFAULT_SERVICE_PASSWORD", "PanelSettings", "SettingsStore", "legacy_password_hash"]

DEFAULT_SERVICE_PASSWORD = "1234"   # documented in the README; change it on the Parameters page


def legacy_password_hash(password: str) -> str:
    """How earlier versions stored the password (unsalted, fast): only read, to upgrade it."""
    return hashlib.sha256(("cnc-panel:" + password).encode()).hexdigest()


def _default_password() -> dict[str, object]:
    from app.service_access import hash_password

    return hash_password(DEFAULT_SERVICE_PASSWORD)


@dataclass(frozen=True, slots=True)
class PanelSettings:
    language: str = "en"
    # scrypt record (``app.service_access``); None: unknown (the file was damaged) = locked
    service_password: dict[str, Any] | None = field(default_factory=_default_password)
    service_failures: int = 0            # wrong tries in a row
    service_next_try: float = 0.0        # wall time before which no try is accepted
    service_locked_until: float = 0.0    # wall time of the end of a lockout
    mdi_history: tuple[str, ...] = ()
    last_program: str = ""
    # keyboard shortcuts: action -> key name, over the defaults (``app.shortcuts``)
    shortcuts: dict[str, str] = field(default_factory=dict)

    def with_changes(self, **changes: object) -> PanelSettings:
        return replace(self, **changes)  # type: ignore[arg-type]


_NUMBERS = ("service_failures", "service_next_try", "service_locked_until")


class SettingsStore:
    """Loads and saves PanelSettings at ``state_dir/panel.json`` (one output writer, atomic)."""

    def __init__(self, state_dir: Path) -> None:
        self.path = Path(state_dir) / "panel.json"
        self.problem = ""     # why the file could not be read ("" when it could)
        self.settings = self._load()

    def _load(self) -> PanelSettings:
        if not self.path.exists():
            return PanelSettings()
        try:
            data = json.loads(self.path.read_text(encoding="utf-8"))
            settings = self._from_dict(data)
            if settings.service_password is None:
                self.problem = (f"the service password in {self.path} is unknown (its file was damaged "
                                "earlier)")
            return settings
        except (OSError, ValueError, TypeError, KeyError) as exc:
            aside = self.path.with_name(f"{self.path.name}.damaged-{int(time.time())}")
            try:
                os.replace(self.path, aside)
                kept = f"kept as {aside.name}"
            except OSError:
                kept = "left in place"
            self.problem = f"the panel settings file {self.path} was damaged ({exc}; {kept})"
            settings = PanelSettings(service_password=None)
            self.settings = settings
            self._save()      # the lock survives a restart: the new file says "unknown"
            return settings

    @staticmethod
    def _from_dict(data: Any) -> PanelSettings:
        if not isinstance(data, dict):
            raise ValueError("not a JSON object")
        known = {k: v for k, v in data.items() if k in PanelSettings.__dataclass_fields__}
        if "service_password" not in data and "service_password_sha256" in data:
            legacy = str(data["service_password_sha256"])
            known["service_password"] = {"scheme": "sha256-legacy", "hash": legacy}
        record = known.get("service_password", _default_password())
        if record is not None and not (isinstance(record, dict) and "scheme" in record):
            raise ValueError("service_password is not a password record")
        for key in _NUMBERS:
            if key in known and (isinstance(known[key], bool) or not isinstance(known[key], (int, float))):
                raise ValueError(f"{key} is not a number")
        if "mdi_history" in known:
            known["mdi_history"] = tuple(str(x) for x in known["mdi_history"])[-50:]
        if not isinstance(known.get("shortcuts", {}), dict):
            raise ValueError("shortcuts is not an object of action: key name")
        if not isinstance(known.get("language", "en"), str):
            raise ValueError("language is not a string")
        return PanelSettings(**known)

    def _save(self) -> None:
        data = asdict(self.settings)
        data["mdi_history"] = list(self.settings.mdi_history)
        write_text(self.path, json.dumps(data, indent=2))

    def update(self, **changes: object) -> PanelSettings:
        self.settings = self.settings.with_changes(**changes)
        self._save()
        return self.settings
