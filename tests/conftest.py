"""Test session set-up: offscreen Qt, the slow marker, hypothesis profiles."""

from __future__ import annotations

import os

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

import pytest  # noqa: E402
from hypothesis import HealthCheck, settings  # noqa: E402

# The suite (make test, CI) draws the same examples on every run, so its result never depends
# on luck; ``make explore`` (HYPOTHESIS_PROFILE=explore) draws new ones each run, to search.
settings.register_profile(
    "ci", derandomize=True, deadline=None, print_blob=True,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.register_profile("explore", deadline=None, print_blob=True,
                          suppress_health_check=[HealthCheck.too_slow])
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addoption("--run-slow", action="store_true", default=False,
                     help="also run tests marked slow")


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    if config.getoption("--run-slow"):
        return
    skip_slow = pytest.mark.skip(reason="slow test: run with --run-slow")
    for item in items:
        if "slow" in item.keywords:
            item.add_marker(skip_slow)


def _shipped_files() -> dict[str, str]:
    """The hash of every file shipped with the control (machines, programs, subroutines)."""
    import hashlib

    from resources import MACHINES, PROGRAMS, SUBROUTINES

    out = {}
    for folder in (MACHINES, PROGRAMS, SUBROUTINES):
        for path in sorted(folder.rglob("*")):
            if path.is_file():
                out[str(path)] = hashlib.sha256(path.read_bytes()).hexdigest()
    return out


@pytest.fixture(autouse=True, scope="session")
def _shipped_files_stay_as_shipped():
    """No test may write into the control's own files (a save landing on a sample program)."""
    before = _shipped_files()
    yield
    after = _shipped_files()
    changed = sorted(p for p in set(before) | set(after) if before.get(p) != after.get(p))
    assert not changed, f"tests changed files shipped with the control: {changed}"
