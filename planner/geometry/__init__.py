"""Path geometry: arcs, curves, corner blends, fillets and transitions, the move tables, the
splitting of moves (resume) and the soft limits of a path. Built on the core; never plans."""
