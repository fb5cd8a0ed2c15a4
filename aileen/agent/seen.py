"""How common each percept is among the objects the agent has been taught on: what no word's
meaning is left with, while no phrase position names its channel.

Why (issue 20, defect (a)): mutual exclusivity takes from a new word the percepts other words
stand for. "grox", said three times on a green box once "green" and "box" are known, kept what
was left: its size, `cv_medium`, and was then true of a blue box and of a green cylinder. The
lexicon already refused a meaning made only of the one value of a channel that any word's
meaning holds; but `lessons/visual.toml` shows one small sphere, which makes `cv_small` a
second value, and that guard let go ("kube", said on a red box and a blue box, then held of a
red sphere). A percept that most objects taught on have (`COMMON`), of a channel no word has
shown a phrase position to name (syntactic bootstrapping: before any size word, modifiers name
colours and heads shapes), tells nothing a word could be for: exclusivity does not leave a
meaning with only such percepts (`Lexicon.uninformative`), so "grox" is the conjunction
("green box") and "kube" a synonym ("box"). Once "small" and "large" are pinned before head
nouns, modifiers name sizes, and "medium red box" means medium however common it is.

The counts are of the objects on the table in the lessons the agent is taught from (informs),
each object once per lesson: not the exams, which would make what is learned depend on how
often it is examined. They are kept with the lexicon in the memory's annotations. A share is
read only once `MIN_OBJECTS` objects have been counted: from a handful, every percept of the
first lessons would look common.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable

from aileen.memory.persist import is_whole
from aileen.terms import Term

__all__ = ["COMMON", "MIN_OBJECTS", "SeenPercepts"]

# A percept at least this share of the objects counted have is common: a meaning made of such
# percepts alone would hold of most objects. (The visual lessons: `cv_medium` 0.82 of the
# objects, and the commonest colour or shape about 0.25; with the size lessons `cv_medium`
# falls to 0.62, with the relation lessons to 0.71, and "medium" is then a word to learn.)
COMMON = 0.75
# Fewer objects than this say too little about what is common.
MIN_OBJECTS = 10


class SeenPercepts:
    """Per percept, the number of objects counted that had it; and the number of objects.
    What is common is made again when they change, not on every question (the lexicon asks on
    every one)."""

    def __init__(self) -> None:
        self.objects = 0
        self.counts: Counter[Term] = Counter()
        self._common: frozenset[Term] = frozenset()
        self._constant: frozenset[Term] = frozenset()
        # per percept, how many objects from the first one on all had it (while unbroken, all
        # counted so far); and per visual word, the number of objects counted when it was
        # last taught: what a word's examples had that no object had yet gone without was
        # nothing a teacher could have pointed out (`unmarked`)
        self.runs: dict[Term, int] = {}
        self._unbroken: set[Term] = set()
        self.taught: dict[str, int] = {}
        self.said: dict[str, int] = {}  # per word, how many of its examples were stored

    def note(self, objects: Iterable[Iterable[str]]) -> bool:
        """Count each object's percepts (one lesson's table); True when what is common changed."""
        before = self._common
        for percepts in objects:
            self.objects += 1
            have = {Term(p) for p in percepts}
            self.counts.update(have)
            if self.objects == 1:
                self._unbroken = set(have)
            else:
                self._unbroken &= have
            for t in self._unbroken:
                self.runs[t] = self.objects
            for t in [t for t, n in self.runs.items() if n < 2 and t not in self._unbroken]:
                del self.runs[t]  # broken at the second object: never unmarked (`unmarked`)
        self._recount()
        return self._common != before

    def common(self) -> frozenset[Term]:
        """The percepts at least `COMMON` of the objects counted have (none before `MIN_OBJECTS`)."""
        return self._common

    def constant(self, also: Iterable[frozenset[Term]] = ()) -> frozenset[Term]:
        """The percepts every object counted had, once two or more were (`cv_medium` while
        every object taught on was medium-sized): no contrast any example has shown; with
        `also`, the objects of the lesson being taught from, not yet counted, must have them too."""
        out = self._constant
        for percepts in also:
            out = out & percepts
        return out

    def _recount(self) -> None:
        self._common = (frozenset() if self.objects < MIN_OBJECTS else
                        frozenset(t for t, n in self.counts.items() if n >= COMMON * self.objects))
        self._constant = (frozenset() if self.objects < 2 else
                          frozenset(t for t, n in self.counts.items() if n == self.objects))

    def note_taught(self, word: str) -> bool:
        """An example of `word` is stored now (the lesson's table counted already): its meaning
        is made of such examples; True when what is unmarked for it changed."""
        before = self.unmarked(word)
        self.taught[word] = self.objects
        # never more examples than objects counted (a word stored twice from one object, say
        # by two phrases of one sentence, made a memory file the loader refuses)
        self.said[word] = min(self.said.get(word, 0) + 1, self.objects)
        return self.unmarked(word) != before

    def all_examples_of(self, word: str) -> bool:
        """Whether every object counted (two or more) was an example of `word`: what they all
        had (`constant`) is then what the word's examples share, which it may name."""
        return self.objects >= 2 and self.said.get(word, 0) >= self.objects

    def unmarked(self, word: str) -> frozenset[Term]:
        """The percepts that every object had, from the first one counted until its latest
        example of `word` was stored (and at least two objects), where some of those objects
        were no example of it: no example could have shown a contrast there, and other things
        had them too, so the word does not name them (a word taught on every object so far, as
        "cylinder" on the first two cylinders, may). "green", said of a medium green
        sphere while every object shown was medium, then "large" and "small" showed that
        modifiers name sizes: it was read as medium (`Lexicon._narrowed`), and a medium red
        box was a "green red box"; with a channel of one's own whose default every object
        had ("matte"), "red" taught on matte objects named no glossy red cone once "glossy"
        was known. Nothing for a word never taught since these were counted (an older
        memory file)."""
        t = self.taught.get(word)
        if t is None:
            return frozenset()
        said = self.said.get(word, 0)
        return frozenset(p for p, n in self.runs.items() if n >= max(2, t) and n > said)

    def to_annotation(self) -> dict:
        out: dict = {"objects": self.objects, "percepts": {str(t): n for t, n in sorted(self.counts.items(), key=str)}}
        if self.runs:
            out["runs"] = {str(t): n for t, n in sorted(self.runs.items(), key=str)}
            out["unbroken"] = sorted(map(str, self._unbroken))
        if self.taught:
            out["taught"] = dict(sorted(self.taught.items()))
            out["said"] = dict(sorted(self.said.items()))
        return out

    def load_annotation(self, data: object) -> None:
        """Read what `to_annotation` wrote; anything else (an older memory file) counts nothing."""
        if not isinstance(data, dict):
            return
        objects, percepts = data.get("objects"), data.get("percepts")
        if not (is_whole(objects) and isinstance(percepts, dict)):
            return
        self.objects = objects
        self.counts = Counter({Term(str(p)): n for p, n in percepts.items() if is_whole(n) and n <= objects})
        runs, unbroken, taught = data.get("runs"), data.get("unbroken"), data.get("taught")
        if isinstance(runs, dict) and isinstance(unbroken, list):
            self.runs = {Term(str(p)): n for p, n in runs.items() if is_whole(n) and n <= objects}
            self._unbroken = {Term(str(p)) for p in unbroken} & set(self.runs)
        said = data.get("said")
        if isinstance(taught, dict) and isinstance(said, dict):
            self.taught = {str(w): n for w, n in taught.items() if is_whole(n) and n <= objects}
            self.said = {str(w): n for w, n in said.items() if is_whole(n) and n <= objects}
        self._recount()
