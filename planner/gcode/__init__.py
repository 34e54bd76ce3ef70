"""Reading G-code as LinuxCNC 2.9 reads it: the lexer, O-word structure, the interpreter, cutter
compensation, lathe cycles, the bulk reader of plain lines, LinuxCNC's canonical calls."""
