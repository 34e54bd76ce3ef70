"""Planner: G-code interpreter, exact arc/helix geometry and jerk-limited motion planning.

Units, stated once for the whole package (as Klipper does in its toolhead):
lengths in mm, time in s, angles of arcs in rad; rotary AXIS positions in degrees, as G-code
writes them. Names carry their unit: ``feed_mm_s``, ``v_max_mm_s``, ``a_max_mm_s2``,
``j_max_mm_s3``, ``ts_s``, ``cycle_time_s``. Inches and mm/min exist only inside the
interpreter, which converts them on reading.

This package imports neither Qt nor ``app``; a test walks the imports to keep it so.
"""
