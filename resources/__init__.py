"""Files shipped with the control, installed with it as package data: machine configurations,
sample programs, the panel's style sheet and its translations.

Everything that needs one of these files asks here, so an installed copy (``pip install .``,
not only an editable checkout) finds them. A leaf: it imports nothing of the project.
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["MACHINES", "PROGRAMS", "ROOT", "STYLES", "SUBROUTINES", "TRANSLATIONS", "shipped_machine",
           "shipped_program"]

ROOT = Path(__file__).resolve().parent
MACHINES = ROOT / "machines"
PROGRAMS = ROOT / "programs"
STYLES = ROOT / "styles"
TRANSLATIONS = ROOT / "translations"
# G-code subroutines shipped with the control (probing wizards, tool measuring after M6)
SUBROUTINES = ROOT / "subroutines"


def shipped_machine(name: str) -> Path:
    """A shipped machine configuration by name ('xyz_mill', 'paper_yzca')."""
    return MACHINES / f"{name}.toml"


def shipped_program(name: str) -> Path:
    """A shipped sample program by file name ('pocket.nc')."""
    return PROGRAMS / name
