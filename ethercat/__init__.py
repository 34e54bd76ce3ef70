"""EtherCAT master side of the CNC control: CiA 402 drives, the bus interface (SoemBus on
pysoem, SimBus on simulated drives), the cyclic 1 ms worker. No Qt, no planner imports.

Units: positions in drive counts (int32 on the wire) or axis units (mm for linear axes,
degrees for rotary ones); times in seconds (`_s`) or microseconds (`_us`) as named.
"""
