"""Alarms as OPC UA conditions through asyncua's client: the events reach a subscription on the
Server object, on the machine and on Messages with every condition field filled; a client that
connects late learns the active alarms with ConditionRefresh; an alarm that needs no
acknowledgement goes inactive when it is cleared; prompts are events of a concrete type; every
value carries its timestamps; the server counts its sessions."""

from __future__ import annotations

from typing import Any

from asyncua import Client, ua

from opcua_server.browse import find_machine
from tests.opcua.conftest import ClientThread, Served

MT = "http://opcfoundation.org/UA/MachineTool/"
FIELDS = ("ConditionClassId", "ConditionClassName", "ConditionName", "BranchId", "Retain", "EnabledState",
          "EnabledState/Id", "Quality", "LastSeverity", "Comment", "ClientUserId", "ActiveState",
          "ActiveState/Id", "AckedState", "AckedState/Id", "InputNode", "SuppressedOrShelved", "ErrorCode")


class Events:
    def __init__(self) -> None:
        self.events: list[Any] = []

    def event_notification(self, event: Any) -> None:
        self.events.append(event)

    def conditions(self, text: str) -> list[Any]:
        return [e for e in self.events if getattr(e, "Message", None) is not None and text in e.Message.Text]


class Watcher:
    """A client with one subscription per notifier: the Server object, the machine, Messages."""

    def __init__(self, served: Served, client_thread: ClientThread) -> None:
        self.served, self.ct = served, client_thread
        self.on = {"server": Events(), "machine": Events(), "messages": Events()}
        self.client = Client(served.url, timeout=10)
        self.subs: dict[str, Any] = {}

    async def start(self) -> None:
        c = self.client
        await c.connect()
        machine = await find_machine(c)
        mt = await c.get_namespace_index(MT)
        messages = await machine.get_child([f"{mt}:Notification", f"{mt}:Messages"])
        alert = c.get_node(ua.NodeId(39, mt))
        for key, node in (("server", c.nodes.server), ("machine", machine), ("messages", messages)):
            sub = await c.create_subscription(20, self.on[key])
            await sub.subscribe_events(node, alert)
            self.subs[key] = sub

    async def refresh(self, key: str) -> None:
        sub_id = self.subs[key].subscription_id
        await self.client.get_node(ua.NodeId(ua.ObjectIds.ConditionType)).call_method(
            ua.NodeId(ua.ObjectIds.ConditionType_ConditionRefresh), ua.Variant(sub_id, ua.VariantType.UInt32))


def _watch(served: Served, client_thread: ClientThread) -> Watcher:
    w = Watcher(served, client_thread)
    client_thread.run(w.start())
    return w


def test_an_estop_reaches_every_notifier_as_one_condition_event_with_every_field(
        served: Served, client_thread: ClientThread) -> None:
    ctl = served.ctl
    w = _watch(served, client_thread)
    try:
        ctl.estop()
        served.step(0.3)
        served.settle()
        alarm = [a for a in ctl.active_alarms if a.code == "estop"][-1]
        seen = {key: events.conditions(alarm.cause) for key, events in w.on.items()}
        assert {key: len(found) for key, found in seen.items()} == {"server": 1, "machine": 1, "messages": 1}
        e = seen["server"][0]
        assert len({found[0].EventId for found in seen.values()}) == 1      # one event, three notifiers
        missing = [name for name in FIELDS if getattr(e, name, None) is None]
        assert missing == []
        assert e.ConditionClassId == ua.NodeId(ua.ObjectIds.SafetyConditionClassType)
        assert e.ConditionClassName.Text == "SafetyConditionClassType"
        assert e.BranchId == ua.NodeId()                                   # the main branch
        assert e.Retain is True and e.EnabledState.Text == "Enabled" and getattr(e, "EnabledState/Id") is True
        assert getattr(e, "ActiveState/Id") is True and getattr(e, "AckedState/Id") is False
        assert e.Quality.is_good() and e.LastSeverity == e.Severity == 1000
        assert e.ErrorCode == "estop" and e.SourceName == ctl.config.machine.name
        assert e.NodeId.Identifier == f"Alarms.{alarm.id}"              # the ConditionId
    finally:
        client_thread.run(w.client.disconnect())


def test_a_client_that_connects_late_learns_the_active_alarm_by_condition_refresh(
        served: Served, client_thread: ClientThread) -> None:
    ctl = served.ctl
    ctl.estop()
    served.step(0.3)
    served.settle()
    alarm = [a for a in ctl.active_alarms if a.code == "estop"][-1]
    w = _watch(served, client_thread)
    try:
        served.step(0.2)
        assert w.on["server"].conditions(alarm.cause) == []              # nothing told on its own
        client_thread.run(w.refresh("server"))
        served.step(0.2)
        served.settle()
        found = w.on["server"].conditions(alarm.cause)
        assert len(found) == 1 and found[0].Retain is True and getattr(found[0], "ActiveState/Id") is True
        assert w.on["machine"].conditions(alarm.cause) == []             # only the caller's subscription
        # acknowledged at the panel: told once, and left out of the replay after
        ctl.acknowledge_alarm(alarm.id)
        served.step(0.2)
        served.settle()
        acked = w.on["server"].conditions(alarm.cause)[-1]
        assert getattr(acked, "AckedState/Id") is True and acked.Retain is False
        before = len(w.on["server"].conditions(alarm.cause))
        client_thread.run(w.refresh("server"))
        served.step(0.2)
        served.settle()
        assert len(w.on["server"].conditions(alarm.cause)) == before
    finally:
        client_thread.run(w.client.disconnect())


def test_a_warning_needs_no_acknowledgement_and_goes_inactive_when_cleared(
        served: Served, client_thread: ClientThread) -> None:
    from app.machine.model import Severity

    ctl = served.ctl
    w = _watch(served, client_thread)
    try:
        alarm = ctl.alarm_log.raise_alarm("opcua", "a warning for the shop", Severity.WARNING, "opcua_failed")
        served.step(0.2)
        served.settle()
        raised = w.on["messages"].conditions(alarm.cause)
        assert len(raised) == 1
        assert getattr(raised[0], "ActiveState/Id") is True and getattr(raised[0], "AckedState/Id") is True
        assert raised[0].Retain is True
        assert raised[0].ConditionClassId == ua.NodeId(ua.ObjectIds.SystemConditionClassType)
        ctl.acknowledge_alarm(alarm.id)                 # the operator clears it
        served.step(0.2)
        served.settle()
        cleared = w.on["messages"].conditions(alarm.cause)
        assert len(cleared) == 2
        assert getattr(cleared[1], "ActiveState/Id") is False and cleared[1].Retain is False
        # the ConditionId (asyncua's client names it NodeId): one condition for both events
        assert cleared[1].NodeId == raised[0].NodeId and cleared[1].NodeId.Identifier == f"Alarms.{alarm.id}"
    finally:
        client_thread.run(w.client.disconnect())


def test_a_program_prompt_is_an_event_of_a_concrete_subtype_of_notification_event_type(
        served: Served, client_thread: ClientThread, tmp_path: Any) -> None:
    ctl = served.ctl
    program = tmp_path / "stop.ngc"
    program.write_text("G21 G90\nG0 X5\nM0\nG0 X0\nM30\n")
    assert ctl.load_program(program, wait=True)
    events = Events()
    holder: dict[str, Any] = {}

    async def subscribe() -> None:
        c = Client(served.url, timeout=10)
        await c.connect()
        holder["c"] = c
        machine = await find_machine(c)
        mt = await c.get_namespace_index(MT)
        own = await c.get_namespace_index("urn:cnc-panel:machine")
        prompt_type = c.get_node(ua.NodeId("PromptEventType", own))
        holder["abstract"] = await prompt_type.read_attribute(ua.AttributeIds.IsAbstract)
        parents = await prompt_type.get_referenced_nodes(ua.ObjectIds.HasSubtype, ua.BrowseDirection.Inverse)
        holder["parent"] = parents[0].nodeid
        holder["mt"] = mt
        messages = await machine.get_child([f"{mt}:Notification", f"{mt}:Messages"])
        sub = await c.create_subscription(20, events)
        await sub.subscribe_events(messages, prompt_type)

    client_thread.run(subscribe())
    try:
        assert ctl.cycle_start(wait=True)
        served.until(lambda: ctl.prompt is not None)
        served.step(0.2)
        served.settle()
        told = events.conditions("M00, line 3")
        assert len(told) == 1
        assert told[0].Identifier == "line-3-program_stop" and told[0].Severity == 200
        assert told[0].EventType == ua.NodeId("PromptEventType", told[0].EventType.NamespaceIndex)
        assert holder["abstract"].Value.Value is False
        assert holder["parent"] == ua.NodeId(35, holder["mt"])           # MT's NotificationEventType
    finally:
        client_thread.run(holder["c"].disconnect())


def test_every_value_of_the_machine_carries_source_and_server_timestamps(
        served: Served, client_thread: ClientThread) -> None:
    seen: list[Any] = []
    holder: dict[str, Any] = {}

    class Changes:
        def datachange_notification(self, node: Any, val: Any, data: Any) -> None:
            seen.append(data.monitored_item.Value)

    async def walk() -> tuple[int, list[str]]:
        c = Client(served.url, timeout=10)
        await c.connect()
        holder["c"] = c
        machine = await find_machine(c)
        own = machine.nodeid.NamespaceIndex
        todo, done, missing, count = [machine], {machine.nodeid}, [], 0
        while todo:
            node = todo.pop()
            for child in await node.get_children(refs=ua.ObjectIds.HierarchicalReferences):
                if child.nodeid in done or child.nodeid.NamespaceIndex != own:
                    continue
                done.add(child.nodeid)
                todo.append(child)
                if await child.read_node_class() != ua.NodeClass.Variable:
                    continue
                count += 1
                dv = await child.read_data_value(raise_on_bad_status=False)
                if dv.SourceTimestamp is None or dv.ServerTimestamp is None:
                    missing.append((await child.read_browse_name()).Name)
        mt = await c.get_namespace_index(MT)
        state = await machine.get_child([f"{mt}:Monitoring", f"{own}:Channel 1", f"{mt}:ChannelState"])
        sub = await c.create_subscription(20, Changes())
        await sub.subscribe_data_change(state)
        return count, missing

    count, missing = client_thread.run(walk())
    try:
        assert count > 60 and missing == []
        assert served.ctl.mdi("G1 X5 F600")
        served.step(1.0)
        served.settle()
        assert len(seen) >= 3                           # the first value, Active, then Reset
        assert all(dv.SourceTimestamp is not None and dv.ServerTimestamp is not None for dv in seen)
    finally:
        client_thread.run(holder["c"].disconnect())


def test_the_server_diagnostics_are_enabled_and_count_the_sessions(
        served: Served, client_thread: ClientThread) -> None:
    async def read() -> tuple[bool, Any]:
        async with Client(served.url, timeout=10):
            pass                                        # one session opened and closed
        async with Client(served.url, timeout=10) as c:
            await __import__("asyncio").sleep(1.5)      # the summary is counted once a second
            flag = await c.get_node(ua.NodeId(ua.ObjectIds.Server_ServerDiagnostics_EnabledFlag)).read_value()
            summary = await c.get_node(
                ua.NodeId(ua.ObjectIds.Server_ServerDiagnostics_ServerDiagnosticsSummary)).read_value()
            return flag, summary

    flag, summary = client_thread.run(read())
    assert flag is True
    assert summary.CurrentSessionCount == 1 and summary.CumulatedSessionCount >= 2
    assert summary.SessionTimeoutCount == 0 and summary.SecurityRejectedSessionCount == 0
