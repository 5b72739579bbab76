import sys

from mechsing.cli import main

sys.exit(main())
