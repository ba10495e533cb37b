"""``python -m chaingraph`` is the ``chaingraph`` command."""

import sys

from chaingraph.cli.main import main

sys.exit(main())
