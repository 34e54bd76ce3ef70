"""Who the server says it is: an ApplicationUri and a ProductInstanceUri of each installation
(two state folders on one host differ, in both security modes), the Identification fields the
configuration gives, and the conformance walk of both shipped machines."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path
from typing import Any

import pytest
from asyncua import Client

from opcua_server.browse import check_mandatory, find_machine
from tests.opcua.conftest import ClientThread, make_served

ROOT = Path(__file__).resolve().parents[2]
DI = "http://opcfoundation.org/UA/DI/"
MACHINERY = "http://opcfoundation.org/UA/Machinery/"


async def _who(url: str) -> tuple[str, str]:
    """The ApplicationUri the endpoints name and the machine's ProductInstanceUri, read over
    the discovery a client does before its session, and over a session."""
    c = Client(url, timeout=10)
    endpoints = await c.connect_and_get_server_endpoints()
    async with Client(url, timeout=10) as s:
        machine = await find_machine(s)
        di = await s.get_namespace_index(DI)
        instance = await machine.get_child([f"{di}:Identification", f"{di}:ProductInstanceUri"])
        uri = await instance.read_value()
        server_array = await s.get_node("i=2254").read_value()
    assert {e.Server.ApplicationUri for e in endpoints} == {server_array[0]}
    return server_array[0], str(uri)


@pytest.mark.parametrize("secure", [False, True], ids=["insecure", "secure"])
def test_two_installations_on_one_host_serve_different_application_and_instance_uris(
        qapp: Any, tmp_path: Path, client_thread: ClientThread, secure: bool) -> None:
    seen = []
    for name in ("one", "two"):
        served = make_served(qapp, tmp_path / name, anonymous=True, security=_modes(secure))
        try:
            seen.append(client_thread.run(_who(served.url)))
            assert (tmp_path / name / "opcua" / "installation").is_file()
        finally:
            served.ctl.shutdown()
    (app_one, machine_one), (app_two, machine_two) = seen
    assert app_one != app_two and machine_one != machine_two
    assert "freeopcua" not in app_one and "freeopcua" not in app_two
    # the same installation started again keeps its ids
    served = make_served(qapp, tmp_path / "one", anonymous=True, security=_modes(secure))
    try:
        assert client_thread.run(_who(served.url)) == seen[0]
    finally:
        served.ctl.shutdown()


def _modes(secure: bool) -> tuple[Any, ...]:
    from opcua_server.settings import SecurityMode

    return (SecurityMode.SIGN_AND_ENCRYPT, SecurityMode.NONE) if secure else (SecurityMode.NONE,)


def test_the_configured_uris_and_identification_fields_are_served(
        qapp: Any, tmp_path: Path, client_thread: ClientThread) -> None:
    from app.machine.config import load_config

    text = (ROOT / "resources" / "machines" / "xyz_mill.toml").read_text()
    assert "[opcua]" not in text
    text += "\n".join(["",
        "[opcua]", 'application_uri = "urn:shop-7:mill-3"', 'product_instance_uri = "urn:shop-7:machines:3"',
        'product_code = "XYZ-600"', "year_of_construction = 2024", "month_of_construction = 5",
        'location = "HALL 2/ROW 3"', 'manufacturer_uri = "https://example.org"', 'hardware_revision = "B"',
        'device_class = "milling machine"', 'asset_id = "A-0042"', ""])
    (tmp_path / "machine.toml").write_text(text)
    cfg = load_config(tmp_path / "machine.toml")
    served = make_served(qapp, tmp_path / "state", cfg=cfg, anonymous=True)

    async def read() -> tuple[tuple[str, str], dict[str, Any]]:
        who = await _who(served.url)
        async with Client(served.url, timeout=10) as c:
            machine = await find_machine(c)
            di, mach = await c.get_namespace_index(DI), await c.get_namespace_index(MACHINERY)
            ident = await machine.get_child([f"{di}:Identification"])
            fields = {}
            for name, ns in (("ProductCode", di), ("YearOfConstruction", mach), ("MonthOfConstruction", mach),
                             ("Location", mach), ("ManufacturerUri", di), ("HardwareRevision", di),
                             ("DeviceClass", di), ("AssetId", di)):
                fields[name] = await (await ident.get_child([f"{ns}:{name}"])).read_value()
            return who, fields

    try:
        who, fields = client_thread.run(read())
    finally:
        served.ctl.shutdown()
    assert who == ("urn:shop-7:mill-3", "urn:shop-7:machines:3")
    assert fields == {"ProductCode": "XYZ-600", "YearOfConstruction": 2024, "MonthOfConstruction": 5,
                      "Location": "HALL 2/ROW 3", "ManufacturerUri": "https://example.org",
                      "HardwareRevision": "B", "DeviceClass": "milling machine", "AssetId": "A-0042"}


@pytest.mark.parametrize("machine", ["xyz_mill.toml", "paper_yzca.toml"])
def test_the_conformance_walk_of_each_shipped_machine_finds_nothing_missing(
        qapp: Any, tmp_path: Path, client_thread: ClientThread, machine: str) -> None:
    from app.machine.config import load_config

    cfg = load_config(ROOT / "resources" / "machines" / machine)
    served = make_served(qapp, tmp_path / "state", cfg=replace(cfg, opcua=replace(cfg.opcua, enabled=True)))

    async def walk() -> Any:
        async with Client(served.url, timeout=10) as c:
            return await check_mandatory(c, await find_machine(c))

    try:
        result = client_thread.run(walk())
    finally:
        served.ctl.shutdown()
    assert result.problems == []
    # the stack light's elements are checked against MachineToolType's own <OrderedObject>
    assert result.checked_declarations > 60
