"""Who may change the machine: the service password, its rate limit, lockout and automatic lock.

The service pages (axes, parameters) change travel, limits and drives, so they sit behind a
password. What keeps that password worth having:

* It is stored as a salted, slow hash (``hashlib.scrypt``, N = 2^14, r = 8, p = 1: about
  50 ms per try on a panel PC), never as text or a fast digest.
* Wrong tries cost time: after the k-th wrong try in a row the next is accepted only after
  min(2^(k-1), 30) s, and after 10 in a row the service level is locked out for 15 minutes.
  The count and the times persist in the settings file, so a restart does not reset them.
* A new password needs the old one, at least ``MIN_LENGTH`` characters and the same text
  twice.
* A settings file that cannot be read means locked, not the default password: the damaged
  file is kept aside and the recovery is done by the integrator at the panel PC
  (``cnc-panel --reset-service-password``, which needs a shell on that PC, restores the
  default password; see README).
* The unlocked state ends when the operator leaves the service pages and after
  ``IDLE_LOCK_S`` without a touch (``MainWindow``).

Pure Python (no Qt); the clock is injectable for tests.
"""

from __future__ import annotations

import hashlib
import hmac
import secrets
import time
from collections.abc import Callable
from dataclasses import dataclass

from app.panel_settings import DEFAULT_SERVICE_PASSWORD, SettingsStore, legacy_password_hash

__all__ = ["IDLE_LOCK_S", "LOCKOUT_AFTER", "LOCKOUT_S", "MIN_LENGTH", "AccessOutcome", "ServiceAccess",
           "hash_password", "verify_password"]

MIN_LENGTH = 6
DELAY_MAX_S = 30.0
LOCKOUT_AFTER = 10
LOCKOUT_S = 900.0
IDLE_LOCK_S = 300.0
_SCRYPT = {"n": 2**14, "r": 8, "p": 1}


def hash_password(password: str, salt: bytes | None = None) -> dict[str, object]:
    """The stored record of a password: scheme, parameters, salt and hash (hex)."""
    salt = salt if salt is not None else secrets.token_bytes(16)
    digest = hashlib.scrypt(password.encode("utf-8"), salt=salt, maxmem=64 * 2**20, dklen=32, **_SCRYPT)
    return {"scheme": "scrypt", **_SCRYPT, "salt": salt.hex(), "hash": digest.hex()}


def verify_password(record: dict[str, object], password: str) -> bool:
    try:
        if record.get("scheme") != "scrypt":
            return False
        salt = bytes.fromhex(str(record["salt"]))
        want = bytes.fromhex(str(record["hash"]))
        n, r, p = int(record["n"]), int(record["r"]), int(record["p"])  # type: ignore[call-overload]
        got = hashlib.scrypt(password.encode("utf-8"), salt=salt, n=n, r=r, p=p, maxmem=64 * 2**20,
                             dklen=len(want))
    except (KeyError, ValueError, TypeError):
        return False
    return hmac.compare_digest(got, want)


@dataclass(frozen=True, slots=True)
class AccessOutcome:
    """What an attempt gave: ``granted``, else the reason to show and, when waiting is the
    reason, how long (s)."""

    granted: bool
    reason: str = ""
    wait_s: float = 0.0

    def __bool__(self) -> bool:
        return self.granted


class ServiceAccess:
    """The service level's lock over the panel settings (``SettingsStore``)."""

    def __init__(self, store: SettingsStore, clock: Callable[[], float] = time.time) -> None:
        self.store = store
        self.clock = clock
        self.unlocked = False
        self.last_touch = clock()

    # ------------------------------------------------------------------ state
    @property
    def damaged(self) -> str:
        """Why the password cannot be checked ("" when it can)."""
        return self.store.problem if self.store.settings.service_password is None else ""

    def _refusal(self) -> AccessOutcome | None:
        if self.damaged:
            return AccessOutcome(False, f"service level locked: {self.damaged}; recovery: run "
                                        "`cnc-panel --reset-service-password` on the panel PC")
        s = self.store.settings
        now = self.clock()
        if s.service_locked_until > now:
            wait = s.service_locked_until - now
            return AccessOutcome(False, f"too many wrong passwords: locked for {wait / 60:.0f} more minutes",
                                 wait)
        if s.service_next_try > now:
            wait = s.service_next_try - now
            return AccessOutcome(False, f"wait {wait:.0f} s before the next try", wait)
        return None

    def _check(self, password: str) -> AccessOutcome:
        """One counted try: refused without checking while waiting or locked out."""
        refused = self._refusal()
        if refused is not None:
            return refused
        s = self.store.settings
        record = s.service_password or {}
        if record.get("scheme") == "sha256-legacy":
            ok = hmac.compare_digest(legacy_password_hash(password), str(record.get("hash", "")))
            if ok:   # an old file: keep the password, store it the safe way from now on
                self.store.update(service_password=hash_password(password))
        else:
            ok = verify_password(record, password)
        now = self.clock()
        if ok:
            self.store.update(service_failures=0, service_next_try=0.0, service_locked_until=0.0)
            return AccessOutcome(True)
        failures = s.service_failures + 1
        if failures >= LOCKOUT_AFTER:
            self.store.update(service_failures=0, service_next_try=0.0, service_locked_until=now + LOCKOUT_S)
            return AccessOutcome(False, f"wrong password {LOCKOUT_AFTER} times: service level locked for "
                                        f"{LOCKOUT_S / 60:.0f} minutes", LOCKOUT_S)
        delay = min(2.0 ** (failures - 1), DELAY_MAX_S)
        self.store.update(service_failures=failures, service_next_try=now + delay)
        return AccessOutcome(False, f"wrong password; next try in {delay:.0f} s", delay)

    # ------------------------------------------------------------------ commands
    def unlock(self, password: str) -> AccessOutcome:
        outcome = self._check(password)
        if outcome:
            self.unlocked = True
            self.last_touch = self.clock()
        return outcome

    def lock(self) -> None:
        self.unlocked = False

    def touch(self) -> None:
        """The operator did something: the idle time starts again."""
        self.last_touch = self.clock()

    def lock_if_idle(self) -> bool:
        """Lock after ``IDLE_LOCK_S`` without a touch; True when this call locked."""
        if self.unlocked and self.clock() - self.last_touch >= IDLE_LOCK_S:
            self.unlocked = False
            return True
        return False

    def change_password(self, old: str, new: str, repeat: str) -> AccessOutcome:
        """Needs the current password (a counted try), ``MIN_LENGTH`` characters and the new one
        twice."""
        if len(new) < MIN_LENGTH:
            return AccessOutcome(False, f"the new password needs at least {MIN_LENGTH} characters")
        if new != repeat:
            return AccessOutcome(False, "the two new passwords differ")
        outcome = self._check(old)
        if not outcome:
            return AccessOutcome(False, f"current password: {outcome.reason}", outcome.wait_s)
        self.store.update(service_password=hash_password(new))
        return AccessOutcome(True)


def reset_service_password(store: SettingsStore) -> None:
    """The integrator's recovery at the panel PC: the default password again, counters cleared."""
    store.update(service_password=hash_password(DEFAULT_SERVICE_PASSWORD), service_failures=0,
                 service_next_try=0.0, service_locked_until=0.0)
    store.problem = ""
