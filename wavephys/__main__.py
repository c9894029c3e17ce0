"""``python -m wavephys``: the ``wavephys`` command."""

import sys

from wavephys.app.cli import main

sys.exit(main())
