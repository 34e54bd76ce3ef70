"""Registry of the panel's pages, in navigation order.

Each entry names the page (used by ``--page NAME``), its navigation label and the module
that builds it. A module exposes ``create_page(context) -> QWidget``. Pages not built yet
say so plainly on screen (see placeholder.py).
"""

from __future__ import annotations

from dataclasses import dataclass

from app.i18n import N_


@dataclass(frozen=True, slots=True)
class PageInfo:
    name: str
    label: str
    module: str          # module under app.pages providing create_page(context)
    service: bool = False  # behind the service password


PAGES: tuple[PageInfo, ...] = (
    PageInfo("auto", N_("Auto"), "auto"),
    PageInfo("manual", N_("Manual"), "manual"),
    PageInfo("program", N_("Program"), "program"),
    PageInfo("preview", N_("Preview"), "preview"),
    PageInfo("machine_zero", N_("Machine zero"), "machine_zero"),
    PageInfo("part_zero", N_("Part zero"), "part_zero"),
    PageInfo("tools", N_("Tools"), "tools"),
    PageInfo("axes", N_("Axes"), "axes", service=True),
    PageInfo("parameters", N_("Parameters"), "parameters", service=True),
    PageInfo("diagnostics", N_("Diagnostics"), "diagnostics"),
    PageInfo("alarms", N_("Alarms"), "alarms"),
)

PAGE_NAMES: tuple[str, ...] = tuple(p.name for p in PAGES)


def page_info(name: str) -> PageInfo:
    for p in PAGES:
        if p.name == name:
            return p
    raise KeyError(f"unknown page {name!r}; pages are: {', '.join(PAGE_NAMES)}")
