"""`python -m ethercat` = `cnc-ethercat`."""

from .cli import main

raise SystemExit(main())
