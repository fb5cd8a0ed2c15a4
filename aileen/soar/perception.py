"""The perceived state on the input-link: objects with their percepts, QSR facts, held, time.

    (<il> ^scene <sc>)
    (<sc> ^time 12 ^object <ob> ^fact <q> ... ^held o3)
    (<ob> ^id o1 ^fact <f> ...)        percepts: isa(o1,cv_red) as (<f> ^predicate isa ^arg1 o1 ^arg2 cv_red)
    (<q> ^predicate w ^arg1 o1 ^arg2 o2)   the other facts of the state: QSR facts between objects,
                                           moved(o1), held(o3) (also as ^held o3)

`^time` is the index of the state in the agent's episodic memory: each perceived state is one
episode, and the agent recalls a demonstration by these times.

An object keeps its identifier while it is in view or held (the tracker keeps its id), and
only facts that changed are replaced, so productions matching an object are not disturbed
by a new frame that shows the same thing.
"""

from __future__ import annotations

from typing import Any

from aileen.soar import wm
from aileen.soar.kernel import SoarKernel
from aileen.terms import Term


class SceneLink:
    def __init__(self, kernel: SoarKernel) -> None:
        self.kernel = kernel
        self._scene = kernel.add(kernel.input_link, "scene")
        self._objects: dict[str, tuple[Any, tuple[Term, ...]]] = {}
        self._facts: dict[Term, Any] = {}
        self._held: Any = None
        self._held_id: str | None = None
        self._time: Any = None

    def clear(self) -> None:
        k = self.kernel
        for wme, _ in self._objects.values():
            k.remove(wme)
        for wme in self._facts.values():
            k.remove(wme)
        if self._held is not None:
            k.remove(self._held)
        self._objects.clear()
        self._facts.clear()
        self._held, self._held_id = None, None
        k.commit()

    def update(self, state: Any, time: int | None = None) -> None:
        """Bring the input-link up to `state` (an `aileen.agent.State`), perceived at `time`."""
        k = self.kernel
        if self._time is not None:
            k.remove(self._time)
        self._time = k.add(self._scene, "time", time) if time is not None else None
        percepts: dict[str, list[Term]] = {}
        others: list[Term] = []
        for f in state.facts:
            if f.name == "isa" and len(f.args) == 2:
                percepts.setdefault(str(f.args[0]), []).append(f)
            else:
                others.append(f)
        keep = set(state.objects) | ({state.held} if state.held else set())
        for oid in list(self._objects):
            if oid not in keep or (oid in percepts and tuple(percepts[oid]) != self._objects[oid][1]):
                k.remove(self._objects.pop(oid)[0])
        for oid, fs in percepts.items():
            if oid not in self._objects:
                ob = k.add(self._scene, "object")
                k.add(ob, "id", oid)
                wm.put_all(k, ob, "fact", fs)
                self._objects[oid] = (ob, tuple(fs))
        now = set(others)
        for f in list(self._facts):
            if f not in now:
                k.remove(self._facts.pop(f))
        for f in others:
            if f not in self._facts:
                self._facts[f] = wm.put(k, self._scene, "fact", f)
        if state.held != self._held_id:
            if self._held is not None:
                k.remove(self._held)
            self._held = k.add(self._scene, "held", state.held) if state.held else None
            self._held_id = state.held
        k.commit()
