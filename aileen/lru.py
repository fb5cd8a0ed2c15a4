"""A bounded, thread-safe memory of answers already computed, least recently used first out.

Why one class: perception remembers a scene's facts (`perception.facts`) and the ASP module
remembers clingo's answers (`reasoning.asp.solve_once`), both because an experiment asks the
same question again and again, both from the threads of one process; the bookkeeping (a lock,
moving a hit to the back, dropping the oldest past the bound) is the same and lives here.
"""

from __future__ import annotations

import threading
from collections import OrderedDict
from collections.abc import Hashable
from typing import Generic, TypeVar

V = TypeVar("V")


class LruMemory(Generic[V]):
    """At most `kept` values by key; `get` refreshes a key, `put` drops the least recently
    used past the bound."""

    def __init__(self, kept: int) -> None:
        self.kept = kept
        self._values: OrderedDict[Hashable, V] = OrderedDict()
        self._lock = threading.Lock()

    def get(self, key: Hashable) -> V | None:
        """The value kept for `key` (now the most recently used), None when there is none."""
        with self._lock:
            value = self._values.get(key)
            if value is not None:
                self._values.move_to_end(key)
            return value

    def put(self, key: Hashable, value: V) -> None:
        with self._lock:
            self._values[key] = value
            self._values.move_to_end(key)
            while len(self._values) > self.kept:
                self._values.popitem(last=False)

    def clear(self) -> None:
        with self._lock:
            self._values.clear()

    def __len__(self) -> int:
        return len(self._values)
