"""Machine controller: the layer between the operator panel and the planner / EtherCAT worker.

No widgets here (QtCore signals at most): it runs and is tested headless. The pages only call
``MachineController`` methods and listen to its signals.
"""

from app.machine.errors import ConfigError, MachineError

__all__ = ["ConfigError", "MachineError"]
