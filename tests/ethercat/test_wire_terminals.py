"""Terminals on a real EtherCAT link: SoemBus (pysoem) against the project's emulator with two
drives and a coupler, a digital input and a digital output terminal behind them (veth pair in a
network namespace, as the other link tests; root).

The terminals have no mailbox: SOEM maps them from their SII PDO categories, as it maps real
EL1008/EL2008 terminals. An input set in the emulated slave reaches the bus within two cycles;
an output written reaches the slave; a terminal of another type is refused naming the slave."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from ethercat.bus import DriveSpec
from ethercat.drive_model import DriveParams
from ethercat.emulator.link import EmulatedLink, link_unavailable_reason
from ethercat.errors import SlaveIdentityError
from ethercat.soem_access import FRAME_TIMEOUT_ENV
from ethercat.soem_bus import SoemBus
from ethercat.terminals import TerminalSpec

REASON = link_unavailable_reason()
pytestmark = [pytest.mark.root,
              pytest.mark.skipif(bool(REASON), reason=f"EtherCAT link tests skipped: {REASON}")]

P = DriveParams()
DRIVES = tuple(DriveSpec(i, "XY"[i], vendor_id=P.vendor_id, product_code=P.product_code) for i in range(2))
TERMINALS = (TerminalSpec(2, "EK1100"), TerminalSpec(3, "EL1008"), TerminalSpec(4, "EL2008"))


def emulated_link(terminals: tuple[str, ...]) -> Iterator[EmulatedLink]:
    """Two emulated drives and ``terminals`` behind them on a link, for a module's tests (the
    emulator's log printed at the end)."""
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv(FRAME_TIMEOUT_ENV, "20000")
        lk = EmulatedLink(2, realtime=True, terminals=terminals)
        try:
            lk.start()
            yield lk
        finally:
            lk.close()
            print(f"\nemulator log ({lk.log_path}):\n{lk.log()}")
            lk.remove_log()
    import pysoem

    pysoem.settings.timeouts.ret = 2000


@pytest.fixture(scope="module")
def link() -> Iterator[EmulatedLink]:
    yield from emulated_link(("EK1100", "EL1008", "EL2008"))


def test_terminals_come_up_beside_the_drives_and_carry_inputs_and_outputs(link: EmulatedLink) -> None:
    bus = SoemBus(DRIVES, adapter=link.master_ifname, terminals=TERMINALS)
    with bus:
        names = [(s.position, s.vendor_id, s.product_code) for s in bus.slaves()]
        assert names[2:] == [(2, 2, 0x044C2C52), (3, 2, 0x03F03052), (4, 2, 0x07D83052)]
        # two drives (LRW: 3 each), the input terminal (1) and the output terminal (2)
        assert bus.expected_wkc == 3 * 2 + 1 + 2
        for value in (0b1000_0001, 0b0110_0000, 0):
            link.control("inputs", slave=3, value=value)
            seen = []
            for _ in range(2):
                assert bus.exchange() == bus.expected_wkc
                seen.append(int(bus.terminal_inputs[1]))
            assert seen[-1] == value, seen
        bus.terminal_outputs[2] = 0b0101_1010
        for _ in range(3):
            bus.exchange()
        status = link.control("status")["slaves"]
        assert status[4]["terminal"] == "EL2008" and status[4]["outputs"] == 0b0101_1010


def test_a_terminal_of_another_type_is_refused_naming_the_slave(link: EmulatedLink) -> None:
    wrong = (TerminalSpec(2, "EK1100"), TerminalSpec(3, "EL1008"), TerminalSpec(4, "EL2004"))
    bus = SoemBus(DRIVES, adapter=link.master_ifname, terminals=wrong)
    with pytest.raises(SlaveIdentityError, match="slave 4"):
        bus.open()
    bus.close()


def test_the_e_stop_chain_on_a_terminal_stops_the_drives_over_the_link(link: EmulatedLink) -> None:
    """The worker on the real link, the E-stop chain on the EL1008's channel 0: enabled while it
    is closed, quick stop when the emulated contact opens, no enable until it closes."""
    import time

    from ethercat.errors import WorkerError
    from ethercat.worker import AlarmCode, CyclicWorker, InputWatch, WatchAction, WorkerConfig, WorkerState

    chain = InputWatch(WatchAction.ESTOP_CHAIN, len(DRIVES) + 1, 0, False, name="estop_chain_ok")
    link.control("inputs", slave=3, value=0b1)
    cfg = WorkerConfig(drives=DRIVES, bus_kind="soem", adapter=link.master_ifname, mode="process",
                       wkc_error_limit=20, terminals=TERMINALS, watches=(chain,))
    w = CyclicWorker(cfg)
    w.start()
    try:
        w.enable()
        assert w.wait_for((WorkerState.ENABLED,), timeout_s=5.0) is WorkerState.ENABLED
        link.control("inputs", slave=3, value=0)
        deadline = time.monotonic() + 2.0
        while w.state() is WorkerState.ENABLED and time.monotonic() < deadline:
            time.sleep(0.005)
        snap = w.snapshot()
        assert snap.state is WorkerState.QUICK_STOP and snap.watches_active == (True,)
        assert any(a.code is AlarmCode.ESTOP_CHAIN for a in snap.alarms)
        w.fault_reset()
        with pytest.raises(WorkerError, match="the E-stop chain is open"):
            w.enable()
        link.control("inputs", slave=3, value=0b1)
        time.sleep(0.05)
        w.fault_reset()
        w.enable()
        assert w.wait_for((WorkerState.ENABLED,), timeout_s=5.0) is WorkerState.ENABLED
    finally:
        w.stop()
