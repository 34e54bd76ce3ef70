"""ESI files: what is read from a drive's description, the [[bus.drives]] table proposed from it
(which the machine configuration must accept as it is), and refusals of broken files."""

from __future__ import annotations

import os
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from app.machine.config import MachineConfig, config_from_dict
from ethercat.drive_setup import MappingPolicy
from ethercat.esi import EsiError, check_slave, propose_drive_block, read_esi
from ethercat.pdo import PdoEntry
from tests.ethercat.third_party import KICKCAT_ESI

ROOT = Path(__file__).resolve().parents[2]
needs_kickcat_esi = pytest.mark.skipif(
    not KICKCAT_ESI.is_file(), reason=f"KickCAT's ESI file is not at {KICKCAT_ESI} (../shared missing)")

#: a small drive description with fixed PDOs, padding and no SYNC0 mode
FIXED_ESI = """<?xml version="1.0"?>
<EtherCATInfo>
  <Vendor><Id>#x00000123</Id><Name>Acme</Name></Vendor>
  <Descriptions><Devices>
    <Device>
      <Type ProductCode="#x00000042" RevisionNo="#x00000002">Acme-Servo</Type>
      <Profile><Dictionary>
        <DataTypes>
          <DataType><Name>UINT</Name><BitSize>16</BitSize></DataType>
          <DataType><Name>DINT</Name><BitSize>32</BitSize></DataType>
        </DataTypes>
        <Objects>
          <Object><Index>#x6040</Index><Name>Controlword</Name><Type>UINT</Type><BitSize>16</BitSize>
            <Flags><Access>rw</Access><PdoMapping>R</PdoMapping></Flags></Object>
          <Object><Index>#x6041</Index><Name>Statusword</Name><Type>UINT</Type><BitSize>16</BitSize>
            <Flags><Access>ro</Access><PdoMapping>T</PdoMapping></Flags></Object>
          <Object><Index>#x607A</Index><Name>Target position</Name><Type>DINT</Type><BitSize>32</BitSize>
            <Flags><Access>rw</Access><PdoMapping>R</PdoMapping></Flags></Object>
          <Object><Index>#x6064</Index><Name>Position actual</Name><Type>DINT</Type><BitSize>32</BitSize>
            <Flags><Access>ro</Access><PdoMapping>T</PdoMapping></Flags></Object>
        </Objects>
      </Dictionary></Profile>
      <RxPdo Fixed="1" Sm="2"><Index>#x1601</Index><Name>Outputs</Name>
        <Entry><Index>#x607A</Index><SubIndex>0</SubIndex><BitLen>32</BitLen><DataType>DINT</DataType></Entry>
        <Entry><Index>#x6040</Index><SubIndex>0</SubIndex><BitLen>16</BitLen><DataType>UINT</DataType></Entry>
        <Entry><Index>#x0</Index><SubIndex>0</SubIndex><BitLen>16</BitLen></Entry>
      </RxPdo>
      <TxPdo Fixed="1" Sm="3"><Index>#x1A01</Index><Name>Inputs</Name>
        <Entry><Index>#x6064</Index><SubIndex>0</SubIndex><BitLen>32</BitLen><DataType>DINT</DataType></Entry>
        <Entry><Index>#x6041</Index><SubIndex>0</SubIndex><BitLen>16</BitLen><DataType>UINT</DataType></Entry>
      </TxPdo>
      <Mailbox><CoE SdoInfo="true" PdoAssign="false" PdoConfig="false"/></Mailbox>
    </Device>
  </Devices></Descriptions>
</EtherCATInfo>
"""

BASE_CONFIG = (ROOT / "resources" / "machines" / "xyz_mill.toml").read_text(encoding="utf-8")


def machine_text(blocks: str, adapter: str = "eth1") -> str:
    """The shipped XYZ mill on a real bus: its own [bus] section replaced by one on `adapter`
    with the given [[bus.drives]] tables pasted after it."""
    head = BASE_CONFIG.split("[bus]")[0]
    return f'{head}[bus]\nkind = "soem"\nadapter = "{adapter}"\n\n{blocks}'


def config_with(block: str, where: str = "pasted.toml") -> MachineConfig:
    text = machine_text(block)
    return config_from_dict(tomllib.loads(text), where, text)


@needs_kickcat_esi
def test_kickcat_description_read() -> None:
    (dev,) = read_esi(KICKCAT_ESI)
    assert (dev.vendor_id, dev.product_code, dev.revision) == (0x29C, 0x03B11002, 0x00050005)
    assert dev.name == "EVS-NET-01" and dev.vendor_name == "Ingenia"
    assert dev.object_name(0x6040) == "Control Word" and dev.objects[(0x6040, 0)].pdo_mapping == "R"
    assert dev.objects[(0x60F4, 0)].data_type == "DINT" and dev.objects[(0x60F4, 0)].signed
    assert not dev.has(0x60FD) and not dev.has(0x60FE, 1)
    assert [hex(p.index) for p in dev.rx_pdos] == ["0x1600", "0x1601", "0x1602"]
    assert dev.rx_pdos[0].sm == 2 and not dev.rx_pdos[0].fixed and dev.rx_pdos[0].excludes == (0x1601, 0x1602)
    assert [e.index for e in dev.rx_pdos[0].entries] == [0x6040, 0x607A, 0x60FF, 0x6060]
    assert dev.complete_access and dev.pdo_config
    assert [m.assign_activate for m in dev.dc_modes] == [0, 0x300]


@needs_kickcat_esi
def test_kickcat_block_is_accepted_by_the_machine_configuration() -> None:
    (dev,) = read_esi(KICKCAT_ESI)
    block = propose_drive_block(dev, 0) + propose_drive_block(dev, 1)
    assert 'rx = ["0x6040:0:16", "0x607A:0:32", "0x6060:0:8"]' in block
    assert '"0x60F4:0:32", "0x603F:0:16"' in block and "0x60FD:" not in block.split("tx = ")[1]
    assert "no 0x60FE in its dictionary" in block and "dc = true" in block
    cfg = config_with(block)
    drive = cfg.bus.drives[0]
    setup = drive.setup()
    assert (drive.vendor_id, drive.product_code) == (0x29C, 0x03B11002)
    assert setup.policy is MappingPolicy.ADAPT and setup.dc and setup.complete_access is None
    assert setup.mapping is not None
    assert setup.mapping.rx == (PdoEntry(0x6040, 0, 16), PdoEntry(0x607A, 0, 32, True),
                                PdoEntry(0x6060, 0, 8, True))


def test_fixed_pdos_give_a_kept_mapping_with_padding(tmp_path: Path) -> None:
    p = tmp_path / "acme.xml"
    p.write_text(FIXED_ESI, encoding="utf-8")
    (dev,) = read_esi(p)
    block = propose_drive_block(dev, 0)
    assert 'mapping = "keep"' in block and "(fixed)" in block and "dc = false" in block
    assert 'rx = ["0x607A:0:32", "0x6040:0:16", "0x0000:0:16"]' in block
    cfg = config_with(block)
    setup = cfg.bus.drives[0].setup()
    assert setup.policy is MappingPolicy.KEEP and not setup.dc
    assert setup.mapping is not None and setup.mapping.rx_pdo == 0x1601 and setup.mapping.rx_struct.size == 8
    # a live slave whose assignment maps an object the description lacks is named
    found = {"rx": [(0x1601, [0x607A0020, 0x60400010, 0x00000010])],
             "tx": [(0x1A01, [0x60640020, 0x60FD0020])]}
    assert check_slave(dev, (0x123, 0x42, 2), found) == [
        "TXPDO 0x1A01 maps 0x60FD:0, which the ESI's dictionary does not have"]
    assert "revision 0x00000003" in check_slave(dev, (0x123, 0x42, 3), found)[0]
    assert "identity" in check_slave(dev, (0x124, 0x42, 2), found)[0]


def test_cli_esi_prints_the_block_and_names_bad_files(tmp_path: Path) -> None:
    p = tmp_path / "acme.xml"
    p.write_text(FIXED_ESI, encoding="utf-8")
    env = {**os.environ}
    res = subprocess.run([sys.executable, "-m", "ethercat", "esi", str(p), "--positions", "0", "3"],
                         capture_output=True, text=True, cwd=ROOT, env=env, timeout=60)
    assert res.returncode == 0, res.stderr
    assert res.stdout.count("[[bus.drives]]") == 2 and "position = 3" in res.stdout
    bad = tmp_path / "bad.xml"
    bad.write_text(FIXED_ESI.replace("</Devices>", ""), encoding="utf-8")
    res = subprocess.run([sys.executable, "-m", "ethercat", "esi", str(bad)], capture_output=True, text=True,
                         cwd=ROOT, env=env, timeout=60)
    assert res.returncode == 1 and f"{bad}:" in res.stderr and "not a well-formed XML file" in res.stderr


@settings(max_examples=60, deadline=None)
@given(cut=st.integers(0, len(FIXED_ESI)), junk=st.text(max_size=12), at=st.integers(0, len(FIXED_ESI)))
def test_mutated_descriptions_give_esi_errors_only(tmp_path_factory: pytest.TempPathFactory, cut: int,
                                                   junk: str, at: int) -> None:
    text = FIXED_ESI[:at] + junk + FIXED_ESI[at:]
    text = text[:cut] if cut < len(text) // 2 else text
    p = tmp_path_factory.mktemp("esi") / "mutated.xml"
    p.write_text(text, encoding="utf-8")
    try:
        devices = read_esi(p)
    except EsiError as exc:
        assert str(p) in str(exc)
        return
    for dev in devices:
        try:
            propose_drive_block(dev, 0)
        except EsiError as exc:
            assert str(p) in str(exc)
