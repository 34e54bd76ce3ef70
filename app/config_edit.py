"""Edits of the machine configuration for the service pages (no Qt): replace fields, validate.

Validation round-trips through the controller package's own TOML writer and strict reader,
so the pages accept exactly what the configuration file accepts, with the same messages.
"""

from __future__ import annotations

import os
import tomllib
from dataclasses import replace
from typing import Any

from app.machine.config import MachineConfig, config_from_dict, config_to_toml
from app.machine.errors import ConfigError

# Axis fields shown on the Axes page: (attribute, label, unit, decimals, minimum, maximum)
AXIS_FIELDS: tuple[tuple[str, str, str, int, float, float], ...] = (
    ("drive_position", "Drive", "", 0, 0, 64),
    ("counts_per_unit", "Counts/unit", "", 3, 1e-6, 1e9),
    ("min_pos", "Min", "unit", 3, -1e6, 1e6),
    ("max_pos", "Max", "unit", 3, -1e6, 1e6),
    ("v_max", "Vmax", "unit/s", 3, 1e-6, 1e6),
    ("a_max", "Amax", "unit/s²", 1, 1e-6, 1e8),
    ("j_max", "Jmax", "unit/s³", 1, 1e-6, 1e10),
    ("following_error_window", "FE window", "unit", 3, 1e-6, 1e3),
)


def validate(config: MachineConfig) -> str:
    """"" when the configuration is valid, else the reader's message (names key and value)."""
    try:
        config_from_dict(tomllib.loads(config_to_toml(config)), "<edited>",
                         base=None if config.path.startswith("<") or not config.path
                         else os.path.dirname(os.path.abspath(config.path)))
    except ConfigError as exc:
        return str(exc)
    except (ValueError, TypeError, KeyError) as exc:
        return f"{type(exc).__name__}: {exc}"
    return ""


def with_axis(config: MachineConfig, index: int, **changes: Any) -> MachineConfig:
    axes = list(config.machine.axes)
    axes[index] = replace(axes[index], **changes)
    return replace(config, machine=replace(config.machine, axes=tuple(axes)))


def with_limits(config: MachineConfig, **changes: float) -> MachineConfig:
    return replace(config, machine=config.machine.with_limits(**changes))


def with_planner(config: MachineConfig, **changes: Any) -> MachineConfig:
    return replace(config, machine=replace(config.machine,
                                           planner=replace(config.machine.planner, **changes)))


def with_homing(config: MachineConfig, **changes: Any) -> MachineConfig:
    return replace(config, homing=replace(config.homing, **changes))


def with_bus(config: MachineConfig, **changes: Any) -> MachineConfig:
    return replace(config, bus=replace(config.bus, **changes))
