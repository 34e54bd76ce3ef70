"""Motion: where the axes are (``positions``), machine zero (``homing``), part zero and the
frame in force (``coordinates``), jobs and their set-points (``streamer``, ``feeding``,
``making``, ``jobs``), the time scale of overrides and holds (``timescale``), jog and MDI
(``manual``)."""
