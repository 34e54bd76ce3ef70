"""Terminals beside the drives, the loop's watched inputs and homing to switches, on the
simulated bus with the worker stepped by hand (simulated time)."""

from __future__ import annotations

import struct

import numpy as np
import pytest

from ethercat.bus import DriveSpec
from ethercat.errors import ConfigurationError, WorkerError
from ethercat.sim_bus import SimBus
from ethercat.sim_io import SimSwitch, input_value
from ethercat.terminals import (
    TERMINAL_TYPES,
    TerminalIo,
    TerminalKind,
    TerminalSpec,
    analog_channels,
    analog_word,
    type_of_identity,
)
from ethercat.worker import (
    AlarmCode,
    CyclicWorker,
    HomingState,
    HomingStep,
    InputWatch,
    SwitchHoming,
    WatchAction,
    WorkerConfig,
    WorkerState,
)

TERMINALS = (TerminalSpec(2, "EK1100"), TerminalSpec(3, "EL1008"), TerminalSpec(4, "EL2008"),
             TerminalSpec(5, "EL5101"))
DRIVES = (DriveSpec(0, "X"), DriveSpec(1, "Z", direction=-1))
IN, OUT = 2 + 1, 2 + 2          # input words of the EL1008 / EL2008 (after the two drives)
COUNTS = 10_000.0


def test_beckhoff_identities_follow_the_type_number() -> None:
    """EL terminals are (type number << 16) | 0x3052, the EK1100 0x044C2C52 (vendor 2), and
    each is found again by its identity."""
    for name, t in TERMINAL_TYPES.items():
        assert t.vendor_id == 2
        if name.startswith("EL"):
            assert t.product_code == int(name[2:]) << 16 | 0x3052
        assert type_of_identity(t.vendor_id, t.product_code) is t
    assert TERMINAL_TYPES["EK1100"].product_code == 0x044C2C52
    assert TERMINAL_TYPES["EL1008"].product_code == 0x03F03052
    assert TERMINAL_TYPES["EL2008"].product_code == 0x07D83052
    assert TERMINAL_TYPES["EL5101"].product_code == 0x13ED3052


def test_process_images_are_the_default_pdo_assignments() -> None:
    """Bytes per direction and the working counter of one LRW, as the ESI's default PDOs
    (EL1008: 8 x 1 bit in; EL2008: 8 x 1 bit out; EL5101: status u8, value u16, latch u16 in,
    control u8, value u16 out; EK1100: none)."""
    got = {n: (TERMINAL_TYPES[n].rx_bytes, TERMINAL_TYPES[n].tx_bytes, TERMINAL_TYPES[n].working_counter)
           for n in ("EK1100", "EL1008", "EL2008", "EL5101", "EL1809")}
    assert got == {"EK1100": (0, 0, 0), "EL1008": (0, 1, 1), "EL2008": (1, 0, 2), "EL5101": (3, 5, 3),
                   "EL1809": (0, 2, 1)}


def test_an_unknown_terminal_or_a_position_taken_is_refused() -> None:
    with pytest.raises(ConfigurationError, match="unknown terminal type 'EL9999'; known: .*EL1008"):
        TerminalSpec(3, "EL9999")
    with pytest.raises(ConfigurationError, match="slave position 1: that position is already a drive"):
        SimBus(DRIVES, terminals=(TerminalSpec(1, "EL1008"),))


class _Slave:
    """SOEM's slave as the bus sees it: ``input`` bytes, ``output`` written."""

    def __init__(self, tx: bytes) -> None:
        self.input = tx
        self.output = b""


def test_the_soem_terminal_io_packs_and_unpacks_the_real_images() -> None:
    """On a real bus the terminal's bytes are read into and written from the bus arrays."""
    bus = SimBus(DRIVES, terminals=TERMINALS)
    din = TerminalIo(bus, 1, _Slave(bytes([0b1010_0101])), TERMINALS[1].type)
    din.read()
    assert int(bus.terminal_inputs[1]) == 0b1010_0101
    dout = TerminalIo(bus, 2, _Slave(b""), TERMINALS[2].type)
    bus.terminal_outputs[2] = 0b0001_0010
    dout.write()
    assert dout.slave.output == bytes([0b0001_0010])
    enc = TerminalIo(bus, 3, _Slave(struct.pack("<BHH", 0x21, 65_000, 1234)), TERMINALS[3].type)
    enc.read()
    assert (int(bus.terminal_inputs[3]), int(bus.terminal_counts[3]), int(bus.terminal_latches[3])) == \
        (0x21, 65_000, 1234)
    bus.terminal_outputs[3], bus.terminal_set_counts[3] = 0x04, 500
    enc.write()
    assert enc.slave.output == struct.pack("<BH", 0x04, 500)


def test_an_analog_output_terminal_carries_each_channel_as_int16_in_16_bits_of_its_word() -> None:
    """EL4002: two INT16 outputs (0x7000:11, 0x7010:11; 0x7FFF = 10 V). The bus keeps both in
    one word, 16 bits a channel; a real bus writes them as the terminal's two INT16, a negative
    value (a +-10 V terminal) included."""
    t = TERMINAL_TYPES["EL4002"]
    assert (t.kind, t.channels, t.rx_bytes, t.tx_bytes, t.working_counter) == \
        (TerminalKind.ANALOG_OUT, 2, 4, 0, 2)
    assert t.product_code == 0x0FA23052 and TERMINAL_TYPES["EL4102"].product_code == 0x10063052
    word = analog_word(analog_word(0, 0, 16_384), 1, -2)
    assert analog_channels(word, 2) == (16_384, -2)
    assert analog_channels(analog_word(word, 0, 0x7FFF), 2) == (0x7FFF, -2)     # the other kept
    terminals = (TerminalSpec(2, "EK1100"), TerminalSpec(3, "EL4002"))
    bus = SimBus(DRIVES, terminals=terminals)
    aout = TerminalIo(bus, 1, _Slave(b""), terminals[1].type)
    bus.terminal_outputs[1] = word
    aout.write()
    assert aout.slave.output == struct.pack("<hh", 16_384, -2)
    # through the loop's command: the word as the terminal's outputs, and in the snapshot
    cfg = WorkerConfig(DRIVES, mode="manual", terminals=terminals)
    w = CyclicWorker(cfg)
    w.start()
    try:
        w.step(3)
        w.set_terminal_output(1, analog_word(0, 1, 0x7FFF))
        w.step(2)
        assert w.snapshot().terminal_outputs[1] == 0x7FFF << 16
        assert int(w._loop.bus.terminal_outputs[1]) == 0x7FFF << 16    # type: ignore[union-attr]
    finally:
        w.stop()


def _worker(**kw: object) -> CyclicWorker:
    options = kw.pop("bus_options", ())
    cfg = WorkerConfig(DRIVES, mode="manual", terminals=TERMINALS, bus_options=options, **kw)  # type: ignore[arg-type]
    w = CyclicWorker(cfg)
    w.start()
    return w


def test_terminals_count_in_the_working_counter_and_are_listed() -> None:
    w = _worker()
    try:
        w.step(3)
        s = w.snapshot()
        assert s.expected_wkc == 3 * 2 + 1 + 2 + 3 and s.wkc == s.expected_wkc
        assert s.terminal_inputs == (0, 0, 0, 0) and s.terminal_outputs == (0, 0, 0, 0)
    finally:
        w.stop()
    bus = SimBus(DRIVES, terminals=TERMINALS)
    bus.open()
    names = [(x.position, x.name, x.product_code) for x in bus.slaves()]
    assert names == [(0, "SimServo X", names[0][2]), (1, "SimServo Z", names[1][2]),
                     (2, "EK1100", 0x044C2C52), (3, "EL1008", 0x03F03052), (4, "EL2008", 0x07D83052),
                     (5, "EL5101", 0x13ED3052)]


def test_an_input_changed_in_a_slave_reaches_the_loop_within_two_cycles_and_outputs_reach_it() -> None:
    w = _worker()
    try:
        w.step(2)
        for bit in (0, 5, 7):
            w.inject("terminal_input", 1, input_value(bit, True))
            w.step(2)
            assert w.snapshot().terminal_inputs[1] >> bit & 1 == 1
        w.inject("terminal_input", 1, input_value(5, False, release=True))
        w.step(2)
        assert w.snapshot().terminal_inputs[1] == 0b1000_0001
        w.set_terminal_output(2, 0b0110)
        w.step(1)
        bus = w._loop.bus  # type: ignore[union-attr]
        assert isinstance(bus, SimBus) and int(bus.io.outputs[2]) == 0b0110
        assert w.snapshot().terminal_outputs[2] == 0b0110
        w.inject("encoder_add", 3, 40)
        w.step(2)
        assert w.snapshot().terminal_counts[3] == 40
    finally:
        w.stop()


CHAIN = InputWatch(WatchAction.ESTOP_CHAIN, IN, 0, False, name="estop_chain_ok")
LIMIT_POS_X = InputWatch(WatchAction.LIMIT, IN, 1, True, axis=0, side=1, name="limit_pos_X")
LIMIT_NEG_X = InputWatch(WatchAction.LIMIT, IN, 2, True, axis=0, side=-1, name="limit_neg_X")


def _ramp(w: CyclicWorker, axis: int, target: float, v: float = 20.0) -> None:
    """Queue a move of one axis from where it stands (constant velocity, set-points of 1 ms)."""
    s = w.snapshot()
    start = s.reference_position.copy()
    n = max(2, int(abs(target - start[axis]) / (v * 0.001)))
    q = np.repeat(start[None, :], n, axis=0)
    q[:, axis] = np.linspace(start[axis], target, n)
    w.push(q)


def test_the_e_stop_chain_stops_the_drives_in_the_cycle_and_no_enable_while_it_stays_open() -> None:
    w = _worker(watches=(CHAIN,), bus_options=(("input_rest", (0, 1, 0, 0)),))
    try:
        w.step(3)
        w.enable()
        w.step(20)
        assert w.state() is WorkerState.ENABLED
        _ramp(w, 0, 5.0)
        w.step(50)
        w.inject("terminal_input", 1, input_value(0, False))      # the chain opens
        w.step(2)
        s = w.snapshot()
        assert s.state is WorkerState.QUICK_STOP and s.watches_active == (True,)
        assert [a.code for a in s.alarms][-1] is AlarmCode.ESTOP_CHAIN
        assert s.buffer_level == 0
        with pytest.raises(WorkerError, match="the E-stop chain is open \\(estop_chain_ok\\)"):
            w.enable()
        w.inject("terminal_input", 1, input_value(0, True, release=True))
        w.step(2)
        w.fault_reset()
        w.step(5)
        w.enable()
        w.step(20)
        assert w.state() is WorkerState.ENABLED
    finally:
        w.stop()


def test_a_limit_switch_stops_the_machine_and_only_a_move_away_is_allowed_with_the_override() -> None:
    # the positive limit switch of X closes from X = 3 on
    switches = (SimSwitch(0, 1, 3.0, 1e9, terminal=1),)
    w = _worker(watches=(LIMIT_POS_X, LIMIT_NEG_X), bus_options=(("switches", switches),))
    try:
        w.step(3)
        w.enable()
        w.step(20)
        _ramp(w, 0, 10.0)
        for _ in range(2000):
            w.step(1)
            if w.state() is not WorkerState.ENABLED:
                break
        s = w.snapshot()
        assert s.state is WorkerState.QUICK_STOP
        alarm = s.alarms[-1]
        assert alarm.code is AlarmCode.LIMIT_SWITCH and "axis X on its positive limit switch" in alarm.message
        assert 3.0 <= s.actual_position[0] < 3.0 + 20.0 * 0.002 + 1e-9   # stopped in the cycle it read it
        w.step(200)                         # the drive's own quick stop brings it to rest
        w.fault_reset()
        w.step(5)
        with pytest.raises(WorkerError, match="axis X is on its positive limit switch: override limits"):
            w.enable()
        w.override_limits(True)
        w.step(2)
        w.enable()
        w.step(20)
        assert w.state() is WorkerState.ENABLED
        _ramp(w, 0, float(w.snapshot().actual_position[0]) + 0.5)     # further on: stopped
        w.step(30)
        assert w.state() is WorkerState.QUICK_STOP
        w.fault_reset()
        w.step(5)
        w.enable()
        w.step(20)
        _ramp(w, 0, 1.0)                    # away: runs, and the override ends off the switch
        w.step(500)
        s = w.snapshot()
        assert s.state is WorkerState.ENABLED and abs(s.actual_position[0] - 1.0) < 1e-3
        assert not s.limits_overridden
    finally:
        w.stop()


EDGE_X = 5.0


def _homing(latch_vel: float, switch: SimSwitch, travel: float = 40.0,
            jerk: float = 400_000.0) -> SwitchHoming:
    return SwitchHoming(0, IN, switch.bit, switch.level, 20.0, latch_vel, travel, 2000.0, jerk)


def _home(w: CyclicWorker, cycles: int = 20_000) -> None:
    w.enable()
    w.step(20)
    w.home_to_switches([0])
    for _ in range(cycles // 100):
        w.step(100)
        if w.state() is not WorkerState.HOMING:
            return


def _home_traced(w: CyclicWorker, cycles: int) -> tuple[list[float], set[HomingStep]]:
    """Home axis 0 cycle by cycle: its reference position at every cycle and the steps seen."""
    w.enable()
    w.step(20)
    w.home_to_switches([0])
    refs: list[float] = []
    steps: set[HomingStep] = set()
    for _ in range(cycles):
        w.step(1)
        s = w.snapshot()
        refs.append(s.reference_position[0])
        steps.add(s.homing_steps[0])
        if w.state() is not WorkerState.HOMING:
            break
    return refs, steps


@pytest.mark.parametrize("latch_vel, n", [(-0.1, 50), (0.1, 10)])
def test_homing_finds_the_switch_edge_within_one_count_from_fifty_start_positions(latch_vel: float, n: int
                                                                                   ) -> None:
    """A home switch closed from X = 5 on (normally open): searched at +20 mm/s, latched leaving
    it at 0.1 mm/s (50 random places, some on the switch), or coming back onto it (10): the
    latched position is the edge within one count (1e-4 mm)."""
    switch = SimSwitch(0, 3, EDGE_X, 1e9, terminal=1)
    rng = np.random.default_rng(7)
    starts = rng.uniform(-20.0, 9.0, n)
    for x0 in starts:
        w = _worker(switch_homing=(_homing(latch_vel, switch),),
                    bus_options=(("switches", (switch,)), ("initial_positions_counts", (x0 * COUNTS, 0.0))))
        try:
            w.step(3)
            _home(w)
            s = w.snapshot()
            assert s.homing[0] is HomingState.DONE and s.homing_steps[0] is HomingStep.DONE, (x0, s.alarms)
            assert abs(s.home_latched[0] - EDGE_X) <= 1.0 / COUNTS + 1e-12, (x0, s.home_latched[0])
        finally:
            w.stop()


def test_homing_steps_keep_the_axis_limits() -> None:
    """Every set-point of a homing (search, stop, back, latch, stop) within the velocity,
    acceleration and jerk given, from the trace of the loop's references."""
    switch = SimSwitch(0, 3, EDGE_X, 1e9, terminal=1)
    a_max, j_max = 2000.0, 40_000.0
    w = _worker(switch_homing=(_homing(-1.0, switch, jerk=j_max),), bus_options=(("switches", (switch,)),))
    try:
        w.step(3)
        refs, _steps = _home_traced(w, 3000)
        assert w.snapshot().homing[0] is HomingState.DONE
    finally:
        w.stop()
    dt = 0.001
    v = np.diff(np.array(refs)) / dt
    a = np.diff(v) / dt
    j = np.diff(a) / dt
    assert np.abs(v).max() <= 20.0 * (1 + 1e-9)
    assert np.abs(a).max() <= a_max * (1 + 1e-6)
    assert np.abs(j).max() <= j_max * (1 + 1e-6)
    assert v.max() > 19.9 and v.min() < -0.99          # it did search and latch


def test_a_missing_switch_stops_at_the_search_travel_with_an_alarm_naming_the_step() -> None:
    switch = SimSwitch(0, 3, 500.0, 1e9, terminal=1)        # beyond the 40 mm search
    w = _worker(switch_homing=(_homing(-0.1, switch, travel=40.0),), bus_options=(("switches", (switch,)),))
    try:
        w.step(3)
        _home(w)
        s = w.snapshot()
        assert s.state is WorkerState.QUICK_STOP and s.homing[0] is HomingState.ERROR
        alarm = s.alarms[-1]
        assert alarm.code is AlarmCode.HOMING_SWITCH
        assert "at step 'search': the switch did not change within the search travel" in alarm.message
        assert 40.0 <= s.actual_position[0] <= 40.0 + 0.5
    finally:
        w.stop()


def test_a_limit_switch_while_homing_fails_the_homing_unless_the_axis_ignores_its_limits() -> None:
    home = SimSwitch(0, 3, EDGE_X, 1e9, terminal=1)
    limit = SimSwitch(0, 1, 2.0, 1e9, terminal=1)           # closes before the home switch
    for ignore, done in ((False, False), (True, True)):
        spec = SwitchHoming(0, IN, 3, True, 20.0, -0.1, 40.0, 2000.0, 40_000.0, ignore_limits=ignore)
        w = _worker(switch_homing=(spec,), watches=(LIMIT_POS_X,), bus_options=(("switches", (home, limit)),))
        try:
            w.step(3)
            _home(w)
            s = w.snapshot()
            assert (s.homing[0] is HomingState.DONE) is done, s.alarms
            if not done:
                assert "a limit switch tripped" in s.alarms[-1].message
        finally:
            w.stop()


def _terminal_esi(tmp_path, product: str, name: str, n_channels: int, direction: str) -> object:
    """An ESI file of a digital terminal as Beckhoff writes them: no mailbox, one PDO of one bit
    per channel, each assigned to the process data sync manager."""
    pdo, index, sm = ("TxPdo", 0x1A00, 0) if direction == "in" else ("RxPdo", 0x1600, 0)
    obj = 0x6000 if direction == "in" else 0x7000
    pdos = "".join(
        f'<{pdo} Fixed="1" Sm="{sm}"><Index>#x{index + c:04x}</Index><Name>Channel {c + 1}</Name>'
        f"<Entry><Index>#x{obj + 0x10 * c:04x}</Index><SubIndex>1</SubIndex><BitLen>1</BitLen>"
        f"<Name>Input</Name><DataType>BOOL</DataType></Entry></{pdo}>" for c in range(n_channels))
    text = (f'<?xml version="1.0"?><EtherCATInfo><Vendor><Id>2</Id><Name>Beckhoff Automation GmbH</Name>'
            f'</Vendor><Descriptions><Devices><Device Physics="YY"><Type ProductCode="{product}" '
            f'RevisionNo="#x00120000">{name}</Type><Name>{name}</Name>{pdos}</Device></Devices>'
            f"</Descriptions></EtherCATInfo>")
    p = tmp_path / f"{name}.xml"
    p.write_text(text)
    return p


def test_cnc_ethercat_esi_writes_a_terminals_table_from_its_esi_and_refuses_another_image(tmp_path, capsys
                                                                                         ) -> None:
    from ethercat.cli import main
    from ethercat.esi import EsiError

    esi = _terminal_esi(tmp_path, "#x03f03052", "EL1008", 8, "in")
    assert main(["esi", str(esi), "--positions", "4"]) == 0
    out = capsys.readouterr().out
    assert '[[bus.terminals]]\nposition = 4\ntype = "EL1008"' in out
    assert "8 input, 0 output bits as its ESI assigns them" in out
    esi = _terminal_esi(tmp_path, "#x07d83052", "EL2008", 8, "out")
    assert main(["esi", str(esi), "--positions", "6"]) == 0
    assert 'type = "EL2008"' in capsys.readouterr().out
    short = _terminal_esi(tmp_path, "#x03f03052", "EL1008", 4, "in")      # not an EL1008's image
    assert main(["esi", str(short), "--positions", "4"]) != 0
    err = capsys.readouterr().err
    assert "assigns 4 input and 0 output bits by default; the control reads a EL1008 as 8 and 0" in err
    with pytest.raises(EsiError, match="is not a terminal this control knows"):
        from ethercat.esi import propose_terminal_block, read_esi

        propose_terminal_block(read_esi(_terminal_esi(tmp_path, "#x0bf83052", "EL3064", 4, "in"))[0], 3)
