"""`python -m sw2sim`: the same as the `sw2sim` command."""

from .cli import main

raise SystemExit(main())
