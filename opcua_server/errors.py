"""The one error type of the OPC UA server."""

from __future__ import annotations


class OpcUaError(Exception):
    """The server cannot start or a setting is unusable; the message says what and why, and
    names the configuration key where one is at fault."""
