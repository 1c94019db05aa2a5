"""``python -m hollowbody``: the same as the ``hollowbody`` command."""

import sys

from hollowbody.cli.main import main

sys.exit(main())
