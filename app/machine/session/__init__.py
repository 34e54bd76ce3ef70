"""The bus session: the worker's life cycle, the poll, persistence of the machine state and simulated time."""
