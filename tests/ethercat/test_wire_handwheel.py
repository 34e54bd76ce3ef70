"""The handwheel on a real EtherCAT link: the worker (its own process, real time) with SoemBus
against the project's emulator, an EL5101 beside two drives (veth pair in a network namespace,
as the other link tests; root). The emulated encoder's counter is turned through the
emulator's control socket, across its 16-bit wrap; the axis ends at the sum of the steps to
one count, every sampled set-point within the axis' limits."""

from __future__ import annotations

import time
from collections.abc import Iterator

import numpy as np
import pytest

from ethercat.bus import DriveSpec
from ethercat.drive_model import DriveParams
from ethercat.emulator.link import EmulatedLink, link_unavailable_reason
from ethercat.terminals import TerminalSpec
from ethercat.worker import CyclicWorker, HandwheelMode, HandwheelSpec, WheelState, WorkerConfig, WorkerState
from tests.ethercat.test_wire_terminals import emulated_link

REASON = link_unavailable_reason()
pytestmark = [pytest.mark.root,
              pytest.mark.skipif(bool(REASON), reason=f"EtherCAT link tests skipped: {REASON}")]

P = DriveParams()
DRIVES = tuple(DriveSpec(i, "XY"[i], vendor_id=P.vendor_id, product_code=P.product_code) for i in range(2))
TERMINALS = (TerminalSpec(2, "EK1100"), TerminalSpec(3, "EL5101"))
V, A, J = 20.0, 1000.0, 20_000.0
SCALE = 0.01 / 4


@pytest.fixture(scope="module")
def link() -> Iterator[EmulatedLink]:
    yield from emulated_link(("EK1100", "EL5101"))


def _wait(w: CyclicWorker, predicate, timeout_s: float = 5.0) -> None:
    deadline = time.monotonic() + timeout_s
    while not predicate():
        assert time.monotonic() < deadline, "timed out"
        time.sleep(0.01)


def test_the_emulated_encoder_turns_the_wheel_across_its_wrap(link: EmulatedLink) -> None:
    link.control("encoder", slave=3, add=65_500)             # 36 counts below the wrap
    cfg = WorkerConfig(drives=DRIVES, bus_kind="soem", adapter=link.master_ifname, mode="process",
                       wkc_error_limit=20, terminals=TERMINALS, handwheel=HandwheelSpec(1))
    w = CyclicWorker(cfg)
    w.start()
    try:
        w.enable()
        assert w.wait_for((WorkerState.ENABLED,), timeout_s=5.0) is WorkerState.ENABLED
        _wait(w, lambda: w.snapshot().terminal_counts[1] == 65_500)
        start = float(w.snapshot().reference_position[0])
        w.drain_trace()
        assert w.handwheel(0, HandwheelMode.POSITION, SCALE, (V, A, J, start - 10.0, start + 10.0))
        turned = 0
        for add in (40, 40, -12, 40, 40, 40, -4):                # through 65535 -> 0 and back
            link.control("encoder", slave=3, add=add)
            turned += add
            time.sleep(0.02)
        _wait(w, lambda: w.snapshot().terminal_counts[1] == (65_500 + turned) & 0xFFFF)
        target = start + turned * SCALE
        _wait(w, lambda: abs(float(w.snapshot().reference_position[0]) - target) < 1e-12)
        time.sleep(0.3)
        snap = w.snapshot()
        assert snap.handwheel_state == WheelState.LIVE and snap.state is WorkerState.ENABLED
        ref = w.drain_trace().reference[:, 0]
        v = np.diff(ref) / cfg.ts_s
        a = np.diff(v) / cfg.ts_s
        assert float(np.abs(v).max()) <= V * (1 + 1e-9) and float(np.abs(a).max()) <= A * (1 + 1e-6)
        assert float(np.abs(np.diff(a)).max()) / cfg.ts_s <= J * (1 + 1e-6)
        assert abs(float(ref[-1]) - target) <= 1.0 / DRIVES[0].counts_per_unit
    finally:
        w.stop()
