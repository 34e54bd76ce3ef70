"""ESI files (EtherCAT Slave Information, ETG.2000): the XML description shipped with every
drive. Read here for what the master needs: the identity of each device, its object
dictionary (names, types, access, which objects can be mapped), its PDOs (fixed or not, the
default assignment), mailbox features and distributed-clock modes. From that,
`propose_drive_block` writes the ``[[bus.drives]]`` table of the machine configuration, and
`check_slave` compares a live slave with its description.

Only the standard library's XML parser is used; a malformed file or a device without the
mandatory CiA 402 objects is an `EsiError` naming the file (and the line where it can).
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path

from .errors import ConfigurationError
from .pdo import CSP_MAPPING, MANDATORY_RX, MANDATORY_TX, OPTIONAL_OBJECTS, PdoEntry

__all__ = ["EsiDcMode", "EsiDevice", "EsiError", "EsiObject", "EsiPdo", "check_slave", "propose_drive_block",
           "read_esi"]

#: ESI base data types: bit size and whether signed
_BASE_TYPES = {"BOOL": (1, False), "BIT": (1, False), "SINT": (8, True), "USINT": (8, False),
               "BYTE": (8, False), "INT": (16, True), "UINT": (16, False), "WORD": (16, False),
               "DINT": (32, True),
               "UDINT": (32, False), "DWORD": (32, False), "LINT": (64, True), "ULINT": (64, False),
               "REAL": (32, True), "LREAL": (64, True)}


class EsiError(ConfigurationError):
    """An ESI file that cannot be read or used."""


@dataclass(frozen=True, slots=True)
class EsiObject:
    """One object dictionary entry as the ESI describes it."""

    index: int
    subindex: int
    name: str
    data_type: str
    bits: int
    access: str = "ro"              # "ro", "rw", "wo" (the ESI's, without the state suffixes)
    pdo_mapping: str = ""           # "R" (RxPDO), "T" (TxPDO), "RT" or ""

    @property
    def signed(self) -> bool:
        return _BASE_TYPES.get(self.data_type, (0, False))[1]


@dataclass(frozen=True, slots=True)
class EsiPdo:
    """One RxPdo or TxPdo element."""

    index: int
    name: str
    fixed: bool
    mandatory: bool
    sm: int | None                  # assigned to this sync manager by default (None: not assigned)
    excludes: tuple[int, ...]
    entries: tuple[PdoEntry, ...]


@dataclass(frozen=True, slots=True)
class EsiDcMode:
    name: str
    description: str
    assign_activate: int            # 0x300: SYNC0 on; 0: free run / SM synchronous
    shift_time_sync0_ns: int


@dataclass(frozen=True, slots=True)
class EsiDevice:
    vendor_id: int
    vendor_name: str
    product_code: int
    revision: int
    name: str
    objects: dict[tuple[int, int], EsiObject] = field(default_factory=dict)
    rx_pdos: tuple[EsiPdo, ...] = ()
    tx_pdos: tuple[EsiPdo, ...] = ()
    complete_access: bool = False
    pdo_assign: bool = False
    pdo_config: bool = False
    dc_modes: tuple[EsiDcMode, ...] = ()
    source: str = ""

    def object_name(self, index: int, subindex: int = 0) -> str:
        obj = self.objects.get((index, subindex))
        return obj.name if obj is not None else ""

    def has(self, index: int, subindex: int = 0) -> bool:
        return (index, subindex) in self.objects

    @property
    def label(self) -> str:
        return (f"{self.name} ({self.vendor_name}, vendor 0x{self.vendor_id:08X}, product "
                f"0x{self.product_code:08X}, revision 0x{self.revision:08X})")


def _int(text: str | None, where: str) -> int:
    """ESI numbers: decimal, ``#x1A00`` hex, or ``0x1A00``."""
    if text is None:
        raise EsiError(f"{where}: a number is missing")
    t = text.strip()
    try:
        if t.lower().startswith("#x"):
            return int(t[2:], 16)
        return int(t, 0)
    except ValueError:
        raise EsiError(f"{where}: {t!r} is not a number") from None


def _text(el: ET.Element | None, tag: str, default: str = "") -> str:
    if el is None:
        return default
    child = el.find(tag)
    return (child.text or "").strip() if child is not None and child.text else default


def _name(el: ET.Element) -> str:
    """The element's Name, English (LcId 1033) preferred."""
    names = el.findall("Name")
    for n in names:
        if n.get("LcId") in (None, "1033") and n.text:
            return n.text.strip()
    return (names[0].text or "").strip() if names and names[0].text else ""


def _flags(el: ET.Element | None) -> tuple[str, str]:
    flags: ET.Element | None = el.find("Flags") if el is not None else None
    access = _text(flags, "Access", "ro").lower()
    access = "rw" if access.startswith("rw") else ("wo" if access.startswith("wo") else "ro")
    mapping = _text(flags, "PdoMapping", "").upper()
    return access, mapping


def _objects(dictionary: ET.Element, where: str) -> dict[tuple[int, int], EsiObject]:
    types: dict[str, ET.Element] = {}
    for dt in dictionary.iterfind("DataTypes/DataType"):
        types[_text(dt, "Name")] = dt
    out: dict[tuple[int, int], EsiObject] = {}
    for obj in dictionary.iterfind("Objects/Object"):
        index = _int(_text(obj, "Index"), f"{where}: object")
        name = _name(obj)
        type_name = _text(obj, "Type")
        access, mapping = _flags(obj)
        described = types.get(type_name)
        subs = described.findall("SubItem") if described is not None else []
        if not subs:
            bits = _BASE_TYPES.get(type_name, (_int(_text(obj, "BitSize", "0"), where), False))[0]
            out[(index, 0)] = EsiObject(index, 0, name, type_name, bits, access, mapping)
            continue
        for sub in subs:
            sub_type = _text(sub, "Type")
            sub_access, sub_mapping = _flags(sub)
            arr = types.get(sub_type)
            info = arr.find("ArrayInfo") if arr is not None else None
            if arr is not None and info is not None:   # an array: elements are sub-indices LBound...
                base = _text(arr, "BaseType")
                lbound = _int(_text(info, "LBound", "1"), where)
                n = _int(_text(info, "Elements", "0"), where)
                for k in range(lbound, lbound + n):
                    bits = _BASE_TYPES.get(base, (0, False))[0]
                    out[(index, k)] = EsiObject(index, k, f"{name} {k}", base, bits, sub_access or access,
                                                sub_mapping or mapping)
                continue
            si = _int(_text(sub, "SubIdx", "0"), where)
            out[(index, si)] = EsiObject(index, si, f"{name}: {_text(sub, 'Name')}", sub_type,
                                         _int(_text(sub, "BitSize", "0"), where), sub_access, sub_mapping)
    return out


def _pdos(device: ET.Element, tag: str, objects: dict[tuple[int, int], EsiObject], where: str
          ) -> tuple[EsiPdo, ...]:
    out = []
    for pdo in device.iterfind(tag):
        entries = []
        for e in pdo.iterfind("Entry"):
            index = _int(_text(e, "Index"), where)
            sub = _int(_text(e, "SubIndex", "0"), where)
            bits = _int(_text(e, "BitLen"), where)
            obj = objects.get((index, sub))
            dtype = _text(e, "DataType") or (obj.data_type if obj is not None else "")
            entries.append(PdoEntry(index, sub, bits, _BASE_TYPES.get(dtype, (0, False))[1]))
        sm = pdo.get("Sm")
        out.append(EsiPdo(index=_int(_text(pdo, "Index"), where), name=_name(pdo),
                          fixed=pdo.get("Fixed", "0") in ("1", "true"),
                          mandatory=pdo.get("Mandatory", "0") in ("1", "true"),
                          sm=int(sm) if sm is not None and sm.isdigit() else None,
                          excludes=tuple(_int(x.text, where) for x in pdo.findall("Exclude")),
                          entries=tuple(entries)))
    return tuple(out)


def read_esi(path: str | Path) -> tuple[EsiDevice, ...]:
    """Every device described in the ESI file at `path`."""
    where = str(path)
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError as exc:
        line, col = exc.position
        raise EsiError(f"{where}:{line}:{col}: not a well-formed XML file ({exc})") from None
    except OSError as exc:
        raise EsiError(f"{where}: cannot read: {exc.strerror or exc}") from None
    if root.tag != "EtherCATInfo":
        raise EsiError(f"{where}: not an ESI file (the root element is <{root.tag}>, not <EtherCATInfo>)")
    vendor = root.find("Vendor")
    vendor_id = _int(_text(vendor, "Id"), f"{where}: Vendor") if vendor is not None else 0
    vendor_name = _text(vendor, "Name") if vendor is not None else ""
    devices = []
    for dev in root.iterfind("Descriptions/Devices/Device"):
        typ = dev.find("Type")
        if typ is None:
            raise EsiError(f"{where}: a Device has no Type (product code, revision)")
        dictionary = dev.find("Profile/Dictionary")
        objects = _objects(dictionary, where) if dictionary is not None else {}
        coe = dev.find("Mailbox/CoE")
        dc_modes = tuple(
            EsiDcMode(_text(m, "Name"), _text(m, "Desc"), _int(_text(m, "AssignActivate", "0"), where),
                      _int(_text(m, "ShiftTimeSync0", "0"), where))
            for m in dev.iterfind("Dc/OpMode"))
        devices.append(EsiDevice(
            vendor_id=vendor_id, vendor_name=vendor_name,
            product_code=_int(typ.get("ProductCode"), f"{where}: Device Type ProductCode"),
            revision=_int(typ.get("RevisionNo", "0"), f"{where}: Device Type RevisionNo"),
            name=(typ.text or "").strip() or _name(dev), objects=objects,
            rx_pdos=_pdos(dev, "RxPdo", objects, where), tx_pdos=_pdos(dev, "TxPdo", objects, where),
            complete_access=coe is not None and coe.get("CompleteAccess", "false") in ("1", "true"),
            pdo_assign=coe is not None and coe.get("PdoAssign", "false") in ("1", "true"),
            pdo_config=coe is not None and coe.get("PdoConfig", "false") in ("1", "true"),
            dc_modes=dc_modes, source=where))
    if not devices:
        raise EsiError(f"{where}: no Device in Descriptions/Devices")
    return tuple(devices)


def _default_pdo(pdos: tuple[EsiPdo, ...], sm: int) -> EsiPdo | None:
    assigned = [p for p in pdos if p.sm == sm]
    return assigned[0] if assigned else (pdos[0] if pdos else None)


def _entry_text(device: EsiDevice, e: PdoEntry) -> str:
    return f"0x{e.index:04X}:{e.subindex}:{e.bits}"


def propose_drive_block(device: EsiDevice, position: int) -> str:
    """The ``[[bus.drives]]`` table for this device at slave `position`, with the reasons as
    comments: the CSP objects the device can map (or its fixed mapping), distributed clocks
    when a SYNC0 mode is described, complete access as the ESI announces it."""
    lines = [f"# {device.label}", f"# from {Path(device.source).name}"]
    rx_default = _default_pdo(device.rx_pdos, 2)
    tx_default = _default_pdo(device.tx_pdos, 3)
    for what, pdo in (("RxPDO", rx_default), ("TxPDO", tx_default)):
        if pdo is not None:
            listed = ", ".join(f"{_entry_text(device, e)} {device.object_name(e.index, e.subindex)}".strip()
                               for e in pdo.entries)
            lines.append(f"# default {what} 0x{pdo.index:04X}{' (fixed)' if pdo.fixed else ''}: {listed}")
    fixed = (rx_default is not None and rx_default.fixed) or (tx_default is not None and tx_default.fixed) \
        or not device.pdo_config
    lines += ["[[bus.drives]]", f"position = {position}", f"vendor_id = 0x{device.vendor_id:08X}",
              f"product_code = 0x{device.product_code:08X}"]
    if fixed:
        if rx_default is None or tx_default is None:
            raise EsiError(f"{device.source}: {device.name} describes no default RxPDO/TxPDO and no PDO "
                           "configuration: nothing to run with")
        rx, tx = rx_default.entries, tx_default.entries
        lines += ["# the PDOs are fixed: the drive's own mapping is used as it is", 'mapping = "keep"']
    else:
        def mappable(e: PdoEntry, direction: str) -> bool:
            obj = device.objects.get((e.index, e.subindex))
            if obj is None:
                return False
            return not obj.pdo_mapping or direction in obj.pdo_mapping
        rx = tuple(e for e in CSP_MAPPING.rx if mappable(e, "R"))
        tx = tuple(e for e in CSP_MAPPING.tx if mappable(e, "T"))
        missing = sorted({e.index for e in CSP_MAPPING.rx + CSP_MAPPING.tx} - {e.index for e in rx + tx})
        for index in missing:
            if index in MANDATORY_RX | MANDATORY_TX:
                raise EsiError(f"{device.source}: {device.name} cannot map 0x{index:04X}, which cyclic "
                               "synchronous position needs")
            lines.append(f"# no 0x{index:04X} in its dictionary: {OPTIONAL_OBJECTS.get(index, 'not mapped')}")
        lines.append('mapping = "adapt"')
    lines += [f"rx_pdo = 0x{(rx_default.index if rx_default else 0x1600):04X}",
              "rx = [" + ", ".join(f'"{_entry_text(device, e)}"' for e in rx) + "]",
              f"tx_pdo = 0x{(tx_default.index if tx_default else 0x1A00):04X}",
              "tx = [" + ", ".join(f'"{_entry_text(device, e)}"' for e in tx) + "]"]
    sync0 = [m for m in device.dc_modes if m.assign_activate & 0x0300 == 0x0300]
    if sync0:
        lines += [f"# distributed clocks: {sync0[0].name} ({sync0[0].description}), SYNC0 = cycle time",
                  "dc = true"]
    else:
        lines += ["# no SYNC0 mode described: free run", "dc = false"]
    lines.append('complete_access = "auto"   # tried at start-up; the ESI says '
                 + ("it is supported" if device.complete_access else "it is not supported"))
    return "\n".join(lines) + "\n"


def check_slave(device: EsiDevice, identity: tuple[int, int, int],
                found: dict[str, list[tuple[int, list[int]]]]) -> list[str]:
    """Differences between a live slave (vendor, product, revision; its PDO assignment as read
    by ``soem_bus.read_mapping``) and its ESI description. Empty: it matches."""
    problems = []
    vendor, product, revision = identity
    if (vendor, product) != (device.vendor_id, device.product_code):
        problems.append(f"identity: vendor 0x{vendor:08X} product 0x{product:08X}, the ESI describes vendor "
                        f"0x{device.vendor_id:08X} product 0x{device.product_code:08X}")
    elif revision != device.revision:
        problems.append(f"revision 0x{revision:08X}, the ESI describes 0x{device.revision:08X} "
                        "(objects and PDOs may differ)")
    for key, pdos in (("rx", device.rx_pdos), ("tx", device.tx_pdos)):
        known = {p.index: p for p in pdos}
        for pdo, entries in found.get(key, []):
            desc = known.get(pdo)
            if desc is None:
                problems.append(f"{key.upper()}PDO 0x{pdo:04X} is assigned but not described in the ESI")
                continue
            for value in entries:
                index, sub = value >> 16, (value >> 8) & 0xFF
                if index and (index, sub) not in device.objects:
                    problems.append(f"{key.upper()}PDO 0x{pdo:04X} maps 0x{index:04X}:{sub}, which the ESI's "
                                    "dictionary does not have")
    return problems


def propose_terminal_block(device: EsiDevice, position: int) -> str:
    """The ``[[bus.terminals]]`` table for this terminal at slave ``position``: its type known by
    identity (``ethercat.terminals``), and its ESI's default process data (the PDOs assigned to a
    sync manager) the image the control reads; EsiError saying what differs otherwise."""
    from .terminals import TERMINAL_TYPES, TerminalKind, type_of_identity

    t = type_of_identity(device.vendor_id, device.product_code)
    if t is None:
        raise EsiError(f"{device.source}: {device.label} is not a terminal this control knows "
                       f"(known: {', '.join(sorted(TERMINAL_TYPES))})")
    tx_bits = sum(e.bits for p in device.tx_pdos if p.sm is not None for e in p.entries)
    rx_bits = sum(e.bits for p in device.rx_pdos if p.sm is not None for e in p.entries)
    want_tx = t.channels if t.kind is TerminalKind.DIGITAL_IN else 8 * t.tx_bytes
    want_rx = t.channels if t.kind is TerminalKind.DIGITAL_OUT else 8 * t.rx_bytes
    if (tx_bits, rx_bits) != (want_tx, want_rx):
        raise EsiError(f"{device.source}: {device.label} assigns {tx_bits} input and {rx_bits} output bits "
                       f"by default; the control reads a {t.name} as {want_tx} and {want_rx}: set its "
                       "default PDOs, or it is not that terminal")
    return "\n".join([
        f"# {device.label}: {t.description}; {tx_bits} input, {rx_bits} output bits as its ESI assigns them",
        "[[bus.terminals]]", f"position = {position}", f'type = "{t.name}"', ""])
