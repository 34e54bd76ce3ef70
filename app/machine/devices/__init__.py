"""What the drives' outputs and inputs do besides the axes: the spindle, the program's outputs,
the tool table and setter, probing (G38.x) and waiting for inputs (M66)."""
