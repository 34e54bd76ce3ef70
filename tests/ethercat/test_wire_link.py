"""Real EtherCAT frames on this machine: SoemBus (pysoem) + the worker against the software
slave on the far end of a veth pair in a network namespace.

Each fixture creates a namespace and a veth pair with names unique to this process, runs
`python -m ethercat emulate s0 --drives N` inside the namespace and, in its teardown
(always), stops the emulator by its pid and deletes the link and the namespace by name.
Skips with the reason when not root or `ip netns` does not work.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from collections.abc import Callable, Iterator

import numpy as np
import pytest

from ethercat.bus import DriveSpec, make_bus
from ethercat.cia402 import Cia402State
from ethercat.drive_model import DriveParams
from ethercat.drive_setup import DriveSetup, MappingPolicy, StartupStep
from ethercat.emulator.link import EmulatedLink, link_unavailable_reason
from ethercat.errors import AdapterError, AlStateError, SdoAbortError, SlaveIdentityError
from ethercat.pdo import CSP_MAPPING, PdoEntry, PdoMapping
from ethercat.soem_access import FRAME_TIMEOUT_ENV
from ethercat.soem_bus import SoemBus
from ethercat.worker import AlarmCode, CyclicWorker, EventCode, WorkerConfig, WorkerEvent, WorkerState
from tests.ethercat.bus_contract import CONTRACT_DRIVES, BusContractTests, enable_all

REASON = link_unavailable_reason()
pytestmark = [pytest.mark.root,
              pytest.mark.skipif(bool(REASON), reason=f"EtherCAT link tests skipped: {REASON}")]

P = DriveParams()
DRIVES3 = tuple(DriveSpec(i, "XYZ"[i], counts_per_unit=10_000.0, following_error_window=0.5,
                          vendor_id=P.vendor_id, product_code=P.product_code) for i in range(3))
W = WorkerState


@pytest.fixture(scope="module", autouse=True)
def slow_far_end() -> Iterator[None]:
    """The slaves here are a process of the same (virtual) machine: when it is not scheduled
    for a few ms a configuration or SDO frame outlives SOEM's 2 ms default and the step fails.
    20 ms for those frames (not the cyclic ones), also for the CLI's subprocesses."""
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv(FRAME_TIMEOUT_ENV, "20000")
        yield
    import pysoem

    pysoem.settings.timeouts.ret = 2000  # SOEM's default, for whatever runs after this module


def _link(n_drives: int) -> Iterator[EmulatedLink]:
    link = EmulatedLink(n_drives, realtime=True)
    try:
        link.start()
        yield link
    finally:
        link.close()
        print(f"\nemulator log ({link.log_path}):\n{link.log()}")
        link.remove_log()


@pytest.fixture(scope="module")
def link3() -> Iterator[EmulatedLink]:
    yield from _link(3)


def cli(*args: str, timeout_s: float = 60.0) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "ethercat", *args], capture_output=True, text=True,
                          timeout=timeout_s, cwd=os.path.dirname(os.path.dirname(os.path.dirname(__file__))))


def emulator_slaves(link: EmulatedLink) -> list[dict[str, object]]:
    return list(link.control("status")["slaves"])  # type: ignore[arg-type]


# ---------------------------------------------------------------------- cnc-ethercat
def test_cli_slaves_pdos_upload_download(link3: EmulatedLink) -> None:
    ifname = link3.master_ifname
    res = cli("slaves", ifname, "--json")
    assert res.returncode == 0, res.stderr
    slaves = json.loads(res.stdout)
    assert [s["position"] for s in slaves] == [0, 1, 2]
    assert all(s["vendor_id"] == P.vendor_id and s["product_code"] == P.product_code for s in slaves)
    assert all(s["state"] == "PRE-OP" and s["name"] == "CNC-Servo-402" for s in slaves)
    res = cli("slaves", ifname)
    assert "vendor 0x00000A5E" in res.stdout and "PRE-OP" in res.stdout
    res = cli("pdos", ifname)
    assert res.returncode == 0, res.stderr
    assert "SM2 RxPDO (outputs) 0x1600" in res.stdout and "0x6040:00  16 bit  controlword" in res.stdout
    assert res.stdout.count("slave ") == 3
    assert cli("download", ifname, "1", "0x6065", "0", "5000").returncode == 0
    res = cli("upload", ifname, "1", "0x6065", "0")
    assert res.returncode == 0 and res.stdout.split() == ["0x00001388", "5000"]
    res = cli("upload", ifname, "0", "0x1008", "0")
    assert res.stdout.strip() == "CNC-Servo-402"
    res = cli("upload", ifname, "0", "0x2FFF", "0")
    assert res.returncode == 1 and "abort code 0x06020000" in res.stderr
    res = cli("slaves", "nosuchif0")
    assert res.returncode == 1 and "nosuchif0" in res.stderr


# ---------------------------------------------------------------------- SoemBus start-up
def test_identity_mismatch_names_position_and_both_identities(link3: EmulatedLink) -> None:
    drives = list(DRIVES3)
    drives[1] = DriveSpec(1, "Y", vendor_id=0x0000_0002, product_code=0x1234_5678)
    bus = SoemBus(drives, adapter=link3.master_ifname)
    with pytest.raises(SlaveIdentityError) as exc:
        bus.open()
    msg = str(exc.value)
    assert "slave 1" in msg and "0x00000002" in msg and "0x12345678" in msg
    assert "0x00000A5E" in msg and "0x04020001" in msg
    assert not bus.is_open


def test_pdo_mapping_refused_with_policy_write_is_a_clear_error(link3: EmulatedLink) -> None:
    bad = PdoMapping(CSP_MAPPING.rx + (PdoEntry(0x6041, 0, 16),), CSP_MAPPING.tx)   # statusword is ro
    setups = {p: DriveSetup(mapping=bad, policy=MappingPolicy.WRITE) for p in range(3)}
    bus = SoemBus(DRIVES3, adapter=link3.master_ifname, setups=setups)
    with pytest.raises(SdoAbortError) as exc:
        bus.open()
    assert exc.value.position == 0 and exc.value.index == 0x1600
    assert exc.value.abort_code == 0x06040041, str(exc.value)
    assert str(exc.value).startswith("configuring the PDO mapping: SDO 0x1600:0 on slave 0 (CNC-Servo-402, "
                                     "vendor 0x00000A5E, product 0x04020001) aborted")
    assert exc.value.step is StartupStep.MAPPING
    assert not bus.is_open


def test_pdo_mapping_refused_falls_back_to_the_drives_own(link3: EmulatedLink) -> None:
    """Adapting (the default): the refused mapping is undone and the drive runs with what it had,
    which carries the mandatory objects; the note names the refusal and the mapping used."""
    bad = PdoMapping(CSP_MAPPING.rx + (PdoEntry(0x6041, 0, 16),), CSP_MAPPING.tx)
    bus = SoemBus(DRIVES3, adapter=link3.master_ifname, mappings={(P.vendor_id, P.product_code): bad})
    with bus:
        assert [m.objects for m in bus.slave_mappings.values()] == [{0x6040, 0x607A, 0x6041, 0x6064}] * 3
        notes = [n for n in bus.notes if "refused the PDO mapping" in n]
        assert len(notes) == 3 and "0x06040041" in notes[0] and "using its own" in notes[0]
        assert [s["rx_mapping"] for s in emulator_slaves(link3)] == [["0x60400010", "0x607A0020"]] * 3
        enable_all(bus)
        assert bus.exchange() == bus.expected_wkc


def test_op_refused_without_sync0_names_slave_and_al_status_code(link3: EmulatedLink) -> None:
    bus = SoemBus(DRIVES3, adapter=link3.master_ifname, dc=False, op_timeout_s=1.0)
    with pytest.raises(AlStateError) as exc:
        bus.open()
    assert exc.value.al_status_code == 0x0030 and exc.value.position == 0
    msg = str(exc.value)
    assert "slave 0" in msg and "slave 2" in msg and "SAFE-OP + ERROR" in msg and "0x0030" in msg
    assert not bus.is_open
    assert [s["al_state"] for s in emulator_slaves(link3)] == ["INIT"] * 3


def test_missing_adapter_is_a_connection_error() -> None:
    with pytest.raises(AdapterError) as exc:
        SoemBus(DRIVES3, adapter="nosuchif0").open()
    assert isinstance(exc.value, ConnectionError) and "nosuchif0" in str(exc.value)


def test_open_maps_pdos_sync0_on_every_slave_op_and_shutdown_to_init(link3: EmulatedLink) -> None:
    bus = SoemBus(DRIVES3, adapter=link3.master_ifname)
    with bus:
        assert bus.expected_wkc == 9
        assert [s.state for s in bus.slaves()] == ["OP"] * 3
        emu = emulator_slaves(link3)
        rx = [f"0x{e.value:08X}" for e in CSP_MAPPING.rx]
        tx = [f"0x{e.value:08X}" for e in CSP_MAPPING.tx]
        for s in emu:
            assert s["al_state"] == "OP" and s["rx_mapping"] == rx and s["tx_mapping"] == tx
            assert s["sync0_active"] and s["sync0_cycle_ns"] == 1_000_000, "SYNC0 on every slave"
        # round trip of one cycle (LRW + DC FRMW) on the emulated link
        rtt = []
        for _ in range(500):
            t0 = time.perf_counter()
            assert bus.exchange() == 9
            rtt.append(time.perf_counter() - t0)
        np.testing.assert_array_equal(bus.target_position, bus.position_actual)
        print(f"\nround trip (3 slaves): median {np.median(rtt) * 1e6:.0f} us, "
              f"p99 {np.percentile(rtt, 99) * 1e6:.0f} us")
    assert [s["al_state"] for s in emulator_slaves(link3)] == ["INIT"] * 3
    assert not any(s["sync0_active"] for s in emulator_slaves(link3))


def test_watchdog_when_process_data_stops(link3: EmulatedLink) -> None:
    with SoemBus(DRIVES3, adapter=link3.master_ifname) as bus:
        enable_all(bus)
        time.sleep(0.3)                                     # no frames: SM watchdog (100 ms)
        states = bus.al_states()
        assert states == (("SAFE-OP", 0x001B),) * 3
        for _ in range(40):
            bus.exchange()
            time.sleep(0.001)
        assert all(s == Cia402State.FAULT for s in
                   (Cia402State[str(x["drive_state"])] for x in emulator_slaves(link3)))
        assert all(x["error_code"] == 0x8700 for x in emulator_slaves(link3))


def test_configured_watchdog_is_written_and_rides_out_a_stall(link3: EmulatedLink) -> None:
    setups = {p: DriveSetup(watchdog_ms=600.0) for p in range(3)}
    with SoemBus(DRIVES3, adapter=link3.master_ifname, setups=setups) as bus:
        assert [x["watchdog_ms"] for x in emulator_slaves(link3)] == pytest.approx([600.0] * 3)
        for word in (0x00,) * 3 + (0x80,) * 3:              # a fault left by the test before: reset
            bus.controlword[:] = word
            bus.exchange()
        enable_all(bus)
        t_last = time.monotonic()
        time.sleep(0.25)                                    # 2.5x the drives' own 100 ms
        states = bus.al_states()
        gap_s = time.monotonic() - t_last
        if gap_s < 0.55:                                    # a stall of this run's machine may be longer
            assert states == (("OP", 0),) * 3, f"{states} after {gap_s * 1e3:.0f} ms without process data"
        for _ in range(20):
            bus.exchange()
            time.sleep(0.001)
        time.sleep(0.9)                                     # past the 600 ms: SAFE-OP, as at 100 ms
        assert bus.al_states() == (("SAFE-OP", 0x001B),) * 3
    # the registers keep what was written until a power cycle: the drives' 100 ms again
    again = {p: DriveSetup(watchdog_ms=100.0) for p in range(3)}
    with SoemBus(DRIVES3, adapter=link3.master_ifname, setups=again):
        assert [x["watchdog_ms"] for x in emulator_slaves(link3)] == pytest.approx([100.0] * 3)


def test_lost_slave_comes_back_and_is_recovered(link3: EmulatedLink) -> None:
    setups = {2: DriveSetup(watchdog_ms=250.0)}
    with SoemBus(DRIVES3, adapter=link3.master_ifname, setups=setups) as bus:
        assert emulator_slaves(link3)[2]["watchdog_ms"] == pytest.approx(250.0)
        link3.control("lose", slave=2)
        assert [bus.exchange() for _ in range(3)] == [6, 6, 6]
        assert bus.lost_slaves() == (2,)
        link3.control("restore", slave=2)              # back, power cycled: INIT, no address
        assert bus.exchange() == 6
        assert bus.recover_slaves() == (2,)
        wkcs = []
        for _ in range(50):
            wkcs.append(bus.exchange())
            time.sleep(0.001)
        assert wkcs[-1] == 9 and bus.lost_slaves() == ()
        assert [s.state for s in bus.slaves()] == ["OP"] * 3
        assert emulator_slaves(link3)[2]["sync0_active"]
        # its settings again after the power cycle (which set 0x0420 back to 100 ms)
        assert emulator_slaves(link3)[2]["watchdog_ms"] == pytest.approx(250.0)
    with SoemBus(DRIVES3, adapter=link3.master_ifname, setups={2: DriveSetup(watchdog_ms=100.0)}):
        pass                                        # the link's drives as the other tests find them


# ---------------------------------------------------------------------- SoemBus + worker
def cosine(q0: np.ndarray, q1: np.ndarray, duration_s: float) -> np.ndarray:
    n = int(round(duration_s / 0.001))
    u = np.arange(1, n + 1) / n
    return q0 + (q1 - q0) * ((1 - np.cos(np.pi * u)) / 2)[:, None]


def run_motion(w: CyclicWorker, q: np.ndarray, timeout_s: float = 10.0) -> None:
    k = 0
    t_end = time.monotonic() + timeout_s
    while k < len(q):
        k += w.push(q[k:])
        time.sleep(0.02)
        assert time.monotonic() < t_end, "motion did not finish"
    while w.snapshot().buffer_level > 0:
        time.sleep(0.02)
        assert time.monotonic() < t_end, "buffer did not drain"
    time.sleep(0.2)


def wait_until(predicate: Callable[[], bool], what: str, timeout_s: float = 3.0) -> None:
    t_end = time.monotonic() + timeout_s
    while not predicate():
        assert time.monotonic() < t_end, what
        time.sleep(0.01)


def wait_alarm(w: CyclicWorker, code: AlarmCode, timeout_s: float = 3.0) -> str:
    t_end = time.monotonic() + timeout_s
    while time.monotonic() < t_end:
        for a in w.snapshot().alarms:
            if a.code is code:
                return a.message
        time.sleep(0.01)
    raise AssertionError(f"no {code.name} alarm; alarms: {[a.message for a in w.snapshot().alarms]}")


def test_worker_csp_fault_reset_lost_slave_shutdown(link3: EmulatedLink) -> None:
    cfg = WorkerConfig(drives=DRIVES3, bus_kind="soem", adapter=link3.master_ifname, mode="process",
                       wkc_error_limit=20, buffer_capacity=3000)
    w = CyclicWorker(cfg)
    w.start()
    try:
        snap = w.snapshot()
        assert snap.expected_wkc == 9
        # a FAULT left by an earlier session is reset once by the worker as it starts
        w.wait_for(W.DISABLED, timeout_s=3.0)
        assert w.state() is W.DISABLED and not w.snapshot().alarms
        # ---- enable and a CSP motion of all three axes
        w.enable()
        w.wait_for(W.ENABLED, timeout_s=5.0)
        q0 = w.snapshot().actual_position.copy()
        q1 = q0 + np.array([5.0, -3.0, 2.0])
        w.reset_tracking()
        run_motion(w, cosine(q0, q1, 1.5))
        snap = w.snapshot()
        assert snap.state is W.ENABLED, [a.message for a in snap.alarms]
        np.testing.assert_allclose(snap.actual_position, q1, atol=1e-3)
        counts = [s["position_actual"] for s in emulator_slaves(link3)]
        np.testing.assert_allclose(counts, np.rint(q1 * 10_000), atol=10)      # arrived at the drives
        assert snap.tracking.samples >= 1400
        assert 0.0 < max(snap.tracking.rmse) < 0.05, snap.tracking
        print(f"\ntracking RMSE per axis (mm): {snap.tracking.rmse}, wkc errors {snap.wkc_errors}")
        # ---- a drive fault: quick stop of all, alarm, fault reset, resume
        link3.control("fault", slave=1, code=0x2310)
        w.wait_for(W.FAULT, timeout_s=2.0)
        msg = wait_alarm(w, AlarmCode.DRIVE_FAULT)
        assert "axis Y" in msg and "0x2310" in msg
        time.sleep(0.1)
        others = [emulator_slaves(link3)[k]["drive_state"] for k in (0, 2)]
        assert all(s in ("QUICK_STOP_ACTIVE", "SWITCH_ON_DISABLED") for s in others), others
        w.fault_reset()
        w.wait_for(W.DISABLED, timeout_s=3.0)
        w.enable()
        w.wait_for(W.ENABLED, timeout_s=5.0)
        here = w.snapshot().actual_position.copy()
        run_motion(w, cosine(here, q0, 1.0))
        np.testing.assert_allclose(w.snapshot().actual_position, q0, atol=1e-3)
        # ---- a slave is lost: alarms, quick stop, the worker keeps running
        link3.control("lose", slave=2)
        msg = wait_alarm(w, AlarmCode.WORKING_COUNTER)
        assert "instead of 9" in msg and "[2]" in msg, msg
        assert "slave 2 (axis Z) lost" in wait_alarm(w, AlarmCode.SLAVE_LOST)
        time.sleep(0.2)
        snap = w.snapshot()
        assert w.running and snap.state is not W.ERROR and snap.cycle > 0
        assert snap.wkc == 6 and snap.lost_slaves == (2,)
        # ---- it comes back power cycled (INIT, no address): the worker's recover_slaves()
        # (helper thread, every 0.1 s) re-configures it to OP while the cycle runs on
        link3.control("restore", slave=2)
        def recovered() -> list[WorkerEvent]:
            return [e for e in w.events() if e.code is EventCode.SLAVE_RECOVERED]

        wait_until(lambda: bool(recovered()), "no SLAVE_RECOVERED event", timeout_s=5.0)
        (event,) = recovered()
        assert event.code is EventCode.SLAVE_RECOVERED and "re-configured to OP" in event.message, event
        wait_until(lambda: w.snapshot().wkc == 9 and w.snapshot().lost_slaves == (), "wkc not back to 9")
        assert emulator_slaves(link3)[2]["al_state"] == "OP" and emulator_slaves(link3)[2]["sync0_active"]
        w.fault_reset()
        w.wait_for(W.DISABLED, timeout_s=3.0)
        w.enable()
        w.wait_for(W.ENABLED, timeout_s=5.0)
        here = w.snapshot().actual_position.copy()
        run_motion(w, cosine(here, here + np.array([0.0, 0.0, 1.0]), 0.5))
        np.testing.assert_allclose(w.snapshot().actual_position, here + [0.0, 0.0, 1.0], atol=1e-3)
    finally:
        w.stop()
        states = [s["al_state"] for s in emulator_slaves(link3)]
        link3.control("restore", slave=2)             # in case it is still lost (test failed)
    # ---- shutdown: every slave was taken back to INIT
    assert states == ["INIT"] * 3, states


# ---------------------------------------------------------------------- contract
@pytest.fixture(scope="module")
def link2() -> Iterator[EmulatedLink]:
    yield from _link(len(CONTRACT_DRIVES))


class TestSoemBusContract(BusContractTests):
    tolerated_lost_frames = 7  # 1 %: the emulator is a process of this VM (see bus_contract.py)

    @pytest.fixture
    def bus(self, link2: EmulatedLink) -> Iterator[SoemBus]:
        b = make_bus("soem", CONTRACT_DRIVES, adapter=link2.master_ifname)
        assert isinstance(b, SoemBus)
        yield b
        b.close()


# ---------------------------------------------------------------------- bench
def test_cli_bench_on_the_emulated_link(link3: EmulatedLink) -> None:
    res = cli("bench", link3.master_ifname, "--seconds", "2", "--json", timeout_s=90)
    assert res.returncode == 0, res.stderr
    figures = json.loads(res.stdout)
    print(f"\ncnc-ethercat bench {link3.master_ifname} --seconds 2: {figures}")
    assert figures["bus"] == "soem" and figures["drives"] == 3
    assert figures["expected_wkc"] == 9
    assert figures["cycles"] > 1000
    assert figures["period_mean_us"] < 1500        # 1000 us cycle; loose: the machine is shared
