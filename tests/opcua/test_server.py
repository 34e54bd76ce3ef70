"""The OPC UA server through a real asyncua client over TCP on 127.0.0.1: the model a shop's
client finds, its values following a program run, alarms as events, and nothing writable."""

from __future__ import annotations

import asyncio
import shutil
from pathlib import Path
from typing import Any

import pytest
from asyncua import Client, ua

from opcua_server.browse import check_mandatory, find_machine
from tests.opcua.conftest import ClientThread, Served, make_served

MT = "http://opcfoundation.org/UA/MachineTool/"
PROGRAM = "G21 G90\nM3 S6000\nG0 X10 Y10\nG1 X40 F3000\nG1 Y40\nG1 X10\nM5\nM30\n"


async def _node(client: Client, *path: tuple[str, str]) -> Any:
    machine = await find_machine(client)
    parts = []
    for name, uri in path:
        ns = await client.get_namespace_index(uri) if uri else (await client.get_namespace_index(
            "urn:cnc-panel:machine"))
        parts.append(f"{ns}:{name}")
    return await machine.get_child(parts)


MONITORING = ("Monitoring", MT)
CHANNEL = [MONITORING, ("Channel 1", "")]


class Changes:
    """Subscription handler: every value seen, per node."""

    def __init__(self) -> None:
        self.values: dict[str, list[Any]] = {}
        self.events: list[Any] = []
        self.names: dict[Any, str] = {}

    def datachange_notification(self, node: Any, val: Any, data: Any) -> None:
        self.values.setdefault(self.names[node.nodeid], []).append(val)

    def event_notification(self, event: Any) -> None:
        self.events.append(event)


def test_the_model_holds_every_mandatory_node_of_its_types_with_values_of_the_declared_type(
        served: Served, client_thread: ClientThread) -> None:
    async def check() -> Any:
        async with Client(served.url) as c:
            machine = await find_machine(c)
            name = (await machine.read_browse_name()).Name
            result = await check_mandatory(c, machine)
            di = await c.get_namespace_index("http://opcfoundation.org/UA/DI/")
            ident = await machine.get_child([f"{di}:Identification"])
            serial = await (await ident.get_child([f"{di}:SerialNumber"])).read_value()
            model = await (await ident.get_child([f"{di}:Model"])).read_value()
            return name, result, serial, model

    name, result, serial, model = client_thread.run(check())
    assert name == served.ctl.config.machine.name
    assert result.problems == []
    assert result.checked_nodes > 60 and result.checked_declarations > 40
    assert model.Text == served.ctl.config.machine.name
    assert serial.endswith(served.ctl.config.machine.name)


def test_the_conformance_walk_finds_a_missing_mandatory_node_and_a_value_of_the_wrong_type(
        served: Served, client_thread: ClientThread) -> None:
    server = served.ctl.remote.server
    assert server is not None and server._loop is not None

    async def damage() -> None:
        model = server.model
        await model.server.delete_nodes([model.values["ChannelMode"]])
        await model.server.write_attribute_value(
            model.values["IsRotating"].nodeid,
            ua.DataValue(ua.Variant(ua.NodeId(ua.ObjectIds.String),
                                    ua.VariantType.NodeId)), ua.AttributeIds.DataType)
        await model.server.write_attribute_value(model.values["OperationMode"].nodeid,
                                                 ua.DataValue(StatusCode=ua.StatusCode(ua.StatusCodes.BadNoData)))

    asyncio.run_coroutine_threadsafe(damage(), server._loop).result(20)

    async def check() -> Any:
        async with Client(served.url) as c:
            return await check_mandatory(c, await find_machine(c))

    problems = client_thread.run(check()).problems
    assert any("ChannelMode is missing" in p for p in problems), problems
    assert any("IsRotating: data type i=12 is not i=1" in p for p in problems), problems
    assert any("OperationMode: no value" in p for p in problems), problems
    assert len(problems) == 3, problems


def test_a_client_follows_a_program_run_by_subscription(served: Served, client_thread: ClientThread,
                                                        tmp_path: Path) -> None:
    ctl = served.ctl
    program = tmp_path / "square.ngc"
    program.write_text(PROGRAM)
    assert ctl.load_program(program, wait=True)
    served.settle()
    changes = Changes()
    holder: dict[str, Any] = {}

    async def subscribe() -> None:
        c = Client(served.url)
        await c.connect()
        holder["client"] = c
        nodes = {
            "ChannelState": await _node(c, *CHANNEL, ("ChannelState", MT)),
            "IsRotating": await _node(c, MONITORING, ("Spindle", ""), ("IsRotating", MT)),
            "ProgramState": await _node(c, ("Production", MT), ("ActiveProgram", MT), ("State", MT),
                                        ("CurrentState", "http://opcfoundation.org/UA/")),
            "Name": await _node(c, ("Production", MT), ("ActiveProgram", MT), ("Name", MT)),
        }
        for key, node in nodes.items():
            changes.names[node.nodeid] = key
        sub = await c.create_subscription(20, changes)
        await sub.subscribe_data_change(list(nodes.values()))

    client_thread.run(subscribe())
    served.step(0.5)
    assert ctl.cycle_start(wait=True)
    served.until(lambda: ctl.last_run is not None and ctl.state.value == "idle")
    served.step(0.5)
    client_thread.run(holder["client"].disconnect())

    states = [v.Text for v in changes.values["ProgramState"]]
    assert states[0] == "Initializing" and "Running" in states and states[-1] == "Ended", states
    assert states.index("Running") < len(states) - 1
    channel = changes.values["ChannelState"]
    assert 0 in channel and channel[-1] == 2, channel          # Active, then Reset
    rotating = changes.values["IsRotating"]
    assert True in rotating and rotating[-1] is False, rotating
    assert changes.values["Name"][-1] == "square.ngc"


def test_an_alarm_arrives_as_an_event_and_its_acknowledgement_as_another(
        served: Served, client_thread: ClientThread) -> None:
    ctl = served.ctl
    changes = Changes()
    holder: dict[str, Any] = {}

    async def subscribe() -> None:
        c = Client(served.url)
        await c.connect()
        holder["client"] = c
        messages = await _node(c, ("Notification", MT), ("Messages", MT))
        mt = await c.get_namespace_index(MT)
        sub = await c.create_subscription(20, changes)
        await sub.subscribe_events(messages, c.get_node(ua.NodeId(39, mt)))

    client_thread.run(subscribe())
    ctl.estop()
    served.step(0.3)
    assert [a for a in ctl.active_alarms if a.code], ctl.active_alarms
    alarm = ctl.active_alarms[-1]
    served.settle()
    served.step(0.3)
    ctl.acknowledge_alarm(alarm.id)
    served.step(0.3)
    served.settle()
    client_thread.run(holder["client"].disconnect())

    raised = [e for e in changes.events if e.Message.Text.endswith(alarm.cause)]
    assert len(raised) == 2, [e.Message.Text for e in changes.events]
    assert raised[0].Severity == 1000 and raised[0].ErrorCode == alarm.code
    assert raised[0].AckedState.Text == "Unacknowledged" and raised[1].AckedState.Text == "Acknowledged"


def test_no_write_and_no_method_call_is_accepted(served: Served, client_thread: ClientThread) -> None:
    async def attempt() -> tuple[str, str, int]:
        async with Client(served.url) as c:
            mode = await _node(c, MONITORING, ("MachineTool", MT), ("OperationMode", MT))
            try:
                await mode.write_value(ua.Variant(0, ua.VariantType.Int32))
                wrote = "accepted"
            except ua.UaStatusCodeError as exc:
                wrote = type(exc).__name__
            server = c.nodes.server
            try:
                await server.call_method("0:GetMonitoredItems", ua.Variant(1, ua.VariantType.UInt32))
                called = "accepted"
            except ua.UaStatusCodeError as exc:
                called = type(exc).__name__
            level = await mode.read_attribute(ua.AttributeIds.UserAccessLevel)
            return wrote, called, level.Value.Value

    wrote, called, level = client_thread.run(attempt())
    assert wrote == "BadUserAccessDenied"
    assert called == "BadUserAccessDenied"
    assert not level & ua.AccessLevel.CurrentWrite.mask


def _client_certificate(folder: Path) -> tuple[Path, Path]:
    from asyncua.crypto.cert_gen import setup_self_signed_certificate
    from cryptography.x509.oid import ExtendedKeyUsageOID

    key, cert = folder / "client_key.pem", folder / "client_cert.der"
    asyncio.run(setup_self_signed_certificate(key, cert, "urn:test:client", "localhost",
                                              [ExtendedKeyUsageOID.CLIENT_AUTH],
                                              {"commonName": "test client"}))
    return key, cert


def test_the_secure_endpoint_takes_a_trusted_client_and_a_user_and_refuses_the_rest(
        qapp: Any, tmp_path: Path, client_thread: ClientThread) -> None:
    from opcua_server.security import UserFile, folder

    state = tmp_path / "state"
    base = folder(state)
    UserFile(base / "users").add("mes", "correct horse")
    key, cert = _client_certificate(tmp_path)
    shutil.copy(cert, base / "trusted" / "client.der")
    served = make_served(qapp, state, secure=True)
    try:
        server_cert = base / "server_cert.der"
        assert (base / "server_key.pem").stat().st_mode & 0o777 == 0o600
        status = served.ctl.opcua_status
        assert status is not None and len(status.thumbprint) == 40

        async def connect(user: str | None, password: str | None, policy: bool = True,
                          client_key: Path = key, client_cert: Path = cert) -> str:
            c = Client(served.url, timeout=10)
            c.application_uri = "urn:test:client"
            if policy:
                await c.set_security_string(
                    f"Basic256Sha256,SignAndEncrypt,{client_cert},{client_key},{server_cert}")
            if user is not None:
                c.set_user(user)
                c.set_password(password or "")
            try:
                await c.connect()
            except Exception as exc:  # noqa: BLE001 - the refusal is what is looked at
                return type(exc).__name__
            try:
                machine = await find_machine(c)
                return (await machine.read_browse_name()).Name
            finally:
                await c.disconnect()

        name = served.ctl.config.machine.name
        assert client_thread.run(connect("mes", "correct horse")) == name
        assert client_thread.run(connect("mes", "wrong horse")) == "BadUserAccessDenied"
        assert client_thread.run(connect(None, None)) == "BadIdentityTokenRejected"
        assert client_thread.run(connect("mes", "correct horse", policy=False)) != name
        (tmp_path / "other").mkdir()
        other_key, other_cert = _client_certificate(tmp_path / "other")
        assert client_thread.run(connect("mes", "correct horse", client_key=other_key,
                                         client_cert=other_cert)) != name
        assert len(list((base / "rejected").glob("*.der"))) == 1
    finally:
        served.ctl.shutdown()


def test_a_port_in_use_is_a_warning_alarm_and_the_machine_runs_on(qapp: Any, tmp_path: Path) -> None:
    import socket

    from app.machine.config import MachineConfig
    from app.machine.controller import MachineController
    from app.machine.model import Severity

    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        port = taken.getsockname()[1]
        cfg = MachineConfig.default()
        ctl = MachineController(cfg, state_dir=tmp_path / "state", worker_mode="manual",
                                opcua=cfg.opcua.insecure_local(port))
        try:
            server = ctl.remote.server
            assert server is not None
            status = server.wait_ready(60)
            assert not status.running and f"port = {port}" in status.error
            assert ctl.connect_bus()
            ctl.advance(0.1)
            warnings = [a for a in ctl.active_alarms if a.code == "opcua_failed"]
            assert len(warnings) == 1 and warnings[0].severity is Severity.WARNING
            assert str(port) in warnings[0].cause
            ctl.set_machine_zero_here()
            assert ctl.mdi("G1 X5 F600")
            ctl.advance(2.0)
            assert ctl.machine_position[0] == pytest.approx(5.0, abs=1e-3)
        finally:
            ctl.shutdown()
