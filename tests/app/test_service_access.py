"""The service password: stored salted and slow, wrong tries cost growing delays and then a
lockout that survives a restart, a new password needs the old one, and a damaged settings
file means locked (not the default password) until the integrator resets it."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from app.panel_settings import DEFAULT_SERVICE_PASSWORD, SettingsStore, legacy_password_hash
from app.service_access import (
    LOCKOUT_AFTER,
    LOCKOUT_S,
    MIN_LENGTH,
    ServiceAccess,
    reset_service_password,
    verify_password,
)


class Clock:
    def __init__(self) -> None:
        self.t = 1_700_000_000.0

    def __call__(self) -> float:
        return self.t


@pytest.fixture
def clock() -> Clock:
    return Clock()


def access_in(folder: Path, clock: Clock) -> ServiceAccess:
    return ServiceAccess(SettingsStore(folder), clock=clock)


def test_the_password_is_stored_salted_and_slow(tmp_path: Path, clock: Clock) -> None:
    a = access_in(tmp_path, clock)
    a.store.update(language="tr")                       # writes the file
    text = (tmp_path / "panel.json").read_text()
    record = json.loads(text)["service_password"]
    assert record["scheme"] == "scrypt" and record["n"] >= 2**14 and len(bytes.fromhex(record["salt"])) == 16
    assert DEFAULT_SERVICE_PASSWORD not in text and legacy_password_hash(DEFAULT_SERVICE_PASSWORD) not in text
    assert verify_password(record, DEFAULT_SERVICE_PASSWORD) and not verify_password(record, "12345")
    other = access_in(tmp_path / "other", clock).store.settings.service_password
    assert other is not None and other["salt"] != record["salt"]      # a salt per store


def test_wrong_tries_cost_growing_delays_then_a_lockout_that_survives_a_restart(tmp_path: Path,
                                                                                clock: Clock) -> None:
    a = access_in(tmp_path, clock)
    waits = []
    for _ in range(LOCKOUT_AFTER - 1):
        out = a.unlock("nope")
        assert not out
        waits.append(out.wait_s)
        early = a.unlock(DEFAULT_SERVICE_PASSWORD)      # even the right one is refused while waiting
        assert not early and "wait" in early.reason
        clock.t += out.wait_s
    assert waits == [1, 2, 4, 8, 16, 30, 30, 30, 30]
    out = a.unlock("nope")
    assert not out and out.wait_s == LOCKOUT_S and "locked" in out.reason
    clock.t += 60
    again = access_in(tmp_path, clock)                   # a restart does not end the lockout
    refused = again.unlock(DEFAULT_SERVICE_PASSWORD)
    assert not refused and "locked for 14 more minutes" in refused.reason
    clock.t += LOCKOUT_S
    assert again.unlock(DEFAULT_SERVICE_PASSWORD) and again.unlocked
    assert again.store.settings.service_failures == 0


def test_a_new_password_needs_the_old_one_a_minimum_length_and_two_equal_entries(tmp_path: Path,
                                                                                 clock: Clock) -> None:
    a = access_in(tmp_path, clock)
    assert "at least" in a.change_password(DEFAULT_SERVICE_PASSWORD, "x", "x").reason
    assert "differ" in a.change_password(DEFAULT_SERVICE_PASSWORD, "abcdefg", "abcdefh").reason
    wrong_old = a.change_password("guess", "abcdefg", "abcdefg")
    assert not wrong_old and "current password" in wrong_old.reason
    clock.t += wrong_old.wait_s
    assert a.change_password(DEFAULT_SERVICE_PASSWORD, "s3cret!", "s3cret!")
    assert len("s3cret!") >= MIN_LENGTH
    b = access_in(tmp_path, clock)
    assert not b.unlock(DEFAULT_SERVICE_PASSWORD)
    clock.t += 1
    assert b.unlock("s3cret!")


@pytest.mark.parametrize("content", ["{not json", "[1, 2]", '{"service_password": "1234"}',
                                     '{"service_failures": "many"}', ""])
def test_a_damaged_settings_file_means_locked_until_reset(tmp_path: Path, clock: Clock, content: str) -> None:
    (tmp_path / "panel.json").write_text(content)
    a = access_in(tmp_path, clock)
    assert a.damaged and "damaged" in a.damaged
    refused = a.unlock(DEFAULT_SERVICE_PASSWORD)
    assert not refused and "cnc-panel --reset-service-password" in refused.reason
    assert [p.name.startswith("panel.json.damaged-") for p in tmp_path.iterdir()].count(True) == 1
    # a restart does not turn the damage into the default password
    b = access_in(tmp_path, clock)
    assert b.damaged and "unknown" in b.damaged
    assert "reset-service-password" in b.unlock(DEFAULT_SERVICE_PASSWORD).reason
    reset_service_password(b.store)                  # the integrator, at the panel PC
    c = access_in(tmp_path, clock)
    assert not c.damaged and c.unlock(DEFAULT_SERVICE_PASSWORD)


def test_an_old_unsalted_password_is_accepted_once_and_stored_the_safe_way(tmp_path: Path,
                                                                             clock: Clock) -> None:
    old = {"language": "en", "service_password_sha256": legacy_password_hash("old-pin")}
    (tmp_path / "panel.json").write_text(json.dumps(old))
    a = access_in(tmp_path, clock)
    assert not a.damaged and a.unlock("old-pin")
    stored = json.loads((tmp_path / "panel.json").read_text())
    assert stored["service_password"]["scheme"] == "scrypt" and "service_password_sha256" not in stored
    assert access_in(tmp_path, clock).unlock("old-pin")


def test_idle_lock(tmp_path: Path, clock: Clock) -> None:
    from app.service_access import IDLE_LOCK_S

    a = access_in(tmp_path, clock)
    assert a.unlock(DEFAULT_SERVICE_PASSWORD)
    clock.t += IDLE_LOCK_S - 1
    a.touch()
    clock.t += IDLE_LOCK_S - 1
    assert not a.lock_if_idle() and a.unlocked
    clock.t += 1
    assert a.lock_if_idle() and not a.unlocked


def test_the_integrators_recovery_command(tmp_path: Path, clock: Clock) -> None:
    import subprocess
    import sys

    (tmp_path / "panel.json").write_text("{damaged")
    assert access_in(tmp_path, clock).damaged
    cmd = [sys.executable, "-m", "app", "--reset-service-password", "--state-dir", str(tmp_path)]
    root = Path(__file__).resolve().parents[2]
    done = subprocess.run(cmd, capture_output=True, text=True, timeout=60, cwd=root)
    assert done.returncode == 0 and "service password reset" in done.stdout
    a = access_in(tmp_path, clock)
    assert not a.damaged and a.unlock(DEFAULT_SERVICE_PASSWORD)
