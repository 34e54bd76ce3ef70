"""The address space: the official nodesets, one MachineToolType instance under Machines,
filled from the machine and kept current from the status snapshot.

Everything typed by the nodesets is made by instantiating their types (asyncua's
``instantiate``), mandatory children only, and the optional parts an operator or MES wants
are instantiated from their declared types one by one. What the specification has no node
for (the program's line, progress and cycle time, the axes' positions) sits in this server's
own namespace beside them.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass, field
from datetime import UTC, datetime
from importlib import resources
from typing import Any

from asyncua import Node, Server, ua
from asyncua.common.instantiate_util import instantiate

from opcua_server.conditions import Conditions, build_conditions
from opcua_server.errors import OpcUaError
from opcua_server.ids import nid
from opcua_server.mapping import AlarmEvent, ProgramState, UaView
from opcua_server.settings import Identity

__all__ = ["NODESETS", "NS_MACHINE", "MachineToolModel", "build_model"]

#: loaded in this order (each needs the ones before): DI 1.03.1, Machinery 1.02.0, IA 1.01.2,
#: Machine Tools 1.01.1 (Machine Tools 1.02 needs the ISA-95 job control nodeset, which asyncua
#: cannot load)
NODESETS = ("Opc.Ua.Di.NodeSet2.xml", "Opc.Ua.Machinery.NodeSet2.xml", "Opc.Ua.IA.NodeSet2.xml",
            "Opc.Ua.MachineTool.NodeSet2.xml")
NS_DI = "http://opcfoundation.org/UA/DI/"
NS_MACHINERY = "http://opcfoundation.org/UA/Machinery/"
NS_IA = "http://opcfoundation.org/UA/IA/"
NS_MT = "http://opcfoundation.org/UA/MachineTool/"
NS_MACHINE = "urn:cnc-panel:machine"

# node ids of the types in their nodesets (Opc.Ua.*.NodeIds.csv)
_MACHINES = 1001                      # Machinery: the Machines folder
_MACHINE_TOOL_TYPE = 13
_CHANNEL_MONITORING_TYPE = 16
_SPINDLE_MONITORING_TYPE = 22
_MESSAGES_TYPE = 38
_CHANNEL_MODIFIER_TYPE = 33
_PROGRAM_STATE_MACHINE_TYPE = 15
_NOTIFICATION_EVENT_TYPE = 35
_ALERT_TYPE = 39
_BASIC_STACKLIGHT_TYPE = 1002         # IA
_STACK_ELEMENT_LIGHT_TYPE = 1006      # IA
_SIGNAL_COLOR_TYPE = 3004            # IA: the SignalColor enumeration
_SIGNAL_COLOR = {"red": 1, "yellow": 4, "green": 2}
_SIGNAL_MODE_LIGHT_TYPE = 3005       # IA: the SignalModeLight enumeration
_SIGNAL_MODE_CONTINUOUS = 0          # the lamps light steadily when on

#: UNECE codes (OPC 10000-8 EngineeringUnits): the unit id is the code's letters as bytes
_UNECE = "http://www.opcfoundation.org/UA/units/un/cefact"


def _unit(code: str, symbol: str, name: str) -> ua.EUInformation:
    unit_id = 0
    for ch in code:
        unit_id = (unit_id << 8) | ord(ch)
    return ua.EUInformation(NamespaceUri=_UNECE, UnitId=unit_id, DisplayName=ua.LocalizedText(symbol),
                            Description=ua.LocalizedText(name))


PERCENT = _unit("P1", "%", "percent")
MILLIMETRE = _unit("MMT", "mm", "millimetre")
DEGREE = _unit("DD", "°", "degree")
RPM = _unit("RPM", "r/min", "revolutions per minute")
SECOND = _unit("SEC", "s", "second")


async def load_nodesets(server: Server) -> None:
    folder = resources.files("opcua_server") / "nodesets"
    for name in NODESETS:
        with resources.as_file(folder / name) as path:
            await server.import_xml(str(path))


@dataclass
class MachineToolModel:
    """The instance's nodes that change, and writing a view to them (only what changed)."""

    server: Server
    machine: Node
    messages: Node
    values: dict[str, Node] = field(default_factory=dict)
    program_state: Node | None = None
    state_ids: dict[ProgramState, tuple[ua.NodeId, int]] = field(default_factory=dict)
    conditions: Conditions | None = None
    _last: dict[str, Any] = field(default_factory=dict)
    _state: ProgramState | None = None
    _power_on: int = -1

    async def write(self, key: str, value: Any, variant: ua.VariantType) -> None:
        if self._last.get(key, _UNSET) == value:
            return
        self._last[key] = value
        # the address space itself: it answers with the status (a value of the wrong type is refused)
        stamped = _stamped(ua.Variant(value, variant), datetime.now(UTC))
        status = await self.server.iserver.aspace.write_attribute_value(self.values[key].nodeid,
                                                                        ua.AttributeIds.Value, stamped)
        if status.is_bad():
            raise OpcUaError(f"OPC UA: {key} refused {value!r}: {status.name}")

    async def update(self, view: UaView, power_on_hours: int) -> None:
        d, b = ua.VariantType.Double, ua.VariantType.Boolean
        i32, u32 = ua.VariantType.Int32, ua.VariantType.UInt32
        await self.write("OperationMode", int(view.operation_mode), i32)
        await self.write("PowerOnDuration", power_on_hours, u32)
        await self.write("MachineFeedOverride", view.feed_override_pct, d)
        await self.write("ChannelState", int(view.channel_state), i32)
        await self.write("ChannelMode", int(view.channel_mode), i32)
        await self.write("FeedOverride", view.feed_override_pct, d)
        await self.write("RapidOverride", view.rapid_override_pct, d)
        await self.write("SingleStep", view.single_block, b)
        await self.write("OptionalStop", view.optional_stop, b)
        await self.write("BlockSkip", view.block_delete, b)
        await self.write("IsRotating", view.spindle_rotating, b)
        await self.write("SpindleOverride", view.spindle_override_pct, d)
        await self.write("CommandedSpeed", view.spindle_commanded_rpm, d)
        await self.write("ProgramName", view.program_name, ua.VariantType.String)
        await self.write("CurrentLine", view.line, u32)
        await self.write("Progress", view.progress_pct, d)
        await self.write("EstimatedCycleTime", view.estimated_cycle_s, d)
        await self.write("RemainingTime", view.remaining_s, d)
        await self.write("ToolInSpindle", view.tool_in_spindle, u32)
        await self.write("MachineState", view.machine_state, ua.VariantType.String)
        for colour in ("red", "yellow", "green"):
            await self.write(f"Light{colour}", getattr(view.stacklight, colour), b)
        for i, (m, w, h) in enumerate(zip(view.machine_pos, view.work_pos, view.homed)):
            if f"MachinePosition{i}" in self.values:
                await self.write(f"MachinePosition{i}", m, d)
                await self.write(f"WorkPosition{i}", w, d)
                await self.write(f"Homed{i}", h, b)
        if view.program_state is not self._state:
            self._state = view.program_state
            node_id, number = self.state_ids[view.program_state]
            await self.write("ProgramStateText", ua.LocalizedText(view.program_state.value, "en"),
                             ua.VariantType.LocalizedText)
            await self.write("ProgramStateId", node_id, ua.VariantType.NodeId)
            await self.write("ProgramStateNumber", number, u32)

    async def emit(self, event: AlarmEvent) -> None:
        """An alarm's condition event (AlertType) or a prompt event, to every notifier."""
        assert self.conditions is not None
        await self.conditions.emit(event)


_UNSET = object()


def _stamped(value: ua.Variant, when: datetime) -> ua.DataValue:
    """The value as set at ``when``: its source and server timestamps."""
    at = ua.DateTime.fromtimestamp(when.timestamp(), UTC)
    return ua.DataValue(value, SourceTimestamp=at, ServerTimestamp=at)


class _Builder:
    def __init__(self, server: Server, idx: int, ns: dict[str, int]) -> None:
        self.server, self.idx, self.ns = server, idx, ns

    def node_id(self, parent: Node, name: str) -> ua.NodeId:
        """A readable id for a node this builder adds: its parent's id, a dot, its name."""
        ident = parent.nodeid.Identifier
        if isinstance(ident, (str, int)):
            base = str(ident)
        else:
            base = parent.nodeid.to_string()
        return nid(f"{base}.{name}", self.idx)

    def type_node(self, uri: str, i: int) -> Node:
        return self.server.get_node(nid(i, self.ns[uri]))

    async def object(self, parent: Node, uri: str, type_id: int, name: str,
                     name_uri: str | None = None) -> Node:
        """An instance of a type of ``uri``; its browse name in the namespace ``name_uri``
        that declared it (the type's, by default; "": this server's, for a placeholder's)."""
        ns = self.idx if name_uri == "" else self.ns[name_uri or uri]
        nodes = await instantiate(parent, self.type_node(uri, type_id), bname=ua.QualifiedName(name, ns),
                                  dname=ua.LocalizedText(name), idx=self.idx, instantiate_optional=False)
        return nodes[0]

    async def analog(self, parent: Node, name: str, name_uri: str | None, unit: ua.EUInformation,
                     lo: float, hi: float) -> Node:
        """An AnalogUnitRangeType variable of Double with its unit and range."""
        ns = self.ns[name_uri] if name_uri else self.idx
        nodes = await instantiate(parent, self.server.get_node(nid(ua.ObjectIds.AnalogUnitRangeType)),
                                  bname=ua.QualifiedName(name, ns), dname=ua.LocalizedText(name),
                                  idx=self.idx, instantiate_optional=False)
        var = nodes[0]
        await var.write_attribute(ua.AttributeIds.DataType,
                                  ua.DataValue(ua.Variant(nid(ua.ObjectIds.Double),
                                                          ua.VariantType.NodeId)))
        await var.write_value(ua.Variant(0.0, ua.VariantType.Double))
        await (await var.get_child("0:EngineeringUnits")).write_value(unit)
        await (await var.get_child("0:EURange")).write_value(ua.Range(lo, hi))
        return var

    async def variable(self, parent: Node, name: str, name_uri: str | None, value: Any,
                       variant: ua.VariantType, datatype: int | ua.NodeId | None = None) -> Node:
        ns = self.ns[name_uri] if name_uri else self.idx
        return await parent.add_variable(self.node_id(parent, name), ua.QualifiedName(name, ns),
                                         ua.Variant(value, variant),
                                         datatype=nid(datatype) if isinstance(datatype,
                                                                                    int) else datatype)

    async def prop(self, parent: Node, name: str, name_uri: str, value: Any, variant: ua.VariantType) -> Node:
        return await parent.add_property(self.node_id(parent, name), ua.QualifiedName(name,
                                                                                      self.ns[name_uri]),
                                         ua.Variant(value, variant))


async def _child(node: Node, *path: tuple[str, int]) -> Node:
    return await node.get_child([f"{ns}:{name}" for name, ns in path])


async def _named(node: Node, name: str) -> Node:
    """The child of that browse name, whichever nodeset declared it."""
    for child in await node.get_children(refs=ua.ObjectIds.HierarchicalReferences):
        if (await child.read_browse_name()).Name == name:
            return child
    raise LookupError(f"{node.nodeid.to_string()} has no child {name}")


async def build_model(server: Server, identity: Identity, axes: tuple[tuple[str, bool], ...],
                      machine_name: str) -> MachineToolModel:
    """Load the nodesets and make the machine's instance; ``axes`` are (name, rotary)."""
    logging.getLogger("asyncua.common.xmlimporter").setLevel(logging.ERROR)
    logging.getLogger("asyncua.common.structures104").setLevel(logging.ERROR)
    await load_nodesets(server)
    idx = await server.register_namespace(NS_MACHINE)
    ns = {uri: await server.get_namespace_index(uri) for uri in (NS_DI, NS_MACHINERY, NS_IA, NS_MT)}
    mt, mach = ns[NS_MT], ns[NS_MACHINERY]
    b = _Builder(server, idx, ns)
    machines = server.get_node(nid(_MACHINES, mach))
    machine = (await instantiate(machines, b.type_node(NS_MT, _MACHINE_TOOL_TYPE),
                                 bname=ua.QualifiedName(machine_name,
                                                        idx), dname=ua.LocalizedText(machine_name),
                                 idx=idx, instantiate_optional=False))[0]
    model = MachineToolModel(server=server, machine=machine, messages=machine)

    # Identification: the mandatory three, and the model and software revision
    ident = await _child(machine, ("Identification", ns[NS_DI]))
    await (await _child(ident, ("Manufacturer", ns[NS_DI]))).write_value(
        ua.LocalizedText(identity.manufacturer, "en"))
    await (await _child(ident, ("SerialNumber", ns[NS_DI]))).write_value(identity.serial_number)
    await (await _child(ident, ("ProductInstanceUri", ns[NS_DI]))).write_value(identity.product_instance_uri)
    await b.prop(ident, "Model", NS_DI, ua.LocalizedText(identity.model, "en"), ua.VariantType.LocalizedText)
    await b.prop(ident, "SoftwareRevision", NS_DI, identity.software_revision, ua.VariantType.String)
    await _identification(b, ident, identity)

    # Monitoring: the machine, a stack light, the channel with its axes, the spindle
    monitoring = await _child(machine, ("Monitoring", mt))
    mtm = await _child(monitoring, ("MachineTool", mt))
    v = model.values
    v["OperationMode"] = await _child(mtm, ("OperationMode", mt))
    v["PowerOnDuration"] = await b.variable(mtm, "PowerOnDuration", NS_MT, 0, ua.VariantType.UInt32,
                                            ua.ObjectIds.UInt32)
    v["MachineFeedOverride"] = await b.analog(mtm, "FeedOverride", NS_MT, PERCENT, 0.0, 200.0)
    await _stacklight(b, monitoring, v)
    channel = await b.object(monitoring, NS_MT, _CHANNEL_MONITORING_TYPE, "Channel 1", "")
    await (await _child(channel, ("Name", mt))).write_value("Channel 1")
    v["ChannelState"] = await _child(channel, ("ChannelState", mt))
    v["ChannelMode"] = await _child(channel, ("ChannelMode", mt))
    v["FeedOverride"] = await _child(channel, ("FeedOverride", mt))
    await (await v["FeedOverride"].get_child("0:EngineeringUnits")).write_value(PERCENT)
    await (await v["FeedOverride"].get_child("0:EURange")).write_value(ua.Range(0.0, 200.0))
    v["RapidOverride"] = await b.analog(channel, "RapidOverride", NS_MT, PERCENT, 0.0, 100.0)
    modifiers = await b.object(channel, NS_MT, _CHANNEL_MODIFIER_TYPE, "ChannelModifiers")
    v["SingleStep"] = await _child(modifiers, ("SingleStep", mt))
    v["OptionalStop"] = await _child(modifiers, ("OptionalStop", mt))
    await (await _child(modifiers, ("DryRun", mt))).write_value(False)
    v["BlockSkip"] = await b.variable(modifiers, "BlockSkip", NS_MT, False, ua.VariantType.Boolean,
                                      ua.ObjectIds.Boolean)
    v["ToolInSpindle"] = await b.variable(channel, "ToolInSpindle", None, 0, ua.VariantType.UInt32,
                                          ua.ObjectIds.UInt32)
    v["MachineState"] = await b.variable(channel, "MachineState", None, "", ua.VariantType.String,
                                         ua.ObjectIds.String)
    axes_folder = await channel.add_folder(b.node_id(channel, "Axes"), ua.QualifiedName("Axes", idx))
    for i, (name, rotary) in enumerate(axes):
        axis = await axes_folder.add_object(b.node_id(axes_folder, name), ua.QualifiedName(name, idx))
        unit = DEGREE if rotary else MILLIMETRE
        v[f"MachinePosition{i}"] = await b.analog(axis, "MachinePosition", None, unit, -1e6, 1e6)
        v[f"WorkPosition{i}"] = await b.analog(axis, "WorkPosition", None, unit, -1e6, 1e6)
        v[f"Homed{i}"] = await b.variable(axis, "Homed", None, False, ua.VariantType.Boolean,
                                          ua.ObjectIds.Boolean)
    spindle = await b.object(monitoring, NS_MT, _SPINDLE_MONITORING_TYPE, "Spindle", "")
    await (await _child(spindle, ("Name", mt))).write_value("Spindle")
    v["IsRotating"] = await _child(spindle, ("IsRotating", mt))
    v["SpindleOverride"] = await b.analog(spindle, "Override", NS_MT, PERCENT, 0.0, 200.0)
    v["CommandedSpeed"] = await b.analog(spindle, "CommandedSpeed", None, RPM, 0.0, 1e6)

    # Production: the active program, its state machine, and where it is
    active = await _child(machine, ("Production", mt), ("ActiveProgram", mt))
    v["ProgramName"] = await _child(active, ("Name", mt))
    await (await _child(active, ("NumberInList", 0))).write_value(ua.Variant(0, ua.VariantType.UInt16))
    current = await _child(active, ("State", mt), ("CurrentState", 0))
    v["ProgramStateText"] = current
    v["ProgramStateId"] = await current.get_child("0:Id")
    v["ProgramStateNumber"] = await current.get_child("0:Number")
    sm_type = b.type_node(NS_MT, _PROGRAM_STATE_MACHINE_TYPE)
    for state in ProgramState:
        state_node = await sm_type.get_child(f"{mt}:{state.value}")
        number = await (await state_node.get_child("0:StateNumber")).read_value()
        model.state_ids[state] = (state_node.nodeid, int(number))
    v["CurrentLine"] = await b.variable(active, "CurrentLine", None, 0, ua.VariantType.UInt32,
                                        ua.ObjectIds.UInt32)
    v["Progress"] = await b.analog(active, "Progress", None, PERCENT, 0.0, 100.0)
    v["EstimatedCycleTime"] = await b.analog(active, "EstimatedCycleTime", None, SECOND, 0.0, 1e9)
    v["RemainingTime"] = await b.analog(active, "RemainingTime", None, SECOND, 0.0, 1e9)

    # Notification: the Messages object, the source of every alarm and message event
    notification = await _child(machine, ("Notification", mt))
    messages = await b.object(notification, NS_MT, _MESSAGES_TYPE, "Messages")
    model.messages = messages
    model.conditions = await build_conditions(server, machine, machine_name, messages,
                                              b.type_node(NS_MT, _ALERT_TYPE),
                                              b.type_node(NS_MT, _NOTIFICATION_EVENT_TYPE), idx)
    return model


async def _identification(b: _Builder, ident: Node, identity: Identity) -> None:
    """The optional Identification fields the configuration gives (an empty one is left out)."""
    texts = (("ProductCode", NS_DI, identity.product_code),
             ("ManufacturerUri", NS_DI, identity.manufacturer_uri),
             ("HardwareRevision", NS_DI, identity.hardware_revision),
             ("DeviceClass", NS_DI, identity.device_class),
             ("AssetId", NS_DI, identity.asset_id),
             ("Location", NS_MACHINERY, identity.location))
    for name, uri, text in texts:
        if text:
            await b.prop(ident, name, uri, text, ua.VariantType.String)
    if identity.year_of_construction:
        await b.prop(ident, "YearOfConstruction", NS_MACHINERY, identity.year_of_construction,
                     ua.VariantType.UInt16)
    if identity.month_of_construction:
        await b.prop(ident, "MonthOfConstruction", NS_MACHINERY, identity.month_of_construction,
                     ua.VariantType.Byte)


async def _stacklight(b: _Builder, monitoring: Node, v: dict[str, Node]) -> None:
    light = await b.object(monitoring, NS_IA, _BASIC_STACKLIGHT_TYPE, "Stacklight", NS_MT)
    await (await _named(light, "StacklightMode")).write_value(ua.Variant(0, ua.VariantType.Int32))
    for number, colour in enumerate(("red", "yellow", "green")):
        name = f"{colour.capitalize()}Light"
        element = (await instantiate(light, b.type_node(NS_IA, _STACK_ELEMENT_LIGHT_TYPE),
                                     bname=ua.QualifiedName(name, b.idx), dname=ua.LocalizedText(name),
                                     idx=b.idx, instantiate_optional=False))[0]
        await light.delete_reference(element.nodeid, ua.ObjectIds.HasComponent, forward=True,
                                     bidirectional=True)
        await light.add_reference(element.nodeid, ua.ObjectIds.HasOrderedComponent)
        await (await _named(element, "NumberInList")).write_value(
            ua.Variant(number, ua.VariantType.UInt32))
        await b.variable(element, "SignalColor", NS_IA, _SIGNAL_COLOR[colour], ua.VariantType.Int32,
                         nid(_SIGNAL_COLOR_TYPE, b.ns[NS_IA]))
        await b.variable(element, "SignalMode", NS_IA, _SIGNAL_MODE_CONTINUOUS, ua.VariantType.Int32,
                         nid(_SIGNAL_MODE_LIGHT_TYPE, b.ns[NS_IA]))
        v[f"Light{colour}"] = await b.prop(element, "SignalOn", NS_IA, False, ua.VariantType.Boolean)
