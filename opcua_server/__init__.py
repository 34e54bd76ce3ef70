"""The OPC UA server (OPC 40501 Machine Tools): read-only monitoring of the machine for a
shop's MES, dashboards and other clients. No Qt; it reads the controller's status snapshot."""

from opcua_server.errors import OpcUaError
from opcua_server.settings import Identity, OpcUaSettings, SecurityMode

__all__ = ["Identity", "OpcUaError", "OpcUaSettings", "SecurityMode"]
