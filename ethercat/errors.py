"""The one error tree of the `ethercat` package.

Every error is an `EtherCATError` (a `RuntimeError`); where a built-in fits, the error
also inherits it (python-can style), so `except TimeoutError` catches every timeout and
`except ConnectionError` a missing adapter. Codes (AL status, SDO abort, CiA 402 error
code) are kept as attributes and appended to the message in hex.
"""

from __future__ import annotations


class EtherCATError(RuntimeError):
    """Base of all errors raised by the `ethercat` package. ``step``: the bus start-up step it
    happened in (a ``StartupStep``), None outside the start-up."""

    step: object = None


class EtherCATTimeoutError(EtherCATError, TimeoutError):
    """An operation did not finish in time (state change, SDO, worker start)."""


class AdapterError(EtherCATError, ConnectionError):
    """The network adapter cannot be opened (missing interface, no CAP_NET_RAW)."""


class BusStateError(EtherCATError):
    """The bus is used in the wrong state (not open, closed, not in OP)."""


class BusFeatureError(EtherCATError, NotImplementedError):
    """The bus backend does not have an optional feature (fault injection on real drives)."""


class ConfigurationError(EtherCATError, ValueError):
    """Invalid configuration (drive list, cycle time, scale, PDO mapping)."""


class SlaveIdentityError(ConfigurationError):
    """A slave's identity differs from the machine configuration."""

    def __init__(self, position: int, expected: tuple[int, int], found: tuple[int, int]) -> None:
        self.position = position
        self.expected = expected
        self.found = found
        super().__init__(
            f"slave {position}: expected vendor 0x{expected[0]:08X} product 0x{expected[1]:08X}, "
            f"found vendor 0x{found[0]:08X} product 0x{found[1]:08X}"
        )


class AlStateError(EtherCATError):
    """A slave did not reach the requested AL state (INIT/PRE-OP/SAFE-OP/OP)."""

    def __init__(self, message: str, position: int = -1, al_status_code: int = 0) -> None:
        self.position = position
        self.al_status_code = al_status_code
        super().__init__(f"{message} (AL status code 0x{al_status_code:04X})")


class AlStateTimeoutError(AlStateError, EtherCATTimeoutError):
    """AL state change not reached within its timeout."""


class SdoError(EtherCATError):
    """A CoE SDO transfer failed."""


class SdoAbortError(SdoError):
    """The slave aborted an SDO transfer (CiA 301 abort code)."""

    #: CiA 301 abort codes used by the drive model and the emulator.
    OBJECT_DOES_NOT_EXIST = 0x0602_0000
    SUBINDEX_DOES_NOT_EXIST = 0x0609_0011
    READ_ONLY = 0x0601_0002
    WRITE_ONLY = 0x0601_0001
    LENGTH_MISMATCH = 0x0607_0010
    VALUE_RANGE = 0x0609_0030
    GENERAL = 0x0800_0000

    def __init__(self, position: int, index: int, subindex: int, abort_code: int, text: str = "",
                 label: str = "") -> None:
        self.position = position
        self.index = index
        self.subindex = subindex
        self.abort_code = abort_code
        detail = f": {text}" if text else ""
        super().__init__(
            f"SDO 0x{index:04X}:{subindex} on {label or f'slave {position}'} aborted{detail} "
            f"(abort code 0x{abort_code:08X})"
        )


class SdoTimeoutError(SdoError, EtherCATTimeoutError):
    """No SDO answer within the mailbox timeout."""


class WorkerError(EtherCATError):
    """The cyclic worker failed to start, or was used in the wrong state."""


class WorkerTimeoutError(WorkerError, EtherCATTimeoutError):
    """The cyclic worker did not answer in time."""
