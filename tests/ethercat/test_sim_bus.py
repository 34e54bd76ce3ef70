"""SimBus: the bus contract, plus its fault injection."""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np
import pytest

from ethercat.bus import DriveSpec, make_bus
from ethercat.cia402 import Cia402State
from ethercat.drive_model import DriveParams
from ethercat.errors import ConfigurationError
from ethercat.sim_bus import SimBus, probe_surface_value
from tests.ethercat.bus_contract import CONTRACT_DRIVES, BusContractTests, enable_all, states_of


class TestSimBusContract(BusContractTests):
    @pytest.fixture
    def bus(self) -> Iterator[SimBus]:
        b = SimBus(CONTRACT_DRIVES)
        yield b
        b.close()


@pytest.fixture
def bus() -> Iterator[SimBus]:
    b = SimBus(CONTRACT_DRIVES)
    b.open()
    yield b
    b.close()


def run(bus: SimBus, n: int, cw: int | None = 0x0F) -> list[int]:
    wkcs = []
    for _ in range(n):
        if cw is not None:
            bus.controlword[:] = cw
        wkcs.append(bus.exchange())
    return wkcs


def test_registry_and_unknown_backend() -> None:
    b = make_bus("sim", CONTRACT_DRIVES, cycle_time_s=0.002)
    assert isinstance(b, SimBus) and b.cycle_time_s == 0.002
    with pytest.raises(ConfigurationError, match="unknown bus kind"):
        make_bus("canbus", CONTRACT_DRIVES)


def test_drive_list_validated() -> None:
    with pytest.raises(ConfigurationError, match="no drives"):
        SimBus(())
    with pytest.raises(ConfigurationError, match="duplicate drive positions"):
        SimBus((DriveSpec(0, "X"), DriveSpec(0, "Y")))
    with pytest.raises(ConfigurationError, match="direction"):
        DriveSpec(0, "X", direction=0)


def test_initial_positions_and_identity_from_config() -> None:
    drives = (DriveSpec(0, "X", vendor_id=0x99, product_code=0x77),)
    with SimBus(drives, initial_positions_counts=[12345.0]) as b:
        assert b.position_actual[0] == 12345
        assert b.target_position[0] == 12345
        assert (b.slaves()[0].vendor_id, b.slaves()[0].product_code) == (0x99, 0x77)


def test_drive_fault_and_reset(bus: SimBus) -> None:
    enable_all(bus)
    bus.inject_drive_fault(1, 0x2310)
    run(bus, 20)
    assert states_of(bus) == [Cia402State.OPERATION_ENABLED, Cia402State.FAULT]
    assert bus.error_code[1] == 0x2310
    run(bus, 1, 0x00)
    run(bus, 2, 0x80)                                  # inputs show the reaction one cycle later
    assert states_of(bus)[1] is Cia402State.SWITCH_ON_DISABLED
    assert bus.error_code[1] == 0


def test_following_error_fault_by_jam() -> None:
    params = DriveParams.for_axis(10_000.0, following_error_window_units=0.01)
    b = SimBus(CONTRACT_DRIVES, drive_params=params)
    with b:
        enable_all(b)
        b.inject_following_error(0)
        x0 = int(b.position_actual[0])
        for k in range(200):
            b.target_position[0] = x0 + 50 * k
            b.controlword[:] = 0x0F
            b.exchange()
        assert states_of(b)[0] is Cia402State.FAULT
        assert b.error_code[0] == 0x8611


def test_lost_frames_keep_inputs_and_return_minus_one(bus: SimBus) -> None:
    enable_all(bus)
    before = bus.statusword.copy()
    bus.drop_frames(3)
    bus.controlword[:] = 0x06                          # not delivered while frames are lost
    assert run(bus, 3, None) == [-1, -1, -1]
    np.testing.assert_array_equal(bus.statusword, before)
    assert run(bus, 2, None) == [bus.expected_wkc] * 2
    assert states_of(bus)[0] is Cia402State.READY_TO_SWITCH_ON


def test_slave_loss_lowers_wkc_then_watchdog_fault(bus: SimBus) -> None:
    enable_all(bus)
    bus.lose_slave(1)
    assert bus.lost_slaves() == (1,)
    assert bus.slaves()[1].state == "SAFE-OP" and bus.slaves()[1].al_status_code == 0x001B
    wkcs = run(bus, 150)
    assert set(wkcs) == {bus.expected_wkc - 3}
    assert bus.models[1].state is Cia402State.FAULT and bus.models[1].error_code == 0x8700
    bus.restore_slave(1)
    assert run(bus, 2) == [bus.expected_wkc] * 2
    assert bus.error_code[1] == 0x8700


def test_inject_by_name(bus: SimBus) -> None:
    bus.inject("drop_frames", 0, 2)
    assert run(bus, 3) == [-1, -1, bus.expected_wkc]
    with pytest.raises(ConfigurationError):
        bus.inject("meteor")


def test_digital_io_in_the_process_data(bus: SimBus) -> None:
    """0x60FE:1 reaches the drive with the frame; 0x60FD comes back with it."""
    bus.digital_outputs[0] = 0b101
    assert bus.sdo_read(0, 0x60FE, 1, "<I") == 0
    bus.exchange()
    assert bus.sdo_read(0, 0x60FE, 1, "<I") == 0b101
    bus.models[1].digital_inputs = 0b10
    bus.exchange()
    assert list(bus.digital_inputs) == [0, 0b10]


def test_the_simulated_probe_touches_a_surface_through_the_inputs_of_its_drive() -> None:
    """Axis 1 (counts running against its units) watched, the probe wired to bit 3 of drive
    0: the bit is on while axis 1 is at or below the level, and off again above it; "above"
    turns the rule round; inject() carries the same through one integer."""
    drives = (DriveSpec(0, "X"), DriveSpec(1, "Z", counts_per_unit=1000.0, direction=-1))
    with SimBus(drives, initial_positions_counts=[0.0, 2000.0]) as b:   # Z at -2 mm
        b.set_probe_surface(1, 3, -1.5, below=True, input_drive=0)
        b.exchange()
        b.exchange()
        assert b.digital_inputs[0] & 0b1000 and not b.digital_inputs[1]
        b.set_probe_surface(1, 3, -1.5, below=False, input_drive=0)
        b.exchange()
        b.exchange()
        assert not b.digital_inputs[0] & 0b1000
        b.inject("probe_surface", 1, probe_surface_value(5, -2.5, False))        # on its own drive
        b.exchange()
        b.exchange()
        assert b.digital_inputs[1] == 1 << 5 and not b.digital_inputs[0] & 0b1000
        b.inject("probe_off", 0, 0)
        b.exchange()
        b.exchange()
        assert b.digital_inputs[1] == 0
        with pytest.raises(ConfigurationError, match="no such drive or bit"):
            b.set_probe_surface(1, 40, 0.0)
