"""The spindle's own drive on a real EtherCAT link: SoemBus maps the emulator's second drive in
cyclic synchronous velocity (controlword, target velocity, mode / statusword, velocity actual,
error code, mode display, written by SDO in PRE-OP) and the worker (its own process, real time)
turns it: the speed read reaches the speed sent, M5 stops and disables it, E-stop quick-stops
it (veth pair in a network namespace, as the other link tests; root)."""

from __future__ import annotations

import time
from collections.abc import Iterator

import pytest

from ethercat.bus import DriveSpec, SpindleDriveSpec
from ethercat.cia402 import Cia402State
from ethercat.drive_model import DriveParams
from ethercat.emulator.link import EmulatedLink, link_unavailable_reason
from ethercat.pdo import VELOCITY_MAPPING
from ethercat.soem_bus import SoemBus
from ethercat.worker import CyclicWorker, SpindleState, WorkerConfig, WorkerState
from tests.ethercat.test_wire_terminals import emulated_link

REASON = link_unavailable_reason()
pytestmark = [pytest.mark.root,
              pytest.mark.skipif(bool(REASON), reason=f"EtherCAT link tests skipped: {REASON}")]

P = DriveParams()
DRIVES = (DriveSpec(0, "X", vendor_id=P.vendor_id, product_code=P.product_code),)
PER_RPM = 10_000.0 / 60.0


@pytest.fixture(scope="module")
def link() -> Iterator[EmulatedLink]:
    yield from emulated_link(())


def _wait(predicate, timeout_s: float = 5.0) -> None:  # type: ignore[no-untyped-def]
    deadline = time.monotonic() + timeout_s
    while not predicate():
        assert time.monotonic() < deadline, "timed out"
        time.sleep(0.01)


def test_soem_bus_maps_the_spindle_drive_in_its_velocity_mode(link: EmulatedLink) -> None:
    bus = SoemBus(DRIVES, adapter=link.master_ifname, spindles=(SpindleDriveSpec(1, PER_RPM, 9),))
    with bus:
        assert bus.slave_mappings[1].same_entries(VELOCITY_MAPPING)
        assert bus.expected_wkc == 3 * 2
        assert int(bus.spindle_modes_display[0]) == 9
        assert bus.exchange() == bus.expected_wkc


@pytest.mark.parametrize("mode", [9, 3])
def test_the_worker_turns_the_emulated_spindle_drive_and_stops_it(link: EmulatedLink, mode: int) -> None:
    cfg = WorkerConfig(drives=DRIVES, bus_kind="soem", adapter=link.master_ifname, mode="process",
                       wkc_error_limit=20, spindle=SpindleDriveSpec(1, PER_RPM, mode))
    w = CyclicWorker(cfg)
    w.start()
    try:
        w.enable()
        assert w.wait_for((WorkerState.ENABLED,), timeout_s=5.0) is WorkerState.ENABLED
        assert w.spindle(3000.0, 20_000.0)
        _wait(lambda: abs(w.snapshot().spindle_rpm_actual - 3000.0) < 3.0)
        s = w.snapshot()
        assert s.spindle_state == SpindleState.RUNNING
        assert s.spindle_drive_state is Cia402State.OPERATION_ENABLED
        assert w.spindle(-1500.0, 20_000.0)
        _wait(lambda: abs(w.snapshot().spindle_rpm_actual + 1500.0) < 3.0)
        assert w.spindle(0.0, 20_000.0)
        _wait(lambda: w.snapshot().spindle_state == SpindleState.OFF)
        _wait(lambda: w.snapshot().spindle_drive_state is not Cia402State.OPERATION_ENABLED)
        assert abs(w.snapshot().spindle_rpm_actual) < 3.0
        assert w.spindle(2000.0, 20_000.0)
        _wait(lambda: abs(w.snapshot().spindle_rpm_actual - 2000.0) < 3.0)
        w.estop("test")
        _wait(lambda: abs(w.snapshot().spindle_rpm_actual) < 1.0)
        assert w.snapshot().spindle_state == SpindleState.OFF
    finally:
        w.stop()
