"""The planner's core: the data model (moves, programs, their columns), the machine and its
schema, the tool table, the frame of offsets, errors and the file writer. Imports nothing else
of the planner."""
