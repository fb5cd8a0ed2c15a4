"""The kinds of concept the memory holds (a concept is created with one)."""

KINDS: tuple[str, ...] = ("visual", "spatial", "action", "composite")
