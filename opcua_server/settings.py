"""What the ``[opcua]`` section of the machine configuration asks of the server.

Read-only monitoring only: the server exposes no method and accepts no write, whatever these
settings say. Security "None" is used only when named (in the file, or by ``--opcua-insecure``,
which also binds 127.0.0.1 alone).
"""

from __future__ import annotations

import enum
import socket
from dataclasses import dataclass, replace
from typing import Any

from planner.core.rules import host_problem

__all__ = ["IDENTIFICATION_KEYS", "Identity", "OpcUaOverride", "OpcUaSettings", "SecurityMode",
           "host_problem"]

#: the optional Identification fields the ``[opcua]`` section may fill (a shop's MES and the
#: umati dashboard show them)
IDENTIFICATION_KEYS = ("product_code", "year_of_construction", "month_of_construction", "location",
                       "manufacturer_uri", "hardware_revision", "device_class", "asset_id")


class SecurityMode(enum.StrEnum):
    """An endpoint's security: the policy and message mode, as OPC UA names them."""

    SIGN_AND_ENCRYPT = "Basic256Sha256_SignAndEncrypt"
    SIGN = "Basic256Sha256_Sign"
    NONE = "None"


@dataclass(frozen=True, slots=True)
class Identity:
    """The MachineTool's Identification (OPC 40501 with OPC 40001-1 and DI): what a shop's
    MES files the machine under."""

    manufacturer: str
    model: str
    serial_number: str
    product_instance_uri: str
    software_revision: str
    product_code: str = ""
    year_of_construction: int = 0     # 0: not given (the node is left out)
    month_of_construction: int = 0    # 0: not given
    location: str = ""
    manufacturer_uri: str = ""
    hardware_revision: str = ""
    device_class: str = ""
    asset_id: str = ""


@dataclass(frozen=True, slots=True)
class OpcUaSettings:
    enabled: bool = False
    host: str = "0.0.0.0"
    port: int = 4840
    security: tuple[SecurityMode, ...] = (SecurityMode.SIGN_AND_ENCRYPT,)
    anonymous: bool = False          # read access without a user name
    rate_hz: float = 10.0            # snapshots read per second, at most
    manufacturer: str = ""
    model: str = ""
    serial_number: str = ""
    product_instance_uri: str = ""
    product_code: str = ""
    year_of_construction: int = 0
    month_of_construction: int = 0
    location: str = ""
    manufacturer_uri: str = ""
    hardware_revision: str = ""
    device_class: str = ""
    asset_id: str = ""
    # the server's ApplicationUri ("": one made for this installation, see ``application_uri_for``)
    application_uri: str = ""
    # a session whose client vanished (no CloseSession) is closed after this long, with its
    # subscriptions; at most ``max_clients`` sessions at once (connections that have not
    # activated one do not count: they have a bound of their own, ``channel.PENDING_CONNECTIONS``)
    session_timeout_s: float = 60.0
    max_clients: int = 64

    @staticmethod
    def from_valid(section: dict[str, Any]) -> OpcUaSettings:
        """From the schema-checked ``[opcua]`` section."""
        return OpcUaSettings(
            enabled=section["enabled"], host=section["host"], port=section["port"],
            security=tuple(SecurityMode(s) for s in dict.fromkeys(section["security"])),
            anonymous=section["anonymous"], rate_hz=section["rate_hz"],
            manufacturer=section["manufacturer"], model=section["model"],
            serial_number=section["serial_number"], product_instance_uri=section["product_instance_uri"],
            **{key: section[key] for key in IDENTIFICATION_KEYS},
            application_uri=section["application_uri"])

    def insecure_local(self, port: int) -> OpcUaSettings:
        """``--opcua-insecure``: security None and anonymous reading, on 127.0.0.1 only."""
        return replace(self, enabled=True, host="127.0.0.1", port=port, security=(SecurityMode.NONE,),
                       anonymous=True)

    @property
    def insecure(self) -> bool:
        """An endpoint anyone who reaches the port can read without a certificate."""
        return SecurityMode.NONE in self.security

    @property
    def endpoint(self) -> str:
        host = self.host if self.host not in ("0.0.0.0", "::") else socket.gethostname()
        return f"opc.tcp://{host}:{self.port}/"

    @property
    def bind_endpoint(self) -> str:
        return f"opc.tcp://{self.host}:{self.port}/"

    def identity(self, machine_name: str, software_revision: str, installation: str) -> Identity:
        """The Identification; ``installation`` is this installation's own id (its state
        folder's), which makes the default ProductInstanceUri differ between installations
        even on one host and with one machine name."""
        host = socket.gethostname()
        serial = self.serial_number or f"{host}-{machine_name}"
        uri = self.product_instance_uri or f"urn:cnc-panel:{host}:{installation}"
        return Identity(manufacturer=self.manufacturer or "cnc-panel", model=self.model or machine_name,
                        serial_number=serial, product_instance_uri=uri, software_revision=software_revision,
                        **{key: getattr(self, key) for key in IDENTIFICATION_KEYS})

    def application_uri_for(self, installation: str) -> str:
        """The server's ApplicationUri: the configured one, or one of this host and this
        installation (OPC UA asks every server application instance for its own)."""
        return self.application_uri or f"urn:{socket.gethostname()}:cnc-panel:{installation}"

    def describe(self) -> str:
        """One line for the operator and the log: where and how it serves."""
        modes = ", ".join(s.value for s in self.security)
        who = "anonymous and users" if self.anonymous else "users only"
        text = f"{self.endpoint} ({modes}; {who})"
        if self.insecure:
            text += ": security None, anyone who reaches the port reads the machine"
        return text


@dataclass(frozen=True, slots=True)
class OpcUaOverride:
    """The command line's ``--opcua-port`` / ``--opcua-insecure`` over the configured
    ``[opcua]``: a port serves with the configured security; insecure serves with none, on
    127.0.0.1 only (the configured port when no port is given)."""

    port: int | None = None
    insecure: bool = False

    def __post_init__(self) -> None:
        if self.port is not None and not 1 <= self.port <= 65535:
            raise ValueError(f"--opcua-port {self.port}: a TCP port is 1 to 65535")

    def apply(self, configured: OpcUaSettings) -> OpcUaSettings:
        if self.insecure:
            return configured.insecure_local(self.port if self.port is not None else configured.port)
        if self.port is not None:
            return replace(configured, enabled=True, port=self.port)
        return configured
