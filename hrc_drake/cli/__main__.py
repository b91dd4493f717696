"""`python -m hrc_drake.cli`: the `hrc-drake` command."""

import sys

from hrc_drake.cli import main

sys.exit(main())
