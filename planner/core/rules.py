"""The machine configuration's rules across keys, checked once for every reader.

``schema.validate`` checks each key alone; these check what keys say together and what the
machine could not run: each drive table names an axis's drive, a tool setter lies in the
travel, a following-error window holds at least one encoder count, an axis crosses its travel
in less than an hour, the OPC UA host is an address. ``cnc-plan --config``, ``cnc-run``, the
panel and its Axes page read a file through ``machine.machine_from_valid``, which applies
them, so they refuse the same files with the same messages.
"""

from __future__ import annotations

import ipaddress
import re
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from planner.core.schema import Locator

if TYPE_CHECKING:
    from planner.core.machine import AxisSpec

__all__ = ["MAX_TRAVEL_TIME_S", "SectionRule", "check_axes", "check_sections", "drive_tables", "host_problem"]

#: an axis at its v_max, or the path at its rapid, crosses the travel in less than this: a
#: slower limit is a typo (v_max = 1e-3 made a 460 mm travel take 128 hours)
MAX_TRAVEL_TIME_S = 3600.0

#: what a caller adds for its own part of the file (the bus's drive tables: ``ethercat``)
SectionRule = Callable[[dict[str, Any], Locator], None]

_HOST_NAME = re.compile(r"(?=.{1,253}$)[A-Za-z0-9](?:[A-Za-z0-9-]{0,61}[A-Za-z0-9])?"
                        r"(?:\.[A-Za-z0-9](?:[A-Za-z0-9-]{0,61}[A-Za-z0-9])?)*")


def host_problem(host: str) -> str:
    """Why ``host`` cannot be an address to listen on ("" when it can): an IP address, or a
    host name of letters, digits, hyphens and dots."""
    try:
        ipaddress.ip_address(host)
        return ""
    except ValueError:
        pass
    if _HOST_NAME.fullmatch(host):
        return ""
    return f"{host!r} is not an IP address or a host name (0.0.0.0 listens on every interface)"


def _duration(seconds: float) -> str:
    return f"{seconds / 3600.0:.3g} h" if seconds >= 3600.0 else f"{seconds:.3g} s"


def check_axes(valid: dict[str, Any], loc: Locator, axes: tuple[AxisSpec, ...]) -> None:
    """What an axis's numbers say together: a window of at least one count; the travel crossed
    within ``MAX_TRAVEL_TIME_S``."""
    for i, ax in enumerate(axes):
        count = 1.0 / ax.counts_per_unit
        if ax.following_error_window < count:
            unit = "deg" if ax.rotary else "mm"
            raise loc.fail(("axes", i, "following_error_window"),
                           f"{ax.following_error_window:g} {unit} is below one encoder count "
                           f"({count:.4g} {unit} at counts_per_unit = {ax.counts_per_unit:g}): the "
                           f"drive would report a following error at the first count (axis {ax.name})")
        travel = 360.0 if ax.wrapped else ax.max_pos - ax.min_pos
        if travel / ax.v_max > MAX_TRAVEL_TIME_S:
            raise loc.fail(("axes", i, "v_max"),
                           f"{ax.v_max:g} crosses the {travel:g} travel in {_duration(travel / ax.v_max)}, "
                           f"more than {_duration(MAX_TRAVEL_TIME_S)}: a typo? (axis {ax.name})")
    linear = [ax.max_pos - ax.min_pos for ax in axes if not ax.rotary]
    lim = valid["limits"]
    if linear:
        longest = max(linear)
        for key in ("v_max_mm_s", "rapid_mm_s"):
            if longest / lim[key] > MAX_TRAVEL_TIME_S:
                raise loc.fail(("limits", key),
                               f"{lim[key]:g} mm/s crosses the {longest:g} mm travel in "
                               f"{_duration(longest / lim[key])}, more than {_duration(MAX_TRAVEL_TIME_S)}: "
                               "a typo?")


def check_sections(valid: dict[str, Any], loc: Locator, axes: tuple[AxisSpec, ...],
                   extra: SectionRule | None = None) -> None:
    """The controller's sections against the axes (``valid`` is schema-checked; a drive
    table's missing position is filled with its index, as the bus numbers it)."""
    check_axes(valid, loc, axes)
    n = len(axes)
    names = tuple(a.name for a in axes)
    positions = {a.drive_position for a in axes}
    positions |= {a.gantry_drive for a in axes if a.gantry_drive is not None}
    spindle = valid.get("spindle", {}).get("drive")
    b = valid["bus"]
    for i, d in enumerate(b["drives"]):
        if d["position"] is None:
            d["position"] = i
        if d["position"] not in positions and d["position"] != spindle:
            whose = f"any axis ({sorted(positions)})"
            whose += f" or the spindle ({spindle})" if spindle is not None else ""
            raise loc.fail(("bus", "drives", i, "position"), f"{d['position']} is not the drive of {whose}")
    for i, d in enumerate(b["drives"]):
        if bool(d["rx"]) != bool(d["tx"]):
            raise loc.fail(("bus", "drives", i, "rx" if not d["rx"] else "tx"),
                           "rx and tx are given together (the whole mapping) or not at all")
    if b["kind"] == "soem" and not b["adapter"]:
        raise loc.fail(("bus", "adapter"), 'is required when kind = "soem" (the network interface)')
    c = valid["controller"]
    z = [a for a in axes if a.name == "Z"]
    clearance = c["restart_clearance_mm"]
    if clearance is not None and z and not z[0].min_pos <= clearance <= z[0].max_pos:
        raise loc.fail(("controller", "restart_clearance_mm"),
                       f"{clearance:g} is outside the Z travel [{z[0].min_pos:g}, {z[0].max_pos:g}]")
    if c["spindle_drive"] >= n:
        raise loc.fail(("controller", "spindle_drive"),
                       f"{c['spindle_drive']} must be below the axis count {n}")
    pr = valid["probe"]
    if pr["drive"] is not None and pr["drive"] >= n:
        raise loc.fail(("probe", "drive"), f"{pr['drive']} must be below the axis count {n}")
    setter_keys = ("setter_x_mm", "setter_y_mm", "setter_z_mm")
    setter = [pr[k] for k in setter_keys]
    if any(v is not None for v in setter) and None in setter:
        missing = [k for k in setter_keys if pr[k] is None]
        raise loc.fail(("probe", missing[0]), "a tool setter needs setter_x_mm, setter_y_mm and "
                       "setter_z_mm together")
    for key, axis in zip(setter_keys, ("X", "Y", "Z"), strict=True):
        spec = next((a for a in axes if a.name == axis), None)
        if pr[key] is not None and (spec is None or not spec.min_pos <= pr[key] <= spec.max_pos):
            where = f"outside the {axis} travel [{spec.min_pos:g}, {spec.max_pos:g}]" if spec else \
                f"the machine has no {axis} axis"
            raise loc.fail(("probe", key), f"{pr[key]:g} is {where}")
    if pr["slow_feed_mm_min"] > pr["fast_feed_mm_min"]:
        raise loc.fail(("probe", "slow_feed_mm_min"), f"{pr['slow_feed_mm_min']:g} is faster than "
                       f"fast_feed_mm_min ({pr['fast_feed_mm_min']:g})")
    if pr["fast_feed_mm_min"] > pr["max_feed_mm_min"]:
        raise loc.fail(("probe", "fast_feed_mm_min"), f"{pr['fast_feed_mm_min']:g} is over "
                       f"max_feed_mm_min ({pr['max_feed_mm_min']:g}), the fastest probe move allowed")
    if valid["toolchange"]["measure"] and (pr["drive"] is None or None in setter):
        raise loc.fail(("toolchange", "measure"), "needs a tool setter: [probe] drive, setter_x_mm, "
                       "setter_y_mm and setter_z_mm")
    if pr["sim_surface_mm"] is not None and pr["sim_axis"] not in names:
        raise loc.fail(("probe", "sim_axis"), f"{pr['sim_axis']} is not an axis of this machine "
                       f"({', '.join(names)})")
    for i, o in enumerate(valid["outputs"]):
        if o["drive"] == c["spindle_drive"] and o["bit"] in (0, 1):
            raise loc.fail(("outputs", i, "bit"), f"bits 0 and 1 of drive {o['drive']} switch the "
                           "spindle ([controller] spindle_drive): use bit 2 or above")
    problem = host_problem(valid["opcua"]["host"])
    if problem:
        raise loc.fail(("opcua", "host"), problem)
    if extra is not None:
        extra(valid, loc)


def _ordinal(n: int) -> str:
    return f"{n}{'th' if 10 <= n % 100 <= 20 else {1: 'st', 2: 'nd', 3: 'rd'}.get(n % 10, 'th')}"


def drive_tables(problem_of: Callable[[dict[str, Any]], tuple[tuple[str | int, ...], str] | None]
                 ) -> SectionRule:
    """The rule that asks ``problem_of`` (the bus package's reading of a ``[[bus.drives]]``
    table) about each drive table and refuses the first problem at its key."""
    def rule(valid: dict[str, Any], loc: Locator) -> None:
        first: dict[int, int] = {}                 # slave position: the table that named it first
        for i, d in enumerate(valid["bus"]["drives"]):
            if d["position"] in first:
                raise loc.fail(("bus", "drives", i, "position"),
                               f"slave position {d['position']} already has a [[bus.drives]] table (the "
                               f"{_ordinal(first[d['position']] + 1)}): one table a drive")
            first[d["position"]] = i
            found = problem_of(d)
            if found is not None:
                key, why = found
                raise loc.fail(("bus", "drives", i, *key), why)
    return rule
