"""CoE object dictionary and SDO server of one emulated CiA 402 drive (ETG.1000.6).

The drive's own objects (0x1000, 0x1018, 0x6xxx) come from the shared
`ethercat.drive_model.DriveModel`; this module adds the communication objects an ESC
application owns: device name 0x1008, the PDO mapping objects 0x1600/0x1601 (RxPDO)
and 0x1A00/0x1A01 (TxPDO), sync manager types 0x1C00, PDO assignment 0x1C12/0x1C13,
SM synchronisation 0x1C32/0x1C33, and a manufacturer object 0x2000 that injects a drive
fault (write the CiA 402 error code). SDO transfers: expedited and normal upload and
download, segmented upload/download, complete access (sub-index 0 travels as 8 bits
plus one pad byte, as SOEM expects), aborts with CiA 301 codes.
"""

from __future__ import annotations

import functools
import struct
from collections.abc import Callable
from dataclasses import dataclass

from ..drive_model import DriveModel
from ..errors import SdoAbortError
from ..object_dictionary import OBJECTS, ObjectEntry, decode_object, encode_object
from .variants import VARIANTS, DriveVariant

# CiA 301 / ETG.1000.6 abort codes used here besides those on SdoAbortError.
ABORT_TOGGLE = 0x0503_0000
ABORT_COMMAND = 0x0504_0001
ABORT_UNSUPPORTED_ACCESS = 0x0601_0000
ABORT_SI0_NOT_ZERO = 0x0601_0003
ABORT_NOT_MAPPABLE = 0x0604_0041
ABORT_PDO_LENGTH = 0x0604_0042
ABORT_STATE = 0x0800_0022

RX_MAPPING = (0x1600, 0x1601)
TX_MAPPING = (0x1A00, 0x1A01)
MAX_MAPPED_ENTRIES = 8
MAX_PDO_BYTES = 32


# Hot-path attribute names of the drive model for PDO entries.
_RX_ATTR = {(0x6040, 0): "controlword", (0x607A, 0): "target_position",
            (0x6060, 0): "modes_of_operation", (0x60FE, 1): "digital_outputs",
            (0x60FF, 0): "target_velocity"}
_TX_ATTR = {(0x6041, 0): "statusword", (0x6064, 0): "position_actual",
            (0x60F4, 0): "following_error_actual", (0x603F, 0): "error_code",
            (0x6061, 0): "modes_of_operation_display", (0x606C, 0): "velocity_actual",
            (0x6062, 0): "position_demand"}


def _abort(index: int, subindex: int, code: int, text: str = "") -> SdoAbortError:
    return SdoAbortError(-1, index, subindex, code, text)


def pack_mapping_entry(index: int, subindex: int, bits: int) -> int:
    """PDO mapping entry value: index << 16 | subindex << 8 | bit length (CiA 301)."""
    return (index << 16) | (subindex << 8) | bits


@dataclass(frozen=True, slots=True)
class PdoLayout:
    """Compiled process data of one direction: struct and the object per field."""

    size_bytes: int
    fmt: struct.Struct
    keys: tuple[tuple[int, int], ...]       # (index, subindex) per field (padding: (0, 0))


class DriveObjects:
    """Object dictionary + SDO server of one emulated drive.

    `al_state` is a callable returning the slave's AL state (1 INIT, 2 PRE-OP, 4 SAFE-OP,
    8 OP): PDO mapping and assignment objects are writable in PRE-OP only.
    """

    def __init__(self, model: DriveModel, name: str, al_state: Callable[[], int],
                 variant: DriveVariant = VARIANTS["standard"]) -> None:
        self.model = model
        self.variant = variant
        self.name = name
        self._al_state = al_state
        # mapping objects: all 8 entry values (kept while sub-index 0 is 0) and the count
        all_maps = RX_MAPPING + TX_MAPPING
        self.map_entries: dict[int, list[int]] = {i: [0] * MAX_MAPPED_ENTRIES for i in all_maps}
        self.map_count: dict[int, int] = dict.fromkeys(RX_MAPPING + TX_MAPPING, 0)
        (rx_pdo, rx_default), (tx_pdo, tx_default) = variant.rx_default, variant.tx_default
        for index, default in ((rx_pdo, rx_default), (tx_pdo, tx_default)):
            for k, e in enumerate(default):
                self.map_entries[index][k] = pack_mapping_entry(*e)
            self.map_count[index] = len(default)
        self.assign_entries: dict[int, list[int]] = {
            0x1C12: [rx_pdo] + [p for p in RX_MAPPING if p != rx_pdo],
            0x1C13: [tx_pdo] + [p for p in TX_MAPPING if p != tx_pdo]}
        self.assign_count: dict[int, int] = {0x1C12: 1, 0x1C13: 1}
        # 0x1C32 / 0x1C33 sub 1 sync mode (2 = DC SYNC0), sub 2 cycle time ns
        self.sync_mode = {0x1C32: 2, 0x1C33: 2}
        self.sync_cycle_ns = {0x1C32: 1_000_000, 0x1C33: 1_000_000}
        # segmented transfer state
        self._up_data = b""
        self._up_toggle = 0
        self._down: tuple[int, int, bool, int, bytearray] | None = None
        self._down_toggle = 0

    def mapping(self, index: int) -> list[int]:
        """Active entries of mapping object `index` (0x16xx / 0x1Axx)."""
        return self.map_entries[index][: self.map_count[index]]

    def assignment(self, index: int) -> list[int]:
        """Active PDOs of assignment object 0x1C12 / 0x1C13."""
        return self.assign_entries[index][: self.assign_count[index]]

    # ------------------------------------------------------------------ PDO layout
    def _layout(self, assign_index: int, outputs: bool) -> PdoLayout:
        fmt = "<"
        keys: list[tuple[int, int]] = []
        for pdo in self.assignment(assign_index):
            for value in self.mapping(pdo):
                index, sub, bits = value >> 16, (value >> 8) & 0xFF, value & 0xFF
                if index == 0:
                    fmt += f"{bits // 8}x"
                    continue
                entry = OBJECTS[(index, sub)]
                # outputs are unpacked signed as typed; inputs are packed from masked values
                code = entry.struct_format[1]
                fmt += code if outputs else code.upper()
                keys.append((index, sub))
        st = struct.Struct(fmt)
        return PdoLayout(st.size, st, tuple(keys))

    def rx_layout(self) -> PdoLayout:
        return self._layout(0x1C12, outputs=True)

    def tx_layout(self) -> PdoLayout:
        return self._layout(0x1C13, outputs=False)

    def make_output_setter(self, layout: PdoLayout) -> Callable[[bytes | memoryview], None]:
        """A function applying RxPDO bytes to the drive model (hot path)."""
        model = self.model
        attrs = [_RX_ATTR.get(k) for k in layout.keys]
        keys = layout.keys
        unpack = layout.fmt.unpack_from

        def apply(data: bytes | memoryview) -> None:
            values = unpack(data)
            for attr, key, value in zip(attrs, keys, values):
                if attr is not None:
                    setattr(model, attr, value)
                else:
                    try:
                        model.write_object(key[0], key[1], value)
                    except SdoAbortError:
                        pass

        return apply

    def make_input_getter(self, layout: PdoLayout) -> Callable[[bytearray, int], None]:
        """A function packing the drive model's TxPDO values into a buffer (hot path)."""
        model = self.model
        getters: list[Callable[[], int]] = []
        masks: list[int] = []
        for key in layout.keys:
            attr = _TX_ATTR.get(key)
            if attr is not None:
                getters.append(functools.partial(getattr, model, attr))
            else:
                getters.append(functools.partial(model.read_object, key[0], key[1]))
            masks.append((1 << OBJECTS[key].bit_length) - 1)
        pack_into = layout.fmt.pack_into

        def fill(buf: bytearray, offset: int) -> None:
            pack_into(buf, offset, *[g() & m for g, m in zip(getters, masks)])

        return fill

    # ------------------------------------------------------------------ object access
    def _entries_of(self, index: int) -> list[tuple[int, str]] | None:
        """(subindex, type) of the communication objects owned here, None if not ours."""
        if index in self.map_count:
            return [(0, "u8")] + [(s, "u32") for s in range(1, MAX_MAPPED_ENTRIES + 1)]
        if index in (0x1C12, 0x1C13):
            return [(0, "u8"), (1, "u16"), (2, "u16")]
        if index == 0x1C00:
            return [(0, "u8")] + [(s, "u8") for s in range(1, 5)]
        if index in (0x1C32, 0x1C33):
            return [(0, "u8"), (1, "u16"), (2, "u32"), (3, "u32"), (4, "u16"), (5, "u32"), (6, "u32")]
        if index == 0x2000:
            return [(0, "u16")]
        if index in (0x1008, 0x1009, 0x100A):
            return [(0, "str")]
        return None

    def _string(self, index: int) -> bytes:
        return {0x1008: self.name, 0x1009: "1.0", 0x100A: "cnc-ethercat emulator 1.0"}[index].encode()

    def _comm_read(self, index: int, sub: int) -> int:
        if index in self.map_count:
            return self.map_count[index] if sub == 0 else self.map_entries[index][sub - 1]
        if index in self.assign_count:
            return self.assign_count[index] if sub == 0 else self.assign_entries[index][sub - 1]
        if index == 0x1C00:
            return 4 if sub == 0 else sub      # SM0 mbx out, SM1 mbx in, SM2 outputs, SM3 inputs
        if index in (0x1C32, 0x1C33):
            return {0: 6, 1: self.sync_mode[index], 2: self.sync_cycle_ns[index], 3: 0,
                    4: 0x0007, 5: 125_000, 6: 20_000}[sub]
        if index == 0x2000:
            return 0
        raise _abort(index, sub, SdoAbortError.OBJECT_DOES_NOT_EXIST)

    def read(self, index: int, sub: int) -> bytes:
        """SDO upload of one sub-index as bytes (raises SdoAbortError)."""
        entries = self._entries_of(index)
        if index in self.variant.missing:
            raise _abort(index, sub, SdoAbortError.OBJECT_DOES_NOT_EXIST)
        if entries is None:
            value = self.model.read_object(index, sub)
            return encode_object(self.model.object_entry(index, sub), value)
        types = dict(entries)
        if sub not in types:
            raise _abort(index, sub, SdoAbortError.SUBINDEX_DOES_NOT_EXIST)
        if types[sub] == "str":
            return self._string(index)
        entry = ObjectEntry(index, sub, "", types[sub], "rw")
        return encode_object(entry, self._comm_read(index, sub))

    def write(self, index: int, sub: int, data: bytes) -> None:
        """SDO download of one sub-index (raises SdoAbortError)."""
        entries = self._entries_of(index)
        if index in self.variant.missing:
            raise _abort(index, sub, SdoAbortError.OBJECT_DOES_NOT_EXIST)
        if entries is None:
            entry = self.model.object_entry(index, sub)
            self.model.write_object(index, sub, decode_object(entry, data))
            return
        types = dict(entries)
        if sub not in types:
            raise _abort(index, sub, SdoAbortError.SUBINDEX_DOES_NOT_EXIST)
        if types[sub] == "str" or index == 0x1C00:
            raise _abort(index, sub, SdoAbortError.READ_ONLY)
        entry = ObjectEntry(index, sub, "", types[sub], "rw")
        value = decode_object(entry, data)
        if index == 0x2000:
            if value:
                self.model.inject_fault(value)
            return
        if index in (0x1C32, 0x1C33):
            if sub == 1:
                if value not in (0, 1, 2):
                    raise _abort(index, sub, SdoAbortError.VALUE_RANGE)
                self.sync_mode[index] = value
            elif sub == 2:
                self.sync_cycle_ns[index] = value
            else:
                raise _abort(index, sub, SdoAbortError.READ_ONLY)
            return
        if self.variant.fixed_mapping:
            raise _abort(index, sub, SdoAbortError.READ_ONLY, "this drive's PDO mapping is fixed")
        if self._al_state() != 2:
            raise _abort(index, sub, ABORT_STATE, "PDO configuration only in PRE-OP")
        if index in self.map_count:
            self._write_mapping(index, sub, value)
        else:
            self._write_assign(index, sub, value)

    def _write_mapping(self, index: int, sub: int, value: int) -> None:
        """CiA 301 PDO mapping: entries only while sub-index 0 is 0; writing n > 0 to
        sub-index 0 checks the entries and activates them."""
        is_rx = index in RX_MAPPING
        if sub != 0:
            if self.map_count[index]:
                raise _abort(index, sub, ABORT_SI0_NOT_ZERO)
            self.map_entries[index][sub - 1] = value
            return
        if value > MAX_MAPPED_ENTRIES:
            raise _abort(index, sub, SdoAbortError.VALUE_RANGE)
        total_bits = 0
        for raw in self.map_entries[index][:value]:
            obj, osub, bits = raw >> 16, (raw >> 8) & 0xFF, raw & 0xFF
            total_bits += bits
            if obj == 0:
                if bits % 8:
                    raise _abort(index, sub, ABORT_NOT_MAPPABLE, "padding must be whole bytes")
                continue
            entry = OBJECTS.get((obj, osub)) if obj not in self.variant.missing else None
            if entry is None or not entry.pdo_mappable or entry.bit_length != bits:
                raise _abort(index, sub, ABORT_NOT_MAPPABLE, f"0x{obj:04X}:{osub} ({bits} bits)")
            if is_rx and entry.access != "rw":
                raise _abort(index, sub, ABORT_NOT_MAPPABLE, f"0x{obj:04X}:{osub} is read only")
        if total_bits > 8 * MAX_PDO_BYTES:
            raise _abort(index, sub, ABORT_PDO_LENGTH)
        self.map_count[index] = value

    def _write_assign(self, index: int, sub: int, value: int) -> None:
        allowed = RX_MAPPING if index == 0x1C12 else TX_MAPPING
        if sub != 0:
            if self.assign_count[index]:
                raise _abort(index, sub, ABORT_SI0_NOT_ZERO)
            if value not in allowed:
                raise _abort(index, sub, SdoAbortError.VALUE_RANGE, f"0x{value:04X} is not a PDO of this SM")
            self.assign_entries[index][sub - 1] = value
            return
        if value > len(allowed) or any(p not in allowed for p in self.assign_entries[index][:value]):
            raise _abort(index, sub, SdoAbortError.VALUE_RANGE)
        self.assign_count[index] = value

    # ------------------------------------------------------------------ complete access
    def _ca_subs(self, index: int) -> list[tuple[int, str]]:
        entries = self._entries_of(index)
        if entries is None:
            subs = sorted(s for (i, s) in OBJECTS if i == index)
            if not subs:
                raise _abort(index, 0, SdoAbortError.OBJECT_DOES_NOT_EXIST)
            return [(s, OBJECTS[(index, s)].data_type) for s in subs]
        return entries

    def read_complete(self, index: int, sub: int) -> bytes:
        """Complete access upload from `sub` (0 or 1) over sub-indices 1..n (n = sub 0)."""
        subs = self._ca_subs(index)
        if subs[0][1] == "str" or len(subs) == 1:
            return self.read(index, 0)
        n = int(self.read(index, 0)[0])
        out = bytearray()
        if sub == 0:
            # the pad byte after sub-index 0 is what ETG.1000.6 asks; some drives leave it out
            out += self.read(index, 0) + (b"" if self.variant.ca_without_pad else b"\x00")
        types = dict(subs)
        for s in range(1, n + 1):
            if s in types:
                out += self.read(index, s)
        return bytes(out)

    def write_complete(self, index: int, sub: int, data: bytes) -> None:
        """Complete access download: sub-index 0 (8 bits + pad) then sub-indices 1..n."""
        subs = dict(self._ca_subs(index))
        if sub != 0:
            raise _abort(index, sub, ABORT_UNSUPPORTED_ACCESS, "complete access must start at sub-index 0")
        if len(data) < 2:
            raise _abort(index, sub, SdoAbortError.LENGTH_MISMATCH)
        n = data[0]
        sizes = []
        for s in range(1, n + 1):
            if s not in subs:
                raise _abort(index, s, SdoAbortError.SUBINDEX_DOES_NOT_EXIST)
            sizes.append(int(subs[s][1:]) // 8)
        if len(data) != 2 + sum(sizes):
            raise _abort(index, sub, SdoAbortError.LENGTH_MISMATCH,
                         f"{len(data)} bytes for {n} entries")
        counted = index in self.map_count or index in self.assign_count
        if counted:
            self.write(index, 0, b"\x00")
        offset = 2
        for s, size in zip(range(1, n + 1), sizes):
            self.write(index, s, data[offset: offset + size])
            offset += size
        if counted:
            self.write(index, 0, data[:1])

    # ------------------------------------------------------------------ SDO server
    def handle_sdo(self, request: bytes, mbx_data_bytes: int) -> bytes:
        """Answer one CoE SDO request (bytes after the CoE header: command, index,
        subindex, data; trimmed to the mailbox header's length). Returns the SDO response
        payload in the same layout (empty: no answer); the caller adds the mailbox and CoE
        headers. `mbx_data_bytes` is the usable mailbox size after the mailbox header."""
        cmd = request[0]
        index, sub = struct.unpack_from("<HB", request, 1)
        ccs = cmd >> 5
        try:
            if ccs == 1:                                    # initiate download
                return self._download_init(cmd, index, sub, request, mbx_data_bytes)
            if ccs == 0:                                    # download segment
                return self._download_segment(cmd, request)
            if ccs == 2:                                    # initiate upload
                return self._upload_init(cmd, index, sub, mbx_data_bytes)
            if ccs == 3:                                    # upload segment
                return self._upload_segment(cmd, index, sub, mbx_data_bytes)
            if ccs == 4:                                    # abort from the master
                self._down = None
                self._up_data = b""
                return b""
            raise _abort(index, sub, ABORT_COMMAND)
        except SdoAbortError as exc:
            self._down = None
            self._up_data = b""
            return struct.pack("<BHBI", 0x80, exc.index, exc.subindex, exc.abort_code)

    def _download_init(self, cmd: int, index: int, sub: int, request: bytes, mbx_data_bytes: int) -> bytes:
        complete = bool(cmd & 0x10)
        if cmd & 0x02:                                      # expedited
            size = 4 - ((cmd >> 2) & 0x03) if cmd & 0x01 else 4
            data = bytes(request[4: 4 + size])
            self._store(index, sub, complete, data)
            return struct.pack("<BHBI", 0x60, index, sub, 0)
        total = struct.unpack_from("<I", request, 4)[0]
        first = bytes(request[8: 8 + min(total, mbx_data_bytes - 2 - 8)])
        if len(first) < total:                              # segments follow
            self._down = (index, sub, complete, total, bytearray(first))
            self._down_toggle = 0
        else:
            self._store(index, sub, complete, first)
        return struct.pack("<BHBI", 0x60, index, sub, 0)

    def _download_segment(self, cmd: int, request: bytes) -> bytes:
        if self._down is None:
            raise _abort(0, 0, ABORT_COMMAND, "download segment without initiate")
        index, sub, complete, total, buf = self._down
        toggle = cmd & 0x10
        if toggle != self._down_toggle:
            raise _abort(index, sub, ABORT_TOGGLE)
        self._down_toggle ^= 0x10
        payload = bytes(request[1:])          # the caller trims to the mailbox length
        if len(payload) <= 7:
            payload = payload[: 7 - ((cmd >> 1) & 0x07)]
        buf += payload
        if cmd & 0x01:
            self._down = None
            self._store(index, sub, complete, bytes(buf[:total]))
        return struct.pack("<B7x", 0x20 | toggle)

    def _store(self, index: int, sub: int, complete: bool, data: bytes) -> None:
        if complete:
            self.write_complete(index, sub, data)
        else:
            self.write(index, sub, data)

    def _upload_init(self, cmd: int, index: int, sub: int, mbx_data_bytes: int) -> bytes:
        complete = bool(cmd & 0x10)
        data = self.read_complete(index, sub) if complete else self.read(index, sub)
        if len(data) <= 4 and not complete:
            return struct.pack("<BHB", 0x43 | ((4 - len(data)) << 2), index, sub) + data.ljust(4, b"\x00")
        room = mbx_data_bytes - 2 - 8
        head = struct.pack("<BHBI", 0x41, index, sub, len(data))
        self._up_data = data[room:]
        self._up_toggle = 0
        return head + data[:room]

    def _upload_segment(self, cmd: int, index: int, sub: int, mbx_data_bytes: int) -> bytes:
        toggle = cmd & 0x10
        if toggle != self._up_toggle:
            raise _abort(index, sub, ABORT_TOGGLE)
        self._up_toggle ^= 0x10
        room = mbx_data_bytes - 2 - 1
        chunk, self._up_data = self._up_data[:room], self._up_data[room:]
        last = 0x01 if not self._up_data else 0x00
        unused = 0
        if len(chunk) < 7:
            unused = 7 - len(chunk)
            chunk = chunk + b"\x00" * unused
        return bytes([toggle | (unused << 1) | last]) + chunk
