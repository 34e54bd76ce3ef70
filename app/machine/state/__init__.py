"""The machine's state: the state machine and its refusals (``states``, ``gate``), the alarm log
(``alarms``) and the status snapshot (``status``)."""
