"""A noun phrase the agent says has one head noun (syntax, not meaning): two words that have
only ever stood as heads, each fitting the object, are not said together ("red box capsule",
with "capsule" learned from capsules the detector read as medium boxes)."""

from __future__ import annotations

from types import SimpleNamespace

from aileen.agent.generation import Generation
from aileen.agent.lexicon import Lexicon
from aileen.terms import Term, fn


def _generation(fits: list[tuple[str, float]], meanings: dict[str, frozenset[Term]],
                positions: dict[str, set[str]]) -> Generation:
    """A generation part over a memory whose retrieval hands back `fits` (word, similarity)
    for the object, and a lexicon of `meanings` whose words stood where `positions` says."""
    lex = Lexicon(lambda c: meanings[c], lambda c: c[2:], lambda: list(meanings))
    lex.positions.update({w: set(p) for w, p in positions.items()})
    memory = SimpleNamespace(fitting=lambda *a, **k: [SimpleNamespace(concept=f"r_{w}", similarity=s,
                                                                        fact=fn("isa", "o1", f"r_{w}"))
                                                      for w, s in fits])
    semantic = SimpleNamespace(word=lambda c: c[2:], concept=lambda w: f"r_{w}")
    agent = SimpleNamespace(memory=memory, semantic=semantic, lexicon=lex,
                            params=SimpleNamespace(mutual_exclusivity=True))
    return Generation(agent)


def _p(*names: str) -> frozenset[Term]:
    return frozenset(Term(n) for n in names)


STATE = SimpleNamespace(percepts=lambda obj: [])


def test_one_head_noun_the_most_typical() -> None:
    meanings = {"r_red": _p("cv_red"), "r_box": _p("cv_box"), "r_capsule": _p("cv_medium")}
    at = {"red": {"modifier"}, "box": {"head"}, "capsule": {"head"}}
    gen = _generation([("red", 0.9), ("box", 0.8), ("capsule", 0.7)], meanings, at)
    assert gen.phrase("o1", STATE).words == ("red", "box")
    gen = _generation([("red", 0.9), ("capsule", 0.85), ("box", 0.8)], meanings, at)
    assert gen.phrase("o1", STATE).words == ("red", "capsule")


def test_modifiers_are_not_limited() -> None:
    meanings = {"r_large": _p("cv_large"), "r_red": _p("cv_red"), "r_box": _p("cv_box")}
    at = {"large": {"modifier"}, "red": {"modifier"}, "box": {"head"}}
    gen = _generation([("red", 0.9), ("box", 0.8), ("large", 0.7)], meanings, at)
    assert set(gen.phrase("o1", STATE).words) == {"large", "red", "box"}
