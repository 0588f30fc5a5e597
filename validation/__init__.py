"""The cross-renderer validation (docs/validation.md), a package: run its
tools from the source tree as `python3 -m validation.validate`,
`python3 -m validation.hard`, `python3 -m validation.peers`."""
