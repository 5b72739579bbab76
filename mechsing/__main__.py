"""``python -m mechsing``: the ``mechsing`` command."""

import sys

from mechsing.cli import main

sys.exit(main())
