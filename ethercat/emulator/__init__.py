"""A software EtherCAT slave segment: N CiA 402 drives answering real frames.

`Segment` handles frames in process (unit tests feed it bytes); `EmulatorServer` puts
it on a network interface (raw socket, EtherType 0x88A4), e.g. the far end of a veth
pair in a network namespace; `cnc-ethercat emulate IFNAME --drives N` runs it. The
drives are the shared `ethercat.drive_model.DriveModel`, the same as `SimBus` uses.
"""

from .segment import ETHERTYPE_ECAT, Segment
from .server import EmulatorServer, control, run

__all__ = ["ETHERTYPE_ECAT", "EmulatorServer", "Segment", "control", "run"]
