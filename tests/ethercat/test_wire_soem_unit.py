"""SoemBus pieces that need no network: PDO mapping rules, exact packing of process data,
judging SOEM's config_map error list, and `cnc-ethercat` argument handling."""

from __future__ import annotations

import json
import struct
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from ethercat.bus import DriveSpec
from ethercat.cli import build_parser, main
from ethercat.errors import ConfigurationError, SdoAbortError
from ethercat.pdo import CSP_MAPPING, DRIVE_MAPPINGS, DriveIo, PdoEntry, PdoMapping
from ethercat.soem_access import al_state_name
from ethercat.soem_bus import SoemBus

ROOT = Path(__file__).resolve().parents[2]
DRIVES = (DriveSpec(0, "X"), DriveSpec(1, "Y", direction=-1))


def test_csp_mapping_sizes_and_entries() -> None:
    assert CSP_MAPPING.rx_struct.size == 13 and CSP_MAPPING.tx_struct.size == 23
    assert [e.value for e in CSP_MAPPING.rx] == [0x60400010, 0x607A0020, 0x60600008, 0x60FE0120, 0x60B80010]
    assert [e.value for e in CSP_MAPPING.tx] == [0x60410010, 0x60640020, 0x60F40020, 0x603F0010, 0x60610008,
                                                 0x60FD0020, 0x60B90010, 0x60BA0020]
    assert (0x0000_0A5E, 0x0402_0001) in DRIVE_MAPPINGS


@pytest.mark.parametrize("rx, tx, text", [
    ((PdoEntry(0x607A, 0, 32, True),), CSP_MAPPING.tx, "controlword"),
    (CSP_MAPPING.rx, (PdoEntry(0x6041, 0, 16),), "position actual"),
    (CSP_MAPPING.rx + (PdoEntry(0x2000, 0, 24),), CSP_MAPPING.tx, "24 bits"),
])
def test_mapping_rules(rx: tuple[PdoEntry, ...], tx: tuple[PdoEntry, ...], text: str) -> None:
    with pytest.raises(ConfigurationError, match=text):
        PdoMapping(rx, tx)


class FakeSlave:
    def __init__(self, inputs: bytes) -> None:
        self.output = b""
        self.input = inputs


def test_process_data_packed_exactly_in_mapping_order() -> None:
    bus = SoemBus(DRIVES, adapter="unused")
    bus.controlword[:] = [0x0F, 0x06]
    bus.target_position[:] = [-123456, 7]
    bus.modes_of_operation[:] = [8, 6]
    bus.digital_outputs[:] = [0x0003_0000, 0]
    bus.touch_probe_function[:] = [0x15, 0]
    inputs = struct.pack("<HiiHbIHi", 0x1237, -5, 3, 0x2310, 8, 0x0001_0004, 0x0003, -70_000)
    slaves = [FakeSlave(inputs), FakeSlave(bytes(23))]
    ios = [DriveIo(bus, i, s, CSP_MAPPING) for i, s in enumerate(slaves)]
    for io in ios:
        io.write()
        io.read()
    assert slaves[0].output == struct.pack("<HibIH", 0x0F, -123456, 8, 0x0003_0000, 0x15)
    assert slaves[1].output == struct.pack("<HibIH", 0x06, 7, 6, 0, 0)
    assert all(len(s.output) == 13 for s in slaves), "never more than the slave's output size"
    assert bus.statusword[0] == 0x1237 and bus.position_actual[0] == -5
    assert bus.following_error[0] == 3 and bus.error_code[0] == 0x2310 and bus.modes_display[0] == 8
    assert bus.digital_inputs[0] == 0x0001_0004
    assert bus.touch_probe_status[0] == 0x0003 and bus.touch_probe_value[0] == -70_000
    np.testing.assert_array_equal(bus.statusword, [0x1237, 0])


def test_config_map_error_list_judged() -> None:
    bus = SoemBus(DRIVES, adapter="unused")
    emergency = SimpleNamespace(slave_pos=3, desc="emergency 0x1000")          # not a configured drive
    bus._judge_config_map_errors([emergency])
    assert bus.warnings == ["slave 2: SimpleNamespace emergency 0x1000"]
    abort = SimpleNamespace(slave_pos=2, index=0x1600, subindex=0, abort_code=0x06040041, desc="not mappable")
    with pytest.raises(SdoAbortError) as exc:
        bus._judge_config_map_errors([emergency, abort])
    assert exc.value.position == 1 and exc.value.abort_code == 0x06040041
    assert "0x1600" in str(exc.value) and "PDO mapping" in str(exc.value)


def test_al_state_names() -> None:
    assert al_state_name(0x08) == "OP"
    assert al_state_name(0x14) == "SAFE-OP + ERROR"


def test_cli_arguments() -> None:
    args = build_parser().parse_args(["download", "eth0", "1", "0x6065", "0", "0x10"])
    assert (args.position, args.index, args.subindex, args.value) == (1, 0x6065, 0, 16)
    assert main(["bench", "--seconds", "1"]) == 1, "neither --sim nor an interface"
    assert main(["download", "eth0", "0", "0x2FFF", "0", "1"]) == 1, "unknown type needs --type"


def test_cli_bench_sim_json() -> None:
    res = subprocess.run([sys.executable, "-m", "ethercat", "bench", "--sim", "--seconds", "1", "--json",
                          "--mode", "thread", "--drives", "2"], capture_output=True, text=True, timeout=60,
                         cwd=ROOT)
    assert res.returncode == 0, res.stderr
    figures = json.loads(res.stdout)
    assert figures["bus"] == "sim" and figures["drives"] == 2 and figures["cycles"] > 500


def test_link_tests_skip_reasons(monkeypatch: pytest.MonkeyPatch) -> None:
    from ethercat.emulator import link

    monkeypatch.setattr(link.os, "geteuid", lambda: 1000)
    assert "root" in link.link_unavailable_reason()
    monkeypatch.setattr(link.os, "geteuid", lambda: 0)
    monkeypatch.setattr(link.shutil, "which", lambda _name: None)
    assert "iproute2" in link.link_unavailable_reason()
    with pytest.raises(ConfigurationError, match="iproute2"):
        link.EmulatedLink(1).start()


def test_frame_timeout_comes_from_the_environment(monkeypatch: pytest.MonkeyPatch) -> None:
    from ethercat.errors import ConfigurationError
    from ethercat.soem_access import FRAME_TIMEOUT_ENV, frame_timeout_us

    monkeypatch.delenv(FRAME_TIMEOUT_ENV, raising=False)
    assert frame_timeout_us() is None                      # SOEM's own default is kept
    monkeypatch.setenv(FRAME_TIMEOUT_ENV, "20000")
    assert frame_timeout_us() == 20000
    for bad in ("fast", "50", "5000000"):
        monkeypatch.setenv(FRAME_TIMEOUT_ENV, bad)
        with pytest.raises(ConfigurationError, match=FRAME_TIMEOUT_ENV):
            frame_timeout_us()


def test_sdo_failures_are_named_so_an_integrator_can_act() -> None:
    """SOEM's errors of one SDO transfer, decoded: the slave by position, name and identity,
    the object, and what the code means, not SOEM's bare "(1, 1)"."""
    import pysoem

    from ethercat.errors import SdoError, SdoTimeoutError
    from ethercat.soem_access import _map_sdo_error

    master = SimpleNamespace(slaves=[None, SimpleNamespace(name="KickCAT drive", man=0x6A5, id=0xB0CAD0)])
    packet = _map_sdo_error(pysoem.PacketError(1, 1), 1, 0x1C12, 0, master)
    assert isinstance(packet, SdoError)
    assert str(packet).startswith("SDO 0x1C12:0 on slave 1 (KickCAT drive, vendor 0x000006A5, product "
                                  "0x00B0CAD0): unexpected frame returned")
    assert "(SOEM packet error 1)" in str(packet)
    mailbox = _map_sdo_error(pysoem.MailboxError(1, 2, "x"), 1, 0x1C12, 0, master)
    assert "mailbox error: the mailbox protocol is not supported by the slave (detail code 2)" in str(mailbox)
    abort = _map_sdo_error(pysoem.SdoError(1, 0x1C12, 0, 0x06010002, "Attempt to write a read only object"),
                           1, 0x1C12, 0, master)
    assert isinstance(abort, SdoAbortError) and abort.abort_code == 0x06010002
    assert "on slave 1 (KickCAT drive" in str(abort) and "read only" in str(abort)
    wkc = _map_sdo_error(pysoem.WkcError(1, 0), 1, 0x6041, 0, master)
    assert isinstance(wkc, SdoTimeoutError) and "no answer" in str(wkc)
    unknown = _map_sdo_error(pysoem.PacketError(1, 9), 1, 0x1C12, 0, None)
    assert str(unknown) == "SDO 0x1C12:0 on slave 1: the answer did not fit the request (SOEM packet error 9)"


# ---------------------------------------------------------------------- mapping pieces
def test_mapping_entries_from_text_and_from_drives() -> None:
    from ethercat.pdo import parse_entry

    assert parse_entry("0x607A:0:32") == PdoEntry(0x607A, 0, 32, True)        # typed from CiA 402
    assert parse_entry(" 0x2010:1:32s ") == PdoEntry(0x2010, 1, 32, True)    # unknown, marked signed
    assert parse_entry("0x0:0:8").is_padding
    for bad, words in (("0x6040:0", "index:subindex:bits"), ("0x6040:0:32", "has 16 bits"),
                       ("0x10000:0:8", "0..0xFFFF")):
        with pytest.raises(ConfigurationError, match=words):
            parse_entry(bad)
    m = PdoMapping.from_values([0x607A0020, 0x60400010, 0x00000008], [0x60640020, 0x60410010, 0x606C0020],
                               0x1601, 0x1A01)
    assert m.objects == {0x607A, 0x6040, 0x6064, 0x6041, 0x606C} and m.rx_struct.size == 7
    assert m.without({0x606C}).tx_struct.size == 6


def test_padding_and_unknown_objects_are_packed_in_place() -> None:
    """A drive's own mapping may order objects differently, pad, and carry objects the bus has no
    array for: written as 0, skipped when read."""
    mapping = PdoMapping.from_values([0x607A0020, 0x60400010, 0x00000008, 0x60FF0020],
                                     [0x60640020, 0x60410010, 0x00000008, 0x606C0020])
    bus = SoemBus(DRIVES, adapter="unused")
    bus.controlword[:] = [0x0F, 0]
    bus.target_position[:] = [-7, 0]
    slave = FakeSlave(struct.pack("<iHxi", 123, 0x1237, 999))
    io = DriveIo(bus, 0, slave, mapping)
    io.write()
    io.read()
    assert slave.output == struct.pack("<iHxi", -7, 0x0F, 0)
    assert bus.position_actual[0] == 123 and bus.statusword[0] == 0x1237


def test_emulated_drive_variants_at_the_object_level() -> None:
    from ethercat.drive_model import DriveModel
    from ethercat.emulator.coe import DriveObjects
    from ethercat.emulator.variants import VARIANTS

    def objects(name: str) -> DriveObjects:
        return DriveObjects(DriveModel(), "drive", lambda: 2, VARIANTS[name])

    fixed = objects("fixed")
    assert fixed.assignment(0x1C12) == [0x1601] and fixed.mapping(0x1601)[0] == 0x607A0020
    with pytest.raises(SdoAbortError) as exc:
        fixed.write(0x1C12, 0, b"\x00")
    assert exc.value.abort_code == SdoAbortError.READ_ONLY
    assert fixed.tx_layout().size_bytes == 4 + 2 + 1 + 1 + 4
    minimal = objects("minimal")
    for index in (0x60F4, 0x603F, 0x60FD):
        with pytest.raises(SdoAbortError) as exc:
            minimal.read(index, 0)
        assert exc.value.abort_code == SdoAbortError.OBJECT_DOES_NOT_EXIST
    assert objects("standard").read_complete(0x1C12, 0) == b"\x01\x00\x00\x16"
    assert objects("picky").read_complete(0x1C12, 0) == b"\x01\x00\x16"      # no pad byte, as KickCAT


def test_a_terminal_of_another_identity_or_image_is_refused_naming_the_slave() -> None:
    """A terminal is checked by identity (vendor 2, its type's product code) and by the bytes of
    its default PDO assignment SOEM mapped; either wrong stops the start-up naming the slave."""
    from ethercat.errors import SlaveIdentityError
    from ethercat.terminals import TerminalSpec

    bus = SoemBus(DRIVES, adapter="unused", terminals=(TerminalSpec(2, "EL1008"), TerminalSpec(3, "EL2008")))

    def slave(man: int, pid: int, n_out: int, n_in: int) -> SimpleNamespace:
        return SimpleNamespace(man=man, id=pid, output=bytes(n_out), input=bytes(n_in), name=f"0x{pid:08X}")

    drives = [slave(0, 0, CSP_MAPPING.rx_struct.size, CSP_MAPPING.tx_struct.size) for _ in DRIVES]
    bus.master = SimpleNamespace(slaves=[*drives, slave(2, 0x03F03052, 0, 1), slave(2, 0x07D43052, 1, 0)])
    with pytest.raises(SlaveIdentityError, match="slave 3"):
        bus._check_identities()                          # an EL2004 where an EL2008 belongs
    bus.master.slaves[3] = slave(2, 0x07D83052, 2, 0)
    bus._check_identities()
    bus.slave_mappings = {0: CSP_MAPPING, 1: CSP_MAPPING}
    with pytest.raises(ConfigurationError, match="slave 3 .*2 output / 0 input bytes; a EL2008 has 1 / 0"):
        bus._build_io()
    bus.master.slaves[3] = slave(2, 0x07D83052, 1, 0)
    bus._build_io()
    bus.terminal_outputs[1] = 0b1001
    bus.master.slaves[2].input = bytes([0b0100_0001])
    for tio in bus._terminal_io:
        tio.write()
        tio.read()
    assert bus.master.slaves[3].output == bytes([0b1001]) and int(bus.terminal_inputs[0]) == 0b0100_0001
