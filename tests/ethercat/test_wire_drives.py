"""Drives the master was not written against, on real EtherCAT frames: each variant of the
emulated drive (fixed mapping, missing objects, faulted at power-up, ...) and KickCAT's CiA 402
drive simulation, written by others. Each runs the same sequence:

1. ``cnc-ethercat bench`` over the link: to OP, a moving set-point stream, every working
   counter right, back to INIT;
2. the worker (own process): start-up (a drive in FAULT is reset once), enable, a CSP motion
   of both axes that arrives, a fault reset, enable again, stop.

Needs root and network namespaces (skips with the reason otherwise); every namespace, link and
process is removed by its name or pid in the fixtures' teardown.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest

from ethercat.bus import DriveSpec
from ethercat.drive_setup import DriveSetup
from ethercat.emulator.link import EmulatedLink, link_unavailable_reason
from ethercat.soem_access import FRAME_TIMEOUT_ENV
from ethercat.worker import AlarmCode, CyclicWorker, EventCode, ProbeLatch, WorkerConfig, WorkerState
from tests.ethercat.test_wire_link import cosine, run_motion, wait_alarm, wait_until
from tests.ethercat.third_party import KickcatLink, kickcat_unavailable_reason

ROOT = Path(__file__).resolve().parents[2]
REASON = link_unavailable_reason()
pytestmark = [pytest.mark.root,
              pytest.mark.skipif(bool(REASON), reason=f"EtherCAT link tests skipped: {REASON}")]
W = WorkerState


@pytest.fixture(scope="module", autouse=True)
def slow_far_end() -> Iterator[None]:
    """Configuration and SDO frames may wait for a far end that is a process of this (virtual)
    machine: 20 ms for those (not the cyclic ones), here and in the CLI's subprocesses."""
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv(FRAME_TIMEOUT_ENV, "20000")
        yield
    import pysoem

    pysoem.settings.timeouts.ret = 2000


def cli(*args: str, timeout_s: float = 90.0) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "ethercat", *args], capture_output=True, text=True,
                          timeout=timeout_s, cwd=ROOT, env={**os.environ, FRAME_TIMEOUT_ENV: "20000"})


def bench_over(ifname: str) -> dict[str, object]:
    res = cli("bench", ifname, "--seconds", "2", "--json")
    assert res.returncode == 0, res.stderr
    result: dict[str, object] = json.loads(res.stdout)
    # a frame lost on the veth link under a loaded 2-core machine (1 in about 2,000 cycles once)
    # is what the worker tolerates, as in ``motion_and_fault_reset``; a wrong mapping loses all
    assert result["alarms"] == [], result
    # the 2 s of deadlines are covered: the cycles run and those a loaded machine made the worker
    # skip (a busy CI machine ran 1027 of 2000 once); the exchange itself is checked by the WKC
    covered = result["cycles"] + result["missed_cycles"]   # type: ignore[operator]
    assert covered > 1500 and result["cycles"] > 100 and result["expected_wkc"] == 6, result  # type: ignore[operator]
    assert result["wkc_errors"] <= result["cycles"] // 100, result   # type: ignore[operator]
    return result


def drives2(**identity: int) -> tuple[DriveSpec, ...]:
    return tuple(DriveSpec(i, "XY"[i], counts_per_unit=10_000.0, following_error_window=2.0, **identity)
                 for i in range(2))


def motion_and_fault_reset(w: CyclicWorker) -> np.ndarray:
    """Enable, move both axes, fault reset, enable again: returns where the axes arrived."""
    w.wait_for(W.DISABLED, timeout_s=5.0)
    assert not w.snapshot().alarms, [a.message for a in w.snapshot().alarms]
    w.enable()
    w.wait_for(W.ENABLED, timeout_s=5.0)
    q0 = w.snapshot().actual_position.copy()
    q1 = q0 + np.array([2.0, -1.5])
    run_motion(w, cosine(q0, q1, 1.0))
    time.sleep(0.3)                           # settling of the drives' own position loops
    snap = w.snapshot()
    assert snap.state is W.ENABLED, [a.message for a in snap.alarms]
    np.testing.assert_allclose(snap.actual_position, q1, atol=0.01)
    # every drive answers now; a frame lost on the way (the veth link and the emulator share a
    # loaded 2-core machine with the rest of the suite: 4 in 1,522 cycles once) is what the
    # worker tolerates, a wrong mapping would lose every one
    assert snap.wkc == snap.expected_wkc == 6 and snap.wkc_errors <= snap.cycle // 100
    w.disable()
    w.wait_for(W.DISABLED, timeout_s=3.0)
    w.fault_reset()
    w.wait_for(W.DISABLED, timeout_s=3.0)
    w.enable()
    w.wait_for(W.ENABLED, timeout_s=5.0)
    return np.asarray(snap.actual_position)


# ---------------------------------------------------------------------- the emulator's variants
@pytest.fixture(params=["standard", "fixed", "minimal", "picky"])
def variant_link(request: pytest.FixtureRequest) -> Iterator[EmulatedLink]:
    link = EmulatedLink(2, realtime=True, variant=request.param)
    try:
        link.start()
        yield link
    finally:
        link.close()
        link.remove_log()


def test_variant_runs_bench_motion_and_fault_reset(variant_link: EmulatedLink) -> None:
    variant = variant_link.variant
    result = bench_over(variant_link.master_ifname)
    notes = "\n".join(result["bus_notes"])     # type: ignore[arg-type]
    slaves = variant_link.control("status")["slaves"]
    assert [s["al_state"] for s in slaves] == ["INIT", "INIT"], "back to INIT after the bench"   # type: ignore[index]
    expected_notes = {
        "standard": [],
        "fixed": ["refused the PDO mapping", "abort code 0x06010002", "using its own: 0x607A:00 32 bit"],
        "minimal": ["no object 0x60F4: following error computed by the master",
                    "no object 0x603F: error code read by SDO"],
        "picky": ["SDO complete access not used", "expected 01 00 00 16"],
    }[variant]
    for text in expected_notes:
        assert text in notes, notes
    if variant == "standard":
        assert notes == ""
    events = "\n".join(result["events"])      # type: ignore[arg-type]
    if variant == "picky":                     # it powered up in FAULT 0x7500: reset once by the worker
        assert events.count("was in FAULT when the bus came up (error code 0x7500") == 2, events
    else:
        assert "FAULT" not in events, events
    # the drives' process data watchdog at 1 s, as an integrator sets it for a master on a shared
    # machine: this test is about motion and fault reset, and a CI machine once held the master
    # back for over the drives' own 100 ms (their watchdog is tested in test_wire_link)
    setups = {p: DriveSetup(watchdog_ms=1000.0) for p in range(2)}
    cfg = WorkerConfig(drives=drives2(), bus_kind="soem", adapter=variant_link.master_ifname, mode="process",
                       wkc_error_limit=20, buffer_capacity=3000, bus_options=(("setups", setups),))
    w = CyclicWorker(cfg)
    w.start()
    try:
        motion_and_fault_reset(w)
        assert [x["watchdog_ms"] for x in variant_link.control("status")["slaves"]] == [1000.0] * 2  # type: ignore[index]
        # the probe on bit 16 of Y's digital inputs, over the wire: latched in the cycle the
        # emulated drive reports it; refused where 0x60FD is not in the process data (the
        # minimal drive has no such object, the fixed drive's own mapping leaves it out)
        armed = w.arm_probe("Y", 16, True)
        assert armed is (variant in ("standard", "picky")), variant
        if armed:
            wait_until(lambda: w.snapshot().probe.latch is ProbeLatch.ARMED, "not armed in the snapshot")
            variant_link.control("inputs", slave=1, value=1 << 16)
            wait_until(lambda: w.probe_latched() is not None, "the probe did not latch")
            wait_until(lambda: w.snapshot().digital_inputs[1] == 1 << 16, "inputs not in the snapshot")
            assert w.probe_latched() == pytest.approx(tuple(w.snapshot().actual_position), abs=1e-3)
            assert not w.arm_probe("Y", 16, True)           # touching: refused
            variant_link.control("inputs", slave=1, value=0)
            w.disarm_probe()
        # a drive fault now: the error code comes from the process data or, where the drive
        # does not map 0x603F, from an SDO beside the cycle
        variant_link.control("fault", slave=1, code=0x2310)
        w.wait_for(W.FAULT, timeout_s=2.0)
        msg = wait_alarm(w, AlarmCode.DRIVE_FAULT)
        if variant in ("standard", "picky"):
            assert "0x2310" in msg, msg
        else:
            assert "being read from 0x603F" in msg, msg
            wait_until(lambda: any(e.code is EventCode.DRIVE_ERROR_CODE for e in w.events()),
                       "no error code event")
            event = next(e for e in w.events() if e.code is EventCode.DRIVE_ERROR_CODE)
            want = "0x2310" if variant == "fixed" else "could not be read"    # minimal: no 0x603F at all
            assert want in event.message and event.axis == "Y", event
        w.fault_reset()
        w.wait_for(W.DISABLED, timeout_s=3.0)
    finally:
        w.stop()
    assert [s["al_state"] for s in variant_link.control("status")["slaves"]] == ["INIT", "INIT"]  # type: ignore[index]


# ---------------------------------------------------------------------- KickCAT's drives
KREASON = kickcat_unavailable_reason()


@pytest.fixture(scope="module")
def kickcat() -> Iterator[KickcatLink]:
    if KREASON:
        pytest.skip(f"KickCAT link test skipped: {KREASON}")
    link = KickcatLink(2)
    try:
        link.start()
        yield link
    finally:
        link.close()
        print(f"\nKickCAT log ({link.log_path}):\n{link.log()[-600:]}")
        link.remove_log()


def test_kickcat_drives_run_bench_and_motion(kickcat: KickcatLink) -> None:
    result = bench_over(kickcat.master_ifname)
    notes = "\n".join(result["bus_notes"])      # type: ignore[arg-type]
    assert "SDO complete access not used" in notes and "EVS-NET-01" in notes, notes
    print(f"\nKickCAT bench: late {result['late_cycles']} of {result['cycles']}, "
          f"p99 {result['jitter_p99_us']} us\n{notes}")
    cfg = WorkerConfig(drives=drives2(vendor_id=0x29C, product_code=0x03B11002), bus_kind="soem",
                       adapter=kickcat.master_ifname, mode="process", wkc_error_limit=20,
                       buffer_capacity=3000)
    w = CyclicWorker(cfg)
    w.start()
    try:
        motion_and_fault_reset(w)
    finally:
        w.stop()
    # and to OP once more after the way back, as after a reconnect
    bench_over(kickcat.master_ifname)


XY_MACHINE = """[machine]
name = "XY table on KickCAT drives"

[[axes]]
name = "X"
kind = "linear"
drive_position = 0
min = -100.0
max = 100.0
v_max = 50.0
a_max = 500.0
j_max = 10000.0
following_error_window = 2.0

[[axes]]
name = "Y"
kind = "linear"
drive_position = 1
min = -100.0
max = 100.0
v_max = 50.0
a_max = 500.0
j_max = 10000.0
following_error_window = 2.0

[homing]
required = false

[bus]
kind = "soem"
adapter = "{adapter}"

"""


def test_kickcat_configuration_from_its_esi_runs_a_program(kickcat: KickcatLink, tmp_path: Path) -> None:
    """`cnc-ethercat esi` on KickCAT's ESI file, pasted as it is into a machine configuration:
    `cnc-run` runs a program moving both axes through the whole controller on these drives."""
    from tests.ethercat.third_party import KICKCAT_ESI

    res = cli("esi", str(KICKCAT_ESI), "--positions", "0", "1")
    assert res.returncode == 0, res.stderr
    config = tmp_path / "machine.toml"
    config.write_text(XY_MACHINE.format(adapter=kickcat.master_ifname) + res.stdout, encoding="utf-8")
    program = tmp_path / "square.ngc"
    program.write_text("G21 G90\nG1 X2 Y-1.5 F600\nG1 X4 Y0\nG0 X3 Y1\nM2\n", encoding="utf-8")
    run = subprocess.run([sys.executable, "-m", "app.run_cli", str(program), "--config", str(config),
                          "--hardware", "--json", "--state-dir", str(tmp_path / "state")],
                         capture_output=True, text=True, cwd=ROOT, timeout=120,
                         env={**os.environ, FRAME_TIMEOUT_ENV: "20000"})
    assert run.returncode == 0, run.stderr + run.stdout
    result = json.loads(run.stdout)
    assert result["completed"] and result["final_state"] == "idle", result
    np.testing.assert_allclose(result["end_position"], [3.0, 1.0], atol=0.01)
    assert result["limits_ok"], result["limits"]
    bus_lines = [a for a in result["alarms"] if a.startswith("bus: ")]
    assert any("SDO complete access not used" in a for a in bus_lines), result["alarms"]
    # and the live slaves match their description
    check = cli("esi", str(KICKCAT_ESI), "--check", kickcat.master_ifname)
    assert check.returncode == 0 and check.stdout.count("matches its ESI") == 2, check.stdout + check.stderr
