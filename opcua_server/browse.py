"""Reading the server as a client does: the machine's instance found under Machines, printed
as a tree (``cnc-opcua``), and checked against its types (every Mandatory instance
declaration of each node's type, its supertypes and interfaces is there, and each variable
holds a value of the declared data type)."""

from __future__ import annotations

from dataclasses import dataclass, field

from asyncua import Client, Node, ua

from opcua_server.ids import nid

__all__ = ["Conformance", "check_mandatory", "find_machine", "tree"]

_MANDATORY = nid(ua.ObjectIds.ModellingRule_Mandatory)
_HAS_INTERFACE = 17603
_NUMERIC = {ua.VariantType.SByte, ua.VariantType.Byte, ua.VariantType.Int16, ua.VariantType.UInt16,
            ua.VariantType.Int32, ua.VariantType.UInt32, ua.VariantType.Int64, ua.VariantType.UInt64,
            ua.VariantType.Float, ua.VariantType.Double}
_UNSIGNED = {ua.VariantType.Byte, ua.VariantType.UInt16, ua.VariantType.UInt32, ua.VariantType.UInt64}


async def find_machine(client: Client) -> Node:
    """The first machine under Machinery's Machines folder."""
    ns = await client.get_namespace_index("http://opcfoundation.org/UA/Machinery/")
    machines = client.get_node(nid(1001, ns))
    children = await machines.get_children()
    if not children:
        raise LookupError("the Machines folder is empty")
    return children[0]


async def tree(node: Node, depth: int = 0, max_depth: int = 8) -> list[str]:
    """The instance as indented lines: browse name, then the value of a variable."""
    lines: list[str] = []
    for child in await node.get_children(refs=ua.ObjectIds.HierarchicalReferences):
        name = (await child.read_browse_name()).Name
        text = "  " * depth + name
        if await child.read_node_class() == ua.NodeClass.Variable:
            value = await child.read_value()
            text += f" = {_show(value)}"
        lines.append(text)
        if depth < max_depth:
            lines += await tree(child, depth + 1, max_depth)
    return lines


def _show(value: object) -> str:
    if isinstance(value, ua.LocalizedText):
        return repr(value.Text)
    if isinstance(value, ua.EUInformation):
        return value.DisplayName.Text or ""
    if isinstance(value, ua.Range):
        return f"[{value.Low:g}, {value.High:g}]"
    return repr(value)[:80]


@dataclass
class Conformance:
    checked_nodes: int = 0
    checked_declarations: int = 0
    problems: list[str] = field(default_factory=list)


class _Types:
    def __init__(self, client: Client) -> None:
        self.client = client
        self._supers: dict[ua.NodeId, list[ua.NodeId]] = {}
        self._decls: dict[ua.NodeId, list[tuple[ua.QualifiedName, ua.NodeClass, ua.NodeId | None]]] = {}

    async def ancestors(self, type_id: ua.NodeId) -> list[ua.NodeId]:
        """The type, its supertypes, and the interfaces any of them has."""
        if type_id in self._supers:
            return self._supers[type_id]
        out: list[ua.NodeId] = []
        current: ua.NodeId | None = type_id
        while current is not None and current not in out:
            out.append(current)
            node = self.client.get_node(current)
            for ref in await node.get_references(refs=_HAS_INTERFACE, direction=ua.BrowseDirection.Forward):
                out.append(ref.NodeId)
            parents = await node.get_references(refs=ua.ObjectIds.HasSubtype,
                                                direction=ua.BrowseDirection.Inverse)
            current = parents[0].NodeId if parents else None
        self._supers[type_id] = out
        return out

    async def mandatory(self, type_id: ua.NodeId) -> list[tuple[ua.QualifiedName, ua.NodeClass,
                                                                ua.NodeId | None]]:
        if type_id in self._decls:
            return self._decls[type_id]
        out = []
        declared: set[tuple[int, str]] = set()   # the most derived declaration of a name counts
        for t in await self.ancestors(type_id):
            for child in await self.client.get_node(t).get_children(refs=ua.ObjectIds.HierarchicalReferences):
                qn = await child.read_browse_name()
                if (qn.NamespaceIndex, qn.Name) in declared:
                    continue
                declared.add((qn.NamespaceIndex, qn.Name))
                rules = await child.get_referenced_nodes(refs=ua.ObjectIds.HasModellingRule)
                if not rules or rules[0].nodeid != _MANDATORY:
                    continue
                cls = await child.read_node_class()
                dt = await child.read_data_type() if cls == ua.NodeClass.Variable else None
                out.append((qn, cls, dt))
        self._decls[type_id] = out
        return out

    async def is_subtype(self, dt: ua.NodeId, of: ua.NodeId) -> bool:
        return of in await self.ancestors(dt)


async def check_mandatory(client: Client, root: Node) -> Conformance:
    """Walk the instance from ``root``: each node's type's Mandatory declarations exist, each
    variable's value is there and of the declared data type; no method anywhere."""
    result = Conformance()
    types = _Types(client)
    seen: set[ua.NodeId] = set()
    valued: set[ua.NodeId] = set()          # variables whose value was checked already
    own_ns = root.nodeid.NamespaceIndex

    async def visit(node: Node, path: str) -> None:
        if node.nodeid in seen:
            return
        seen.add(node.nodeid)
        result.checked_nodes += 1
        cls = await node.read_node_class()
        if cls == ua.NodeClass.Method:
            result.problems.append(f"{path}: a method (the server offers none)")
            return
        children = await node.get_children(refs=ua.ObjectIds.HierarchicalReferences)
        names: dict[tuple[int, str], Node] = {}
        for child in children:
            qn = await child.read_browse_name()
            names[(qn.NamespaceIndex, qn.Name)] = child
        typedef = await node.read_type_definition() if cls in (ua.NodeClass.Object,
                                                               ua.NodeClass.Variable) else None
        if typedef is not None:
            for bname, decl_cls, dt in await types.mandatory(typedef):
                result.checked_declarations += 1
                found = names.get((bname.NamespaceIndex, bname.Name))
                if found is None:
                    result.problems.append(f"{path}: mandatory {bname.to_string()} is missing")
                    continue
                if decl_cls == ua.NodeClass.Variable and dt is not None:
                    valued.add(found.nodeid)
                    await _check_value(types, found, f"{path}/{bname.Name}", dt, result)
        if cls == ua.NodeClass.Variable and node.nodeid not in valued:
            await _check_value(types, node, path, await node.read_data_type(), result)
        for (_, name), child in names.items():
            if child.nodeid.NamespaceIndex == own_ns:
                await visit(child, f"{path}/{name}")

    await visit(root, (await root.read_browse_name()).Name)
    return result


async def _check_value(types: _Types, node: Node, path: str, declared: ua.NodeId,
                       result: Conformance) -> None:
    actual = await node.read_data_type()
    if actual != declared and not await types.is_subtype(actual, declared):
        result.problems.append(f"{path}: data type {actual.to_string()} is not {declared.to_string()}")
        return
    dv = await node.read_data_value(raise_on_bad_status=False)
    variant = dv.Value
    if variant is None or variant.Value is None:
        result.problems.append(f"{path}: no value")
        return
    vt = variant.VariantType
    builtin = actual.Identifier if actual.NamespaceIndex == 0 and isinstance(actual.Identifier, int) else 0
    if 0 < builtin <= 25:
        ok = vt == ua.VariantType(builtin)
    elif await types.is_subtype(actual, nid(ua.ObjectIds.Enumeration)):
        ok = vt == ua.VariantType.Int32
    elif actual == nid(ua.ObjectIds.Number):
        ok = vt in _NUMERIC
    elif actual == nid(ua.ObjectIds.UInteger):
        ok = vt in _UNSIGNED
    elif await types.is_subtype(actual, nid(ua.ObjectIds.Structure)):
        ok = vt == ua.VariantType.ExtensionObject
    else:
        ok = True
    if not ok:
        result.problems.append(f"{path}: value of type {vt.name} for data type {actual.to_string()}")
