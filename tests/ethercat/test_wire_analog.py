"""An analog output terminal on a real EtherCAT link: SoemBus (pysoem) against the project's
emulator with two drives, a coupler and an EL4002 behind them (veth pair in a network
namespace, as the other link tests; root). SOEM maps the terminal from its SII PDOs (0x1600
and 0x1602: 0x7000:11 and 0x7010:11, INT16 each); both channels' values reach the slave."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from ethercat.emulator.link import EmulatedLink, link_unavailable_reason
from ethercat.soem_bus import SoemBus
from ethercat.terminals import TerminalSpec, analog_channels, analog_word
from tests.ethercat.test_wire_terminals import DRIVES, emulated_link

REASON = link_unavailable_reason()
pytestmark = [pytest.mark.root,
              pytest.mark.skipif(bool(REASON), reason=f"EtherCAT link tests skipped: {REASON}")]

TERMINALS = (TerminalSpec(2, "EK1100"), TerminalSpec(3, "EL4002"))


@pytest.fixture(scope="module")
def link() -> Iterator[EmulatedLink]:
    yield from emulated_link(("EK1100", "EL4002"))


def test_both_channels_of_an_analog_terminal_reach_the_slave(link: EmulatedLink) -> None:
    bus = SoemBus(DRIVES, adapter=link.master_ifname, terminals=TERMINALS)
    with bus:
        names = [(s.position, s.vendor_id, s.product_code) for s in bus.slaves()]
        assert names[2:] == [(2, 2, 0x044C2C52), (3, 2, 0x0FA23052)]
        assert bus.expected_wkc == 3 * 2 + 2            # two drives, the outputs written
        for values in ((16_384, 0), (0x7FFF, -3_000), (0, 0)):
            bus.terminal_outputs[1] = analog_word(analog_word(0, 0, values[0]), 1, values[1])
            for _ in range(3):
                assert bus.exchange() == bus.expected_wkc
            status = link.control("status")["slaves"]
            assert status[3]["terminal"] == "EL4002"
            assert analog_channels(status[3]["outputs"], 2) == values
