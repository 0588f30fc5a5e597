"""The hard-case stability suite: cases.py (the scenes), bounds.py (what
each renderer must reach on them), runner.py (rendering and checking).
Run it with `python3 -m validation.hard` (runner.main)."""
