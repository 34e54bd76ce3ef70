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
_PLACEHOLDERS = {nid(ua.ObjectIds.ModellingRule_OptionalPlaceholder),
                 nid(ua.ObjectIds.ModellingRule_MandatoryPlaceholder)}
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


@dataclass(frozen=True)
class _Decl:
    """An instance declaration: a child of a type, or of another declaration."""

    node: Node
    name: ua.QualifiedName
    cls: ua.NodeClass
    rule: ua.NodeId | None
    datatype: ua.NodeId | None
    typedef: ua.NodeId | None

    @property
    def key(self) -> tuple[int, str]:
        return (self.name.NamespaceIndex, self.name.Name)

    @property
    def placeholder(self) -> bool:
        return self.rule in _PLACEHOLDERS


@dataclass
class _Decls:
    """The declarations that apply to one instance's children: by browse name, and the
    placeholders (``<OrderedObject>``), which stand for any number of children of their type."""

    named: dict[tuple[int, str], _Decl] = field(default_factory=dict)
    placeholders: list[_Decl] = field(default_factory=list)

    def over(self, base: _Decls) -> _Decls:
        """These declarations before ``base``'s: a nested declaration of a parent type is more
        derived than the child type's own."""
        named = dict(base.named)
        named.update(self.named)
        return _Decls(named, self.placeholders + base.placeholders)


class _Types:
    def __init__(self, client: Client) -> None:
        self.client = client
        self._supers: dict[ua.NodeId, list[ua.NodeId]] = {}
        self._decls: dict[ua.NodeId, _Decls] = {}
        self._children: dict[ua.NodeId, _Decls] = {}

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

    async def _declared(self, parent: Node) -> list[_Decl]:
        out = []
        for child in await parent.get_children(refs=ua.ObjectIds.HierarchicalReferences):
            rules = await child.get_referenced_nodes(refs=ua.ObjectIds.HasModellingRule)
            if not rules:
                continue            # not an instance declaration
            cls = await child.read_node_class()
            dt = await child.read_data_type() if cls == ua.NodeClass.Variable else None
            typedef = await child.read_type_definition() if cls in (ua.NodeClass.Object,
                                                                     ua.NodeClass.Variable) else None
            out.append(_Decl(child, await child.read_browse_name(), cls, rules[0].nodeid, dt, typedef))
        return out

    async def of_type(self, type_id: ua.NodeId) -> _Decls:
        """The declarations of a type, its supertypes and interfaces; the most derived
        declaration of a name counts."""
        if type_id in self._decls:
            return self._decls[type_id]
        decls = _Decls()
        for t in await self.ancestors(type_id):
            for d in await self._declared(self.client.get_node(t)):
                if d.placeholder:
                    decls.placeholders.append(d)
                elif d.key not in decls.named:
                    decls.named[d.key] = d
        self._decls[type_id] = decls
        return decls

    async def nested(self, decl: _Decl) -> _Decls:
        """What a declaration declares for its own children (a parent type's nested
        declarations, a placeholder's children included)."""
        if decl.node.nodeid in self._children:
            return self._children[decl.node.nodeid]
        decls = _Decls()
        for d in await self._declared(decl.node):
            if d.placeholder:
                decls.placeholders.append(d)
            else:
                decls.named[d.key] = d
        self._children[decl.node.nodeid] = decls
        return decls

    async def is_subtype(self, dt: ua.NodeId, of: ua.NodeId) -> bool:
        return of in await self.ancestors(dt)


async def check_mandatory(client: Client, root: Node) -> Conformance:
    """Walk the instance from ``root``: each node's Mandatory declarations exist (its type's,
    its supertypes' and interfaces', and those nested in the declaration it instantiates, a
    placeholder's included); each variable's value is there and of the declared data type;
    no method anywhere."""
    result = Conformance()
    types = _Types(client)
    seen: set[ua.NodeId] = set()
    valued: set[ua.NodeId] = set()          # variables whose value was checked already
    own_ns = root.nodeid.NamespaceIndex

    async def declaration_of(child: Node, key: tuple[int, str], decls: _Decls) -> _Decl | None:
        if key in decls.named:
            return decls.named[key]
        typedef = await child.read_type_definition()
        for d in decls.placeholders:
            if typedef is None or d.typedef is None or await types.is_subtype(typedef, d.typedef):
                return d
        return None

    async def visit(node: Node, path: str, nested: _Decls) -> None:
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
        decls = nested.over(await types.of_type(typedef)) if typedef is not None else nested
        for key, d in decls.named.items():
            if d.rule != _MANDATORY:
                continue
            result.checked_declarations += 1
            found = names.get(key)
            if found is None:
                result.problems.append(f"{path}: mandatory {d.name.to_string()} is missing")
                continue
            if d.cls == ua.NodeClass.Variable and d.datatype is not None:
                valued.add(found.nodeid)
                await _check_value(types, found, f"{path}/{d.name.Name}", d.datatype, result)
        if cls == ua.NodeClass.Variable and node.nodeid not in valued:
            await _check_value(types, node, path, await node.read_data_type(), result)
        for key, child in names.items():
            if child.nodeid.NamespaceIndex != own_ns:
                continue
            decl = await declaration_of(child, key, decls)
            inner = await types.nested(decl) if decl is not None else _Decls()
            await visit(child, f"{path}/{key[1]}", inner)

    await visit(root, (await root.read_browse_name()).Name, _Decls())
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
