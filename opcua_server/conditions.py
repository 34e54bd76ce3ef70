"""Alarms as OPC UA conditions (OPC 10000-9) and program prompts as events, delivered through
the notifier hierarchy.

Every alarm of the panel is a condition of Machine Tools' ``AlertType`` (an
AlarmConditionType): each event carries its ConditionId, class, EnabledState, Quality, Retain,
ActiveState, AckedState, Severity and LastSeverity, Comment and ClientUserId. What the states
mean is decided in ``mapping.AlarmEvent``. Conditions are not exposed as nodes (OPC 10000-9
allows that): their ConditionIds name them, and the server is read-only, so no client
acknowledges through them; the operator does, at the panel.

Events go to a subscription on ``Messages``, on the machine and on the Server object (the
Server HasNotifier the machine, the machine HasNotifier Messages), each one with one EventId
whichever notifier it came through. ``ConditionRefresh`` and ``ConditionRefresh2`` replay
the conditions that are retained (active, or still to be acknowledged) between a
RefreshStartEvent and a RefreshEndEvent, to the subscription that asked.
"""

from __future__ import annotations

import copy
import time
import uuid
from dataclasses import dataclass, field
from datetime import UTC, datetime
from typing import Any

from asyncua import Node, Server, ua
from asyncua.common import events
from asyncua.common.methods import uamethod

from opcua_server.ids import nid
from opcua_server.mapping import AlarmEvent, ConditionClass

__all__ = ["Conditions", "build_conditions"]

_CONDITION_CLASS = {
    ConditionClass.PROCESS: (ua.ObjectIds.ProcessConditionClassType, "ProcessConditionClassType"),
    ConditionClass.SYSTEM: (ua.ObjectIds.SystemConditionClassType, "SystemConditionClassType"),
    ConditionClass.SAFETY: (ua.ObjectIds.SafetyConditionClassType, "SafetyConditionClassType")}


def _status(code: int) -> ua.StatusCode:
    return ua.StatusCode(ua.UInt32(code))


def _set(event: Any, name: str, value: Any, variant: ua.VariantType) -> None:
    # the event object types a property from its data type node and leaves Null where that
    # is not a built-in type: the value is typed here
    setattr(event, name, value)
    event.data_types[name] = variant


def _stamp(event: Any, when: datetime) -> None:
    _set(event, "EventId", uuid.uuid4().hex.encode("ascii"), ua.VariantType.ByteString)
    _set(event, "Time", when, ua.VariantType.DateTime)
    _set(event, "ReceiveTime", when, ua.VariantType.DateTime)
    offset = ua.TimeZoneDataType()
    local = time.localtime(when.timestamp())
    offset.Offset = local.tm_gmtoff // 60
    offset.DaylightSavingInOffset = bool(local.tm_isdst > 0)
    _set(event, "LocalTime", offset, ua.VariantType.ExtensionObject)


@dataclass
class Conditions:
    """The event templates, the notifiers and the retained conditions of one server."""

    server: Server
    source: Node                        # the machine: SourceNode of every event
    source_name: str
    notifiers: tuple[ua.NodeId, ...]    # Messages, the machine, the Server object
    alert: Any                          # the AlertType event object, copied for each event
    prompt: Any                         # the prompt event type's event object
    refresh_start: Any
    refresh_end: Any
    condition_ns: int
    retained: dict[ua.NodeId, Any] = field(default_factory=dict)
    refreshes: int = 0

    def condition_id(self, alarm_id: int) -> ua.NodeId:
        return nid(f"Alarms.{alarm_id}", self.condition_ns)

    async def emit(self, event: AlarmEvent) -> None:
        """The event to every subscription that watches one of the notifiers."""
        when = datetime.now(UTC)
        e = copy.deepcopy(self.prompt if event.alarm is None else self.alert)
        _stamp(e, when)
        _set(e, "SourceNode", self.source.nodeid, ua.VariantType.NodeId)
        _set(e, "SourceName", self.source_name, ua.VariantType.String)
        _set(e, "Message", ua.LocalizedText(event.message, "en"), ua.VariantType.LocalizedText)
        _set(e, "Severity", event.severity, ua.VariantType.UInt16)
        if event.alarm is None:
            _set(e, "Identifier", event.identifier, ua.VariantType.String)
        else:
            self._condition(e, event, when)
        await self._deliver(e, self.server.iserver.subscription_service.subscriptions.values())

    def _condition(self, e: Any, event: AlarmEvent, when: datetime) -> None:
        assert event.alarm is not None
        alarm = event.alarm
        cid = self.condition_id(alarm.id)
        class_id, class_name = _CONDITION_CLASS[event.condition_class]
        b, text = ua.VariantType.Boolean, ua.VariantType.LocalizedText
        _set(e, "NodeId", cid, ua.VariantType.NodeId)                  # the ConditionId
        _set(e, "ConditionClassId", nid(class_id), ua.VariantType.NodeId)
        _set(e, "ConditionClassName", ua.LocalizedText(class_name, "en"), text)
        _set(e, "ConditionName", alarm.code or "alarm", ua.VariantType.String)
        _set(e, "BranchId", ua.NodeId(), ua.VariantType.NodeId)         # the main branch: null
        _set(e, "ErrorCode", alarm.code or event.identifier, ua.VariantType.String)
        _set(e, "Retain", event.retain, b)
        _set(e, "EnabledState", ua.LocalizedText("Enabled", "en"), text)
        _set(e, "EnabledState/Id", True, b)
        _set(e, "Quality", _status(ua.StatusCodes.Good), ua.VariantType.StatusCode)
        _set(e, "Quality/SourceTimestamp", when, ua.VariantType.DateTime)
        _set(e, "LastSeverity", event.severity, ua.VariantType.UInt16)
        _set(e, "LastSeverity/SourceTimestamp", when, ua.VariantType.DateTime)
        _set(e, "Comment", ua.LocalizedText("", "en"), text)
        _set(e, "Comment/SourceTimestamp", when, ua.VariantType.DateTime)
        _set(e, "ClientUserId", "", ua.VariantType.String)
        _set(e, "ActiveState", ua.LocalizedText("Active" if event.active else "Inactive", "en"), text)
        _set(e, "ActiveState/Id", event.active, b)
        acked = event.acked_state
        _set(e, "AckedState", ua.LocalizedText("Acknowledged" if acked else "Unacknowledged", "en"), text)
        _set(e, "AckedState/Id", acked, b)
        _set(e, "InputNode", ua.NodeId(), ua.VariantType.NodeId)
        _set(e, "SuppressedOrShelved", False, b)
        if event.retain:
            self.retained[cid] = e
        else:
            self.retained.pop(cid, None)

    async def _deliver(self, e: Any, subscriptions: Any, mid: int | None = None) -> None:
        """``e`` to each subscription, through every notifier it watches (or to the one
        monitored item ``mid``, through the notifier that item watches)."""
        for sub in list(subscriptions):
            watched = sub.monitored_item_srv._monitored_events
            for node in self.notifiers:
                mids = watched.get(node)
                if not mids or (mid is not None and mid not in mids):
                    continue
                one = copy.copy(e)
                one.emitting_node = node
                await sub.monitored_item_srv.trigger_event(one, mid)

    async def refresh(self, subscription_id: int, mid: int | None = None) -> ua.StatusCode:
        service = self.server.iserver.subscription_service
        sub = service.subscriptions.get(subscription_id)
        if sub is None:
            return _status(ua.StatusCodes.BadSubscriptionIdInvalid)
        if mid is not None and mid not in sub.monitored_item_srv._monitored_items:
            return _status(ua.StatusCodes.BadMonitoredItemIdInvalid)
        self.refreshes += 1
        when = datetime.now(UTC)
        start, end = copy.deepcopy(self.refresh_start), copy.deepcopy(self.refresh_end)
        _stamp(start, when)
        _stamp(end, when)
        for e in (start, *self.retained.values(), end):
            await self._deliver(e, (sub,), mid)
        return _status(ua.StatusCodes.Good)


async def _event_object(server: Server, type_id: ua.NodeId) -> Any:
    return await events.get_event_obj_from_type_node(server.get_node(type_id))


async def build_conditions(server: Server, machine: Node, machine_name: str, messages: Node,
                           alert_type: Node, notification_type: Node, idx: int) -> Conditions:
    """The notifier hierarchy, the prompt's event type, the event templates and the
    ConditionRefresh methods of a server whose address space holds the machine."""
    server_node = server.nodes.server
    for node in (messages, machine):
        await node.set_event_notifier([ua.EventNotifier.SubscribeToEvents])
    await server_node.add_reference(machine.nodeid, ua.ObjectIds.HasNotifier)
    await machine.add_reference(messages.nodeid, ua.ObjectIds.HasNotifier)
    prompt_type = await notification_type.add_object_type(
        nid("PromptEventType", idx), ua.QualifiedName("PromptEventType", idx))
    await prompt_type.write_attribute(ua.AttributeIds.Description, ua.DataValue(ua.Variant(
        ua.LocalizedText("A program stop that asks the operator for something: an M0 or M1 message, "
                         "a tool change, a single block", "en"), ua.VariantType.LocalizedText)))
    for event_type in (alert_type, prompt_type):
        await messages.add_reference(event_type.nodeid, ua.ObjectIds.GeneratesEvent)
    alert = await _event_object(server, alert_type.nodeid)
    alert.add_property("NodeId", None, ua.VariantType.NodeId)      # the ConditionId
    conditions = Conditions(
        server=server, source=machine, source_name=machine_name,
        notifiers=(messages.nodeid, machine.nodeid, server_node.nodeid),
        alert=alert, prompt=await _event_object(server, prompt_type.nodeid),
        refresh_start=await _event_object(server, nid(ua.ObjectIds.RefreshStartEventType)),
        refresh_end=await _event_object(server, nid(ua.ObjectIds.RefreshEndEventType)), condition_ns=idx)
    for template in (conditions.refresh_start, conditions.refresh_end):
        _set(template, "SourceNode", server_node.nodeid, ua.VariantType.NodeId)
        _set(template, "SourceName", "Server", ua.VariantType.String)
        _set(template, "Severity", 1, ua.VariantType.UInt16)

    @uamethod
    async def refresh(parent: ua.NodeId, subscription_id: int) -> ua.StatusCode:
        return await conditions.refresh(int(subscription_id))

    @uamethod
    async def refresh2(parent: ua.NodeId, subscription_id: int, mid: int) -> ua.StatusCode:
        return await conditions.refresh(int(subscription_id), int(mid))

    session = server.iserver.isession
    session.add_method_callback(nid(ua.ObjectIds.ConditionType_ConditionRefresh), refresh)
    session.add_method_callback(nid(ua.ObjectIds.ConditionType_ConditionRefresh2), refresh2)
    return conditions
