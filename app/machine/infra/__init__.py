"""What every part stands on: the typed channels they talk by (``events``), the worker's handle
(``drives``), the configuration in force (``settings``), the state folder (``persist``) and
the facade's declarations (``forward``)."""
