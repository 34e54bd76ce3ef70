"""Motion planning: joint speeds by look-ahead, jerk-limited profiles, the plan, interpolation,
plans made as a run reaches them (window), the limit meter and stops along the path. Asks
the geometry; never reads G-code."""
