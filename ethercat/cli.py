"""`cnc-ethercat`: the integrator's command line tool (in the spirit of IgH's `ethercat`).

    cnc-ethercat slaves IFNAME                       position, AL state, vendor, product, name
    cnc-ethercat pdos IFNAME [--esi FILE]            PDO assignment and mapping per slave
    cnc-ethercat esi FILE.xml [--positions P ...]    [[bus.drives]] tables from a drive's ESI file
                                                     ([[bus.terminals]] from a terminal's)
    cnc-ethercat esi FILE.xml --check IFNAME         live slaves compared with their ESI
    cnc-ethercat upload IFNAME POS INDEX SUB         SDO read (value by the object's type)
    cnc-ethercat download IFNAME POS INDEX SUB VALUE SDO write
    cnc-ethercat emulate IFNAME --drives N [--terminals EK1100,EL1008]   software slaves on IFNAME
    cnc-ethercat bench [--sim | IFNAME] --seconds S --json   cycle timing of the worker

The bus commands need root (raw socket). They leave the slaves in PRE-OP, as found after
the scan. Exit status: 0 ok, 1 EtherCAT error (message on stderr), 2 usage error.
"""

from __future__ import annotations

import argparse
import json
import struct
import sys
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from .emulator.variants import VARIANTS
from .errors import ConfigurationError, EtherCATError
from .object_dictionary import KNOWN_OBJECTS, OBJECTS

if TYPE_CHECKING:
    from .esi import EsiDevice

_FORMATS = {"u8": "<B", "i8": "<b", "u16": "<H", "i16": "<h", "u32": "<I", "i32": "<i", "u64": "<Q",
            "i64": "<q"}


def _int(text: str) -> int:
    return int(text, 0)


def _scan(ifname: str) -> Any:
    from . import soem_access

    master = soem_access.open_master(ifname)
    try:
        soem_access.config_init(master, ifname)
        master.state_check(soem_access.AL_PREOP, 2_000_000)
    except BaseException:
        master.close()
        raise
    return master


def cmd_slaves(args: argparse.Namespace) -> int:
    from .soem_access import slave_infos

    master = _scan(args.ifname)
    try:
        infos = slave_infos(master)
    finally:
        master.close()
    if args.json:
        print(json.dumps([{"position": s.position, "state": s.state, "al_status_code": s.al_status_code,
                           "vendor_id": s.vendor_id, "product_code": s.product_code,
                           "revision": s.revision, "name": s.name} for s in infos]))
        return 0
    for s in infos:
        err = f"  AL status code 0x{s.al_status_code:04X}" if s.al_status_code else ""
        print(f"{s.position:3d}  {s.state:<8s} vendor 0x{s.vendor_id:08X}  product 0x{s.product_code:08X}  "
              f"rev 0x{s.revision:08X}  {s.name}{err}")
    return 0


def _entry_text(value: int, esi: EsiDevice | None = None) -> str:
    index, sub, bits = value >> 16, (value >> 8) & 0xFF, value & 0xFF
    entry = KNOWN_OBJECTS.get((index, sub))
    name = entry.name if entry is not None else ("padding" if index == 0 else "")
    if esi is not None and esi.object_name(index, sub):
        name = esi.object_name(index, sub)
    return f"0x{index:04X}:{sub:02X}  {bits:2d} bit  {name}"


def _esi_devices(path: str | None) -> dict[tuple[int, int], EsiDevice]:
    if not path:
        return {}
    from .esi import read_esi

    return {(d.vendor_id, d.product_code): d for d in read_esi(path)}


def cmd_pdos(args: argparse.Namespace) -> int:
    from .soem_access import read_mapping

    described = _esi_devices(args.esi)
    master = _scan(args.ifname)
    try:
        for pos, s in enumerate(master.slaves):
            print(f"slave {pos}: {s.name}")
            esi = described.get((int(s.man), int(s.id)))
            mapping = read_mapping(master, pos)
            for key, sm, label in (("rx", 2, "RxPDO (outputs)"), ("tx", 3, "TxPDO (inputs)")):
                for pdo, entries in mapping[key]:
                    print(f"  SM{sm} {label} 0x{pdo:04X}")
                    for e in entries:
                        print(f"    {_entry_text(e, esi)}")
    finally:
        master.close()
    return 0


def _object_format(index: int, sub: int, type_name: str | None) -> str | None:
    if type_name:
        return _FORMATS[type_name]
    entry = OBJECTS.get((index, sub))
    return entry.struct_format if entry is not None else None


def cmd_upload(args: argparse.Namespace) -> int:
    from .soem_access import sdo_upload

    master = _scan(args.ifname)
    try:
        data = sdo_upload(master, args.position, args.index, args.subindex)
    finally:
        master.close()
    fmt = _object_format(args.index, args.subindex, args.type)
    if fmt is not None and struct.calcsize(fmt) == len(data):
        value = struct.unpack(fmt, data)[0]
        print(f"0x{value & ((1 << (8 * len(data))) - 1):0{2 * len(data)}X} {value}")
    elif data and all(32 <= b < 127 for b in data):
        print(data.decode("ascii"))
    else:
        print(data.hex(" "))
    return 0


def cmd_download(args: argparse.Namespace) -> int:
    from .soem_access import sdo_download

    fmt = _object_format(args.index, args.subindex, args.type)
    if fmt is None:
        raise ConfigurationError(f"type of 0x{args.index:04X}:{args.subindex} unknown: give --type")
    try:
        data = struct.pack(fmt, args.value)
    except struct.error as exc:
        raise ConfigurationError(f"value {args.value} does not fit {fmt}: {exc}") from exc
    master = _scan(args.ifname)
    try:
        sdo_download(master, args.position, args.index, args.subindex, data)
    finally:
        master.close()
    return 0


def cmd_esi(args: argparse.Namespace) -> int:
    """The ``[[bus.drives]]`` tables for the devices of an ESI file, or with --check, the
    live slaves compared with it."""
    from .esi import check_slave, propose_drive_block, propose_terminal_block, read_esi
    from .terminals import type_of_identity

    devices = read_esi(args.file)
    if args.check:
        from .soem_access import read_mapping

        described = {(d.vendor_id, d.product_code): d for d in devices}
        master = _scan(args.check)
        bad = 0
        try:
            for pos, s in enumerate(master.slaves):
                identity = (int(s.man), int(s.id), int(s.rev))
                device = described.get(identity[:2])
                if device is None:
                    print(f"slave {pos} ({s.name}): not described in {args.file}")
                    continue
                problems = check_slave(device, identity, read_mapping(master, pos))
                bad += bool(problems)
                verdict = "; ".join(problems) if problems else "matches its ESI"
                print(f"slave {pos} ({s.name}): {verdict}")
        finally:
            master.close()
        return 1 if bad else 0
    if args.product is not None:
        devices = tuple(d for d in devices if d.product_code == args.product)
        if not devices:
            raise ConfigurationError(f"{args.file}: no device with product code 0x{args.product:08X}")
    device = devices[0]
    if len(devices) > 1:
        print(f"# {args.file} describes {len(devices)} devices; this is the first (choose with --product)")
    terminal = type_of_identity(device.vendor_id, device.product_code) is not None
    for pos in args.positions:
        print(propose_terminal_block(device, pos) if terminal else propose_drive_block(device, pos))
    return 0


def cmd_emulate(args: argparse.Namespace) -> int:
    from .emulator import run

    terminals = [t for t in args.terminals.split(",") if t] if args.terminals else []
    return run(args.ifname, args.drives, control_path=args.control, realtime=args.realtime,
               counts_per_unit=args.counts_per_unit, variant=args.variant, terminals=terminals)


def cmd_bench(args: argparse.Namespace) -> int:
    from .benchmark import run_bench

    if args.sim == bool(args.ifname):
        raise ConfigurationError("bench needs either --sim or an interface name")
    kwargs: dict[str, Any] = {"mode": args.mode}
    if args.sim:
        n = args.drives or 4
        result = run_bench("sim", "", args.seconds, n_drives=n, **kwargs)
    else:
        n = args.drives or _count_slaves(args.ifname)
        result = run_bench("soem", args.ifname, args.seconds, n_drives=n, **kwargs)
    if args.json:
        print(json.dumps(result))
    else:
        for key, value in result.items():
            if key == "bus_notes":
                continue
            print(f"{key:28s} {value}")
        for note in result.get("bus_notes", ()):
            print(f"note: {note}")
    return 0


def _count_slaves(ifname: str) -> int:
    master = _scan(ifname)
    try:
        return len(master.slaves)
    finally:
        master.close()


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="cnc-ethercat", description="EtherCAT tool of the CNC control")
    sub = p.add_subparsers(dest="command", required=True)
    s = sub.add_parser("slaves", help="list slaves: position, AL state, identity, name")
    s.add_argument("ifname")
    s.add_argument("--json", action="store_true")
    s.set_defaults(func=cmd_slaves)
    s = sub.add_parser("pdos", help="PDO assignment and mapping of every slave")
    s.add_argument("ifname")
    s.add_argument("--esi", default=None, help="ESI file naming the objects")
    s.set_defaults(func=cmd_pdos)
    s = sub.add_parser("esi", help="[[bus.drives]] tables from a drive's ESI file, or --check live slaves")
    s.add_argument("file", help="the drive's ESI XML file")
    s.add_argument("--positions", type=_int, nargs="+", default=[0], help="slave positions (default 0)")
    s.add_argument("--product", type=_int, default=None, help="product code, when the file has several")
    s.add_argument("--check", metavar="IFNAME", default=None,
                   help="compare the slaves on IFNAME with the file instead")
    s.set_defaults(func=cmd_esi)
    for name, helptext in (("upload", "SDO upload (read)"), ("download", "SDO download (write)")):
        s = sub.add_parser(name, help=helptext)
        s.add_argument("ifname")
        s.add_argument("position", type=_int, help="slave position (0-based)")
        s.add_argument("index", type=_int, help="object index, e.g. 0x6041")
        s.add_argument("subindex", type=_int)
        if name == "download":
            s.add_argument("value", type=_int)
        s.add_argument("--type", choices=sorted(_FORMATS), help="data type (default: from the CiA 402 model)")
        s.set_defaults(func=cmd_upload if name == "upload" else cmd_download)
    s = sub.add_parser("emulate", help="emulate CiA 402 drives on an interface (software slaves)")
    s.add_argument("ifname")
    s.add_argument("--drives", type=int, default=3)
    s.add_argument("--control", default=None, help="UNIX socket path for fault injection (JSON)")
    s.add_argument("--realtime", action="store_true", help="SCHED_FIFO if permitted")
    s.add_argument("--counts-per-unit", type=float, default=10_000.0)
    s.add_argument("--variant", choices=tuple(VARIANTS), default="standard",
                   help="how the drives differ from the project's own (see ethercat.emulator.variants)")
    s.add_argument("--terminals", default="",
                   help="terminals behind the drives, comma-separated (e.g. EK1100,EL1008,EL2008)")
    s.set_defaults(func=cmd_emulate)
    s = sub.add_parser("bench", help="cycle timing of the worker (simulated drives or a real link)")
    s.add_argument("ifname", nargs="?", default="")
    s.add_argument("--sim", action="store_true")
    s.add_argument("--seconds", type=float, default=10.0)
    s.add_argument("--drives", type=int, default=0,
                   help="drives (default: 4 with --sim, all slaves on a link)")
    s.add_argument("--mode", choices=("process", "thread"), default="process")
    s.add_argument("--json", action="store_true")
    s.set_defaults(func=cmd_bench)
    return p


def main(argv: Sequence[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    try:
        return int(args.func(args))
    except EtherCATError as exc:
        print(f"cnc-ethercat: error: {exc}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        return 130


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())
