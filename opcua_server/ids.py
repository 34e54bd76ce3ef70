"""Node ids, typed as asyncua's ``NodeId`` declares its fields."""

from __future__ import annotations

from asyncua import ua

__all__ = ["nid"]


def nid(identifier: int | str, ns: int = 0) -> ua.NodeId:
    """The node ``identifier`` (a number or a string) in namespace ``ns``."""
    value: ua.Int32 | ua.String = ua.Int32(identifier) if isinstance(identifier,
                                                                     int) else ua.String(identifier)
    return ua.NodeId(value, ua.Int16(ns))
