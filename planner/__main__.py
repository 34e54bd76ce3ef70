"""``python -m planner`` = ``cnc-plan``."""

import sys

from planner.cli import main

sys.exit(main())
