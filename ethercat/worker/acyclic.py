"""The loop's helper for slow bus calls: SDO transfers and slave recovery take milliseconds
on a real bus, so they never run inside the 1 ms cycle. The cycle hands one job at a time to
a helper thread (inline in mode "manual", where there is no clock to miss) and looks at the
outcome in a later cycle."""

from __future__ import annotations

import threading
from collections.abc import Callable

__all__ = ["AcyclicHelper"]


class AcyclicHelper:
    """One job slot, run beside the cycle. ``busy`` is True from ``submit`` until the job has
    finished; then ``error`` holds its exception text ("" when it succeeded) and ``value`` what
    it returned."""

    def __init__(self, inline: bool) -> None:
        self.inline = inline
        self.busy = False
        self.kind = ""                   # what the running or last job was for
        self.value: object = None
        self.error = ""
        self._job: Callable[[], object] | None = None
        self._wake = threading.Event()
        self._stop = False
        self._thread: threading.Thread | None = None

    def submit(self, kind: str, job: Callable[[], object]) -> bool:
        """Start `job`; False (nothing started) while another job runs."""
        if self.busy:
            return False
        self.kind = kind
        self.value = None
        self.error = ""
        self.busy = True
        if self.inline:
            self._run(job)
            return True
        self._job = job
        if self._thread is None:
            self._thread = threading.Thread(target=self._main, name="ethercat-acyclic", daemon=True)
            self._thread.start()
        self._wake.set()
        return True

    def _run(self, job: Callable[[], object]) -> None:
        try:
            self.value = job()
        except Exception as exc:  # noqa: BLE001 - reported to the cycle as text
            self.error = f"{type(exc).__name__}: {exc}" or "failed"
        finally:
            self.busy = False

    def _main(self) -> None:
        while not self._stop:
            if not self._wake.wait(0.2):
                continue
            self._wake.clear()
            job, self._job = self._job, None
            if job is not None and not self._stop:
                self._run(job)

    def close(self, timeout_s: float = 5.0) -> None:
        """Let a running job finish (bounded), then end the thread."""
        self._stop = True
        self._wake.set()
        if self._thread is not None:
            self._thread.join(timeout=timeout_s)
            self._thread = None


_RECOVERY = "recover"


class SlaveRecovery:
    """Lost slaves brought back beside the cycle: every ``every`` cycles while some are lost,
    the bus's ``recover_slaves()`` (find the slave again, check identity, remap, SYNC0, OP) runs
    on the helper, so the cycle goes on for the others (as SOEM's ecatcheck). ``recovered``:
    the positions it brought back (a bit each)."""

    def __init__(self, helper: AcyclicHelper, every: int) -> None:
        self.helper = helper
        self.every = every
        self.countdown = 0
        self.recovered = 0
        self.calls = 0

    def attempt(self, recover: Callable[[], object]) -> None:
        if self.countdown > 0:
            self.countdown -= 1
            return
        self.countdown = self.every
        self.collect()
        if self.helper.submit(_RECOVERY, recover):
            self.calls += 1
            self.collect()       # inline mode: already done

    def collect(self) -> None:
        helper = self.helper
        if helper.kind == _RECOVERY and not helper.busy and isinstance(helper.value, tuple):
            for pos in helper.value:
                self.recovered |= 1 << min(int(pos), 62)
            helper.value = None

    @property
    def running(self) -> bool:
        return self.helper.busy and self.helper.kind == _RECOVERY
