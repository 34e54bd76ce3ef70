"""The operator panel (PySide6). Pages and widgets talk to the machine controller
(app.machine) through Qt signals; the planner and EtherCAT packages know nothing of Qt."""
