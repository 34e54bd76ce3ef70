"""``python -m cli`` = ``cnc-plan``."""

import sys

from cli.plan import main

sys.exit(main())
