"""The names the agent's facts are made of beside the calculi's relations, declared once.

Why here: a relation of one's own (`calculi.declare`) named like one of them would make its
facts read as another's (`isa(o1,o2)` a membership, `holds(...)` the planner's), and the
domain is where a declaration is checked. The memory (`soar.bridge.RESERVED`), the agent's
reading of a verb (`agent.verbs`) and the concept symbols (`memory.semantic`) read them from
here; the planner's predicates are read from its shipped programs (`planner`), whose folder
`reasoning.rulefiles` finds through `shipped_rules`.
"""

from __future__ import annotations

import functools
import re
from pathlib import Path

import aileen

__all__ = ["CONCEPT_PREFIX", "MEMORY", "NOT_YET", "SLOT", "STAYED", "planner", "shipped_rules"]

SLOT = "said_rel"  # h(T, said_rel(a,b)): the sentence's relation holds between a and b
NOT_YET = "not_said_rel"  # h(T0, not_said_rel(a,b)): at the start it did not (what the move changed)
STAYED = "stayed"  # the object a verb's demonstration did not move
# The predicates of the memory's facts: isa(o,c), h(T,fact), after(T1,T0), start(T), and the
# roles of a verb's example above.
MEMORY: frozenset[str] = frozenset({"isa", "h", "after", "start", SLOT, NOT_YET, STAYED})
CONCEPT_PREFIX = "r_"  # a concept's symbol: the word "left of" is the concept r_left_of


@functools.lru_cache(maxsize=1)
def shipped_rules() -> Path | None:
    """The folder of the shipped ASP programs (in the package, or beside it in a checkout);
    None when there is none."""
    pkg = Path(aileen.__file__).resolve().parent
    return next((c for c in (pkg / "asp", pkg.parent / "asp") if c.is_dir() and any(c.glob("*.lp"))), None)


@functools.lru_cache(maxsize=1)
def planner() -> frozenset[str]:
    """Every predicate the shipped ASP programs use (holds, occurs, poss, rel, calculus, ...),
    read from them (comments left out)."""
    folder = shipped_rules()
    texts = (re.sub(r"%.*", "", p.read_text()) for p in sorted(folder.glob("*.lp"))) if folder else ()
    return frozenset(m for t in texts for m in re.findall(r"\b([a-z][A-Za-z0-9_]*)\(", t))
