"""``python -m dhsym`` runs the command line."""

import sys

from dhsym.cli.main import main

sys.exit(main())
