"""One part of the agent (reading, grounding, demonstrations, composites, learning, acting,
generation, feedback): an object the `Agent` holds, with its own caches and records, that
reads the agent's shared memories through the agent.

Why parts rather than mixins: a mixin's caches lived in the agent's one namespace, made lazily
by one mixin and reset by others, and a reader could not tell which method belonged to which
job. A part keeps what it made, as fields made in its `__init__` and reset by its own methods
(the grounding its last comprehension's evidence, the feedback part its last answer, ...), and
what it asks of another part it asks by name (`self.agent.grounding.understand`,
`self.agent.generation.location`). The agent inherits none of them: its public signals
(`inform`, `verify`, `react`, ...) hand each call to the part that does it.

The shared memories (`memory`, `semantic`, `episodic`, `lexicon`, `directions`, the scene
`state`, `params`) are the agent's, read-only here: a part never rebinds them (a part that
assigned `self.state` would shadow the agent's; the properties have no setter, so it cannot).
The body's state (`held`, the tracker, the agent's random stream) and `perceive` are the
agent's too; the acting part moves the hand through them (`self.agent.held`).

A copy of the agent (`Agent.snapshot`, `restore`, `forget`) copies its parts with it; their
back reference (`agent`) is mapped to the agent the copy becomes.
"""

from __future__ import annotations

from typing import Any


class Part:
    """A part of an agent (`agent`: the `aileen.agent.Agent` it belongs to; typed loosely, since
    the agent's module imports its parts)."""

    def __init__(self, agent: Any) -> None:
        self.agent = agent

    @property
    def memory(self) -> Any:  # aileen.memory.concept.ConceptMemory
        return self.agent.memory

    @property
    def semantic(self) -> Any:  # aileen.memory.semantic.SemanticMemory
        return self.agent.semantic

    @property
    def episodic(self) -> Any:  # aileen.memory.episodic.EpisodicMemory
        return self.agent.episodic

    @property
    def lexicon(self) -> Any:  # aileen.agent.lexicon.Lexicon
        return self.agent.lexicon

    @property
    def directions(self) -> Any:  # aileen.agent.directions.Directions
        return self.agent.directions

    @property
    def params(self) -> Any:  # aileen.agent.records.AgentParams
        return self.agent.params

    @property
    def state(self) -> Any:  # aileen.agent.state.State | None: the scene now seen
        return self.agent.state
