"""``python -m chaingraph`` is the ``chaingraph`` command."""

import sys

from .cli import main

sys.exit(main())
