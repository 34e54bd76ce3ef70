"""The program: loading and checking it off the controller's thread (``loader``, ``checks``),
running it (``runner``: cycle start, hold, resume, stop, run from line, overrides) and the
operator's scripted actions of ``cnc-run --script`` (``scenario``)."""
