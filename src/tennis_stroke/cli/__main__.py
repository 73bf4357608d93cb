"""``python -m tennis_stroke.cli``: the ``tennis-stroke`` command, where the console script
is not on the PATH."""

import sys

from . import main

sys.exit(main())
