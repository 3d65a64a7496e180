"""``python -m exudyn_atcm``: the command line (see :mod:`exudyn_atcm.cli`)."""

from .cli import main

raise SystemExit(main())
