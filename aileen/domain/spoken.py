"""Who already says a word: the live declarations, read when a new one is made.

Why: a word of a sentence is read as one thing. A relation spelled "striped" beside a channel
value "striped", a verb spelled "red", a channel value "cube" beside the shape spelled so: each
reader then takes the word for whichever it asks first, and the other is never heard. Each
`declare` (relations, channels, actions) asks `owner` of every word it would add, so whether a
declaration is refused does not depend on which module was loaded first, and it reads what is
declared now (a user's verb, a user's channel), never a list of its own.

Each registry is read where its module is imported (`sys.modules`), never imported from here:
the registries ask this module, and a declaration of one's own exists only once its module is
imported; `extensions.load` imports the shipped domain before any module of one's own, so
every shipped word is there to be asked.
"""

from __future__ import annotations

import sys

__all__ = ["owner"]


def _relation(word: str) -> str | None:
    relations = sys.modules.get("aileen.domain.relations")
    if relations is None or not hasattr(relations, "_ALIASES"):
        return None
    name = relations._ALIASES.get(relations._normalise(word))
    if name is not None:
        return f"the relation {name!r}"
    # a word of a relation's phrase ("abreast" of "abreast of"): the reader takes the phrase
    phrase = next((s for s in relations.spellings() if word in s.split()), None)
    return f"a word of the relation {relations.spellings()[phrase]!r}" if phrase is not None else None


def _channel(word: str) -> str | None:
    channels = sys.modules.get("aileen.domain.channels")
    for c in getattr(channels, "CHANNELS", ()):
        if word in c.values:
            return f"a {c.name} ({word!r})"
        spelled = dict(c.spellings).get(word)
        if spelled is not None:
            return f"a {c.name} (a spelling of {spelled!r})"
    return None


def _verb(word: str) -> str | None:
    actions = sys.modules.get("aileen.domain.actions")
    if actions is None or not hasattr(actions, "VERBS"):
        return None
    name = actions.verb_words().get(word)
    return f"the verb {name!r}" if name is not None else None


_KINDS = {"relation": _relation, "channel": _channel, "verb": _verb}


def owner(word: str, *, skip: str = "") -> str | None:
    """What a declared relation (any spelling), channel value or spelling, or verb (name or
    spelling) already says `word` with, in words ("the relation 'left of'"); None when none
    does. `skip` names the kind ("relation", "channel", "verb") the caller checks itself."""
    for kind, ask in _KINDS.items():
        if kind != skip:
            found = ask(word)
            if found is not None:
                return found
    return None
