"""`python3 -m validation.hard`: the hard-case suite (runner.py)."""
import sys

from .runner import main

sys.exit(main())
