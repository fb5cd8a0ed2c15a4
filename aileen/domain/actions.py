"""The body's primitive actions, the fluents they change and the verbs taught with them, declared once.

Why one place: grading, the trainer's layouts and demonstrations, the agent's body and hand,
its perception of what the hand did and the planner's action models all ask the same
questions of an action ("does it go to an object or into a region?", "what does it change?",
"when has the trainer's verb been done?"). Each answer is declared here and read there, so no
verb is "a push" by default and "not touching" does not mean "place" anywhere.

A `Fluent` is a fact the action models change over time (`holds(F,T)` in `asp/planning.lp`):
its name and arity in the models, and how the agent knows it holds (`known`):

* `hand`: what the hand holds, from its grasp and release (`held(O)`);
* `sight`: what the camera shows (`rel(P,A,B)` for a relation fact, `moved(O)` when a centre
  shifted);
* `deed`: the hand was seen doing it to the object, or did it itself (`pushed(O)`): the mark an
  action leaves, perceived in the frame right after it.

A `PrimitiveAction` says everything the rest of aileen needs about one thing the hand can do:

* `name`: its symbol in plans, traces and transcripts (`pick_up(o1)`), and the name of its
  action model in `asp/actions.lp` (or in its own `model` file);
* `spellings`: how lesson files may write it in demonstration steps (`pick-up`, `pickup`);
* `kind`: `touch` (the hand goes to an object, addressed by where it is seen in the image: the
  trainer's pointing during a demonstration, the agent's own body when it acts) or `region`
  (it puts an object into a region: the planner's relations, made a position by region
  sampling, or the trainer's layout);
* `hand`: what it does to what the agent holds (`grasp`, `release`, or nothing);
* `world`: the call that carries it out in the simulator (the trainer's demonstrations and the
  agent's body both end here);
* `adds`, `dels`: the fluents its model makes true and false (unary fluents of the object it
  is done to; `rel`: the relations of its region, or every relation of its object that is not
  static). The model in the `.lp` file says the same, and `reasoning/models.py` holds the two
  together when the planner loads it;
* `model`: the file of its ASP model when it is not in the shipped `asp/actions.lp`.

A `Verb` is a word the trainer teaches with a demonstration: `move` (with a relation: "move X
left of Y", pick X up and place it so) or `push` (one object: "push X"). What the verb means is
learned from the demonstration; the declaration tells the trainer how to demonstrate it
(`steps`), where the object must stand so the demonstration can be shown (`room`) and when a
react has done it (`goal`), and the grammar the words that say it (`spellings`).

To add an action or a verb: `declare(...)` it (a test may do so inside `declared(...)` only),
with a model in `asp/actions.lp` or its own `.lp` file (`model`); docs/architecture.md has
the recipe and `tests/test_actions.py` follows it for "pull".
"""

from __future__ import annotations

import contextlib
import dataclasses
import re
import sys
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TypeVar

from aileen.domain import calculi, relations
from aileen.errors import UserError
from aileen.terms import DECLARED_NAME, Term, fn
from aileen.world import catalog, stacks
from aileen.world.camera import Table
from aileen.world.sim import SettleReport, World, WorldObject

WorldCall = Callable[[World, str, "tuple[float, float] | None", "str | None"], "SettleReport | None"]

TOUCH, REGION = "touch", "region"  # PrimitiveAction.kind
KINDS: tuple[str, ...] = (TOUCH, REGION)
GRASP, RELEASE = "grasp", "release"  # PrimitiveAction.hand
HAND, SIGHT, DEED = "hand", "sight", "deed"  # Fluent.known
REL = "rel"  # the fluent of a relation fact: rel(P,A,B) for P(A,B)


@dataclass(frozen=True)
class Fluent:
    """A fact the action models change over time; see the module doc."""

    name: str
    arity: int  # its arguments in the action models: held(O) 1, rel(P,A,B) 3
    known: str  # HAND | SIGHT | DEED: how the agent knows it holds
    doc: str = ""


@dataclass(frozen=True)
class PrimitiveAction:
    """One thing the hand can do; see the module doc."""

    name: str
    spellings: tuple[str, ...]
    kind: str  # TOUCH | REGION
    hand: str | None  # GRASP | RELEASE | None
    world: WorldCall  # (world, object id, position or None, object to rest on or None)
    syntax: str  # how a demonstration step writes it (docs and error messages)
    adds: tuple[str, ...] = ()  # fluents its model makes true
    dels: tuple[str, ...] = ()  # fluents its model makes false
    # its ASP model, when it is not in asp/actions.lp; a relative path is read from the folder
    # of the module that declares it
    model: Path | None = None

    @property
    def touches(self) -> bool:
        """Addressed at an object's pixel (`kind` touch), rather than into a region."""
        return self.kind == TOUCH

    @property
    def marks(self) -> tuple[str, ...]:
        """The fluents the agent records of the object in the frame right after it: it saw (or
        felt) the hand do it (`Fluent.known` deed)."""
        return tuple(f for f in self.adds if FLUENTS[f].known == DEED)


@dataclass(frozen=True)
class Outcome:
    """What the trainer sees when it grades a react: the lesson's objects now (the one the
    verb is done to first, then its reference), where each stood before it, and the relation
    the sentence names."""

    objects: tuple[WorldObject, ...]
    start: tuple[tuple[float, float] | None, ...]
    relation: str | None = None


GoalTest = Callable[[Outcome], bool]
# (x, y, half-width of the object, table, the trainer's edge margin) -> can the verb be shown
# on an object standing there?
Room = Callable[[float, float, float, Table, float], bool]


@dataclass(frozen=True)
class Verb:
    """A verb the trainer demonstrates: with a relation (`move X <r> Y`) or on one object."""

    name: str
    steps: tuple[str, ...]  # the primitive actions of its demonstration, on object 1 (region: <r> object 2)
    goal: GoalTest  # has a react done it? (the trainer's grading, as a person judges)
    room: Room | None = None  # where the object it is done to must stand to show it (None: anywhere)
    spellings: tuple[str, ...] = ()  # other words a sentence may say it with

    @property
    def takes_relation(self) -> bool:
        """Its demonstration puts the object into a region: the sentence names the relation."""
        return any(ACTIONS[s].kind == REGION for s in self.steps)

    @property
    def words(self) -> tuple[str, ...]:
        return (self.name, *self.spellings)


# ------------------------------------------------------------------ goal tests and room


def in_relation(out: Outcome) -> bool:
    """`move X <r> Y` is done: X and Y are on the table and X stands in the relation to Y
    (`relations.holds`, as a person judges it: 45 degrees either side for a direction)."""
    if out.relation is None or len(out.objects) < 2:
        raise UserError("the goal 'in the relation' needs a relation and two objects")
    a, b = out.objects[0], out.objects[1]
    return not a.held and not b.held and relations.holds(out.relation, a, b)


def slid(dx: float, dy: float) -> GoalTest:
    """The object slid along (dx, dy) (a unit vector; north is (0, 1), away from the trainer) by
    at least half its width from where it stood, no further than its width sideways, and is on
    the table."""

    def test(out: Outcome) -> bool:
        a, start = out.objects[0], out.start[0] if out.start else None
        if start is None:
            raise UserError("cannot grade a slide without where the object started")
        x0, y0 = start
        along = dx * (a.x - x0) + dy * (a.y - y0)
        across = abs(dy * (a.x - x0) - dx * (a.y - y0))
        return not a.held and along >= 0.5 * a.footprint and across <= a.footprint

    return test


def room_ahead(dx: float, dy: float, halves: float = 5.0) -> Room:
    """Room to slide along (dx, dy) (an axis: (0, 1) north, (0, -1) south, ...): the point
    `halves` half-widths ahead of the object's centre keeps the edge margin of the table."""

    def room(x: float, y: float, half: float, table: Table, margin: float) -> bool:
        ax, ay = x + dx * (halves * half), y + dy * (halves * half)
        return ((dy <= 0 or ay + margin < table.depth) and (dy >= 0 or ay - margin > 0.0)
                and (dx <= 0 or ax + margin < table.width) and (dx >= 0 or ax - margin > 0.0))

    return room


# ------------------------------------------------------------------ the world calls


def _point(world: World, obj: str, position: tuple[float, float] | None, onto: str | None) -> None:
    world.point(obj)


def _pick_up(world: World, obj: str, position: tuple[float, float] | None, onto: str | None) -> None:
    world.pick_up(obj)


def _place(world: World, obj: str, position: tuple[float, float] | None, onto: str | None) -> SettleReport:
    if position is None:
        raise UserError(f"place({obj}) has no position")
    if onto is None:
        return world.place(obj, position[0], position[1])
    return world.place(obj, position[0], position[1], onto=onto)


def _push(world: World, obj: str, position: tuple[float, float] | None, onto: str | None) -> SettleReport:
    return world.push_away(obj)


# ------------------------------------------------------------------ the registries

FLUENTS: dict[str, Fluent] = {}
ACTIONS: dict[str, PrimitiveAction] = {}
VERBS: dict[str, Verb] = {}
_DECLARED = [0]  # declarations so far (`version`)


def declare(*items: Fluent | PrimitiveAction | Verb) -> None:
    """Add fluents, primitive actions and verbs (fluents first, then actions, then verbs, so
    one call may declare an action with its new fluent and the verb taught with it). A
    declaration that names what is not declared is a `ValueError`: a mistake in the code. One
    that would replace what is declared (a fluent "held", an action "place", a verb "push"), a
    name clingo or a sentence cannot carry, or a verb word another word already is, is a
    `UserError` naming it; nothing of a refused call is declared."""
    fluents, acts, verbs = dict(FLUENTS), dict(ACTIONS), dict(VERBS)
    folder = _declaring_folder()
    items = tuple(_with_model_in(_guarded(i), folder) for i in items)
    for f in (i for i in items if isinstance(i, Fluent)):
        _new_name("fluent", f.name, f, fluents)
        if f.known not in (HAND, SIGHT, DEED) or f.arity < 1:
            raise ValueError(f"fluent {f.name}: known must be hand, sight or deed, arity >= 1")
        fluents[f.name] = f
    for a in (i for i in items if isinstance(i, PrimitiveAction)):
        _new_name("action", a.name, a, acts)
        if a.kind not in KINDS or a.hand not in (None, GRASP, RELEASE):
            raise ValueError(f"action {a.name}: kind must be one of {KINDS}, hand grasp, release or None")
        unknown = [f for f in (*a.adds, *a.dels) if f not in fluents]
        if unknown:
            raise ValueError(f"action {a.name} changes undeclared fluents: {', '.join(unknown)}")
        _spelled_once(a, acts)
        acts[a.name] = a
    for v in (i for i in items if isinstance(i, Verb)):
        _new_name("verb", v.name, v, verbs)
        unknown = [s for s in v.steps if s not in acts]
        if unknown or not v.steps:
            raise ValueError(f"verb {v.name}: its steps must be declared actions, not {', '.join(unknown) or 'none'}")
        _verb_words(v, verbs)
        verbs[v.name] = v
    _DECLARED[0] += 1
    for registry, staged in zip((FLUENTS, ACTIONS, VERBS), (fluents, acts, verbs)):
        registry.update(staged)  # type: ignore[attr-defined]


_VERB_WORD = re.compile(r"[a-z]+")
_Item = TypeVar("_Item", Fluent, PrimitiveAction, Verb)


def _declaring_folder() -> Path:
    """The folder of the module that called `declare` (the first caller outside aileen and
    `contextlib`, as `declared` is a context manager); the current directory when it has no
    file (an interactive session)."""
    frame = sys._getframe(1)
    while frame is not None:
        module = frame.f_globals.get("__name__", "")
        if not (module == "aileen" or module.startswith("aileen.") or module == "contextlib"):
            break
        frame = frame.f_back
    where = frame.f_globals.get("__file__") if frame is not None else None
    return Path(where).resolve().parent if where else Path.cwd()


def _with_model_in(item: _Item, folder: Path) -> _Item:
    """An action whose `model` is a relative path, with it read from `folder` (the declaring
    module's): `model=Path("nudge.lp")` beside nudge.py was looked for in the current
    directory, so the module worked only when run from its own folder."""
    if isinstance(item, PrimitiveAction) and item.model is not None and not Path(item.model).is_absolute():
        return dataclasses.replace(item, model=folder / item.model)
    return item


def _guarded(item: _Item) -> _Item:
    """`item` with its functions of one's own guarded (`guard.guarded`): an error inside a
    user's world call, goal test or room test is one line naming it, and the run saves what
    it learned, never a traceback (a world call raising AttributeError lost the memory)."""
    from aileen.domain import guard

    if isinstance(item, PrimitiveAction):
        return dataclasses.replace(item, world=guard.guarded(f"action {item.name!r}: its world call", item.world))
    if isinstance(item, Verb):
        return dataclasses.replace(item, goal=guard.guarded(f"verb {item.name!r}: its goal", item.goal),
                                   room=guard.guarded(f"verb {item.name!r}: its room", item.room))
    return item


def _new_name(what: str, name: str, item: object, declared_now: Mapping[str, object]) -> None:
    """A name clingo reads as a constant, and not one declared already (a fluent "held" of
    one's own silently replaced the hand's; declaring the very same thing again is no change)."""
    if not isinstance(name, str) or not DECLARED_NAME.fullmatch(name):
        raise UserError(f"{what} {name!r}: expected a name of lowercase letters a-z, digits and '_', a letter "
                        f"first (its symbol in the action models)")
    if name in declared_now and declared_now[name] != item:
        article = "an" if what[:1] in "aeiou" else "a"  # ("expected a action")
        raise UserError(f"{what} {name!r} is already declared; expected {article} {what} of one's own to take a new "
                        f"name")


def _key(spelling: str) -> str:
    """A demonstration step's spelling as `action` reads it ("pick-up", "pick up" -> "pick_up")."""
    return spelling.strip().lower().replace("-", "_").replace(" ", "_")


def _spelled_once(a: PrimitiveAction, declared_now: Mapping[str, PrimitiveAction]) -> None:
    """No spelling of `a` spells another action (`action` would read the first declared)."""
    for other in declared_now.values():
        if other.name == a.name:
            continue
        theirs = {_key(s) for s in (other.name, *other.spellings)}
        clash = next((s for s in (a.name, *a.spellings) if _key(s) in theirs), None)
        if clash is not None:
            raise UserError(f"action {a.name!r}: spelling {clash!r} already spells the action {other.name!r}")


def _verb_words(v: Verb, declared_now: Mapping[str, Verb]) -> None:
    """Each word of a verb is one lowercase word that says nothing else: not a word of the
    grammar, a relation word, a number, a relation's spelling, a channel's value or spelling,
    or another verb's word (a spelling "the", "left", "red" or "push" made the sentence say
    that instead, and "pull it" or "Pull" was never read)."""
    from aileen.domain import spoken, words

    others = {w: o.name for o in declared_now.values() if o.name != v.name for w in o.words}
    for word in v.words:
        if not isinstance(word, str) or not _VERB_WORD.fullmatch(word):
            raise UserError(f"verb {v.name!r}: {word!r} must be one word of the lowercase letters a-z (a sentence "
                            f"says it)")
        if word in words.FUNCTION_WORDS or word in words.RELATION_WORDS or word in words.NUMBERS:
            raise UserError(f"verb {v.name!r}: {word!r} is a word of the grammar (a function word, a relation "
                            f"word or a number), which the readers read as such")
        taken = f"the verb {others[word]!r}" if word in others else spoken.owner(word, skip="verb")
        if taken is not None:
            raise UserError(f"verb {v.name!r}: {word!r} already says {taken}; expected a word of the verb's own")
    if len(set(v.words)) != len(v.words):
        raise UserError(f"verb {v.name!r}: a word is given twice in {', '.join(v.words)}")


@contextlib.contextmanager
def declared(*items: Fluent | PrimitiveAction | Verb) -> Iterator[None]:
    """Within the block, `items` are declared; after it the registries are as they were (a test
    declares its own action this way, and the published experiments never see it)."""
    saved = dict(FLUENTS), dict(ACTIONS), dict(VERBS)
    declare(*items)
    try:
        yield
    finally:
        for registry, before in zip((FLUENTS, ACTIONS, VERBS), saved):
            registry.clear()
            registry.update(before)  # type: ignore[arg-type]
        _DECLARED[0] += 1


def version() -> int:
    """Changes with every declaration (what is read from the registries may be cached by it)."""
    return _DECLARED[0]


declare(
    Fluent("held", 1, HAND, "O is in the agent's hand (at most one object at a time)"),
    Fluent("pointed", 1, DEED, "the agent has pointed at O"),
    Fluent(calculi.MOVED, 1, SIGHT, "O has just moved (carried or pushed): perception's motion fact"),
    Fluent(REL, 3, SIGHT, "the relation fact P(A,B), e.g. rel(w,o1,o2) for w(o1,o2)"),
    Fluent("pushed", 1, DEED, "the hand has just pushed O"),
    PrimitiveAction("point", ("point",), TOUCH, None, _point, "point N", adds=("pointed",)),
    PrimitiveAction("pick_up", ("pick_up", "pickup", "pick-up", "pick up"), TOUCH, GRASP, _pick_up, "pick_up N",
                    adds=("held",), dels=(REL,)),
    PrimitiveAction("place", ("place", "put"), REGION, RELEASE, _place,
                    "place N <relation> M | place N at X Y | place N on M",
                    adds=(REL, calculi.MOVED), dels=("held", REL)),
    PrimitiveAction("push", ("push",), TOUCH, None, _push, "push N", adds=(calculi.MOVED, "pushed"), dels=(REL,)),
    Verb("move", ("pick_up", "place"), in_relation),
    Verb("push", ("push",), slid(0.0, 1.0), room_ahead(0.0, 1.0)),
)


# ------------------------------------------------------------------ look-ups


def action(name: str) -> PrimitiveAction:
    """The action for a spelling; an unknown one is a `UserError` listing them."""
    key = name.strip().lower().replace("-", "_").replace(" ", "_")
    for a in ACTIONS.values():
        if key == a.name or key in {s.replace("-", "_").replace(" ", "_") for s in a.spellings}:
            return a
    raise UserError(f"unknown action {name!r}; expected one of: {', '.join(ACTIONS)}")


def verb_words() -> dict[str, str]:
    """Every word a sentence may say a declared verb with -> the verb's name."""
    return {w: v.name for v in VERBS.values() for w in v.words}


def find_verb(word: str) -> Verb | None:
    """The verb a word says (its name or a spelling), else None."""
    name = verb_words().get(word.strip().lower())
    return VERBS[name] if name is not None else None


def verb(name: str) -> Verb:
    """The verb a word says; an unknown one is a `UserError` listing them."""
    found = find_verb(name)
    if found is None:
        raise UserError(f"unknown verb {name!r}; expected one of: {', '.join(VERBS)}")
    return found


def changes(relation: str) -> bool:
    """Does some declared action change the relation fact `relation`: one that adds or deletes
    relations (`rel`), and a relation of no static calculus (`calculi.is_static`: which of two
    is larger stays however they are moved)? A sentence asking for one no action changes is
    refused before anything is done ("move the red box larger than the blue cone")."""
    if calculi.is_static(relation):
        return False
    return any(REL in (*a.adds, *a.dels) for a in ACTIONS.values())


def unary_fluents() -> frozenset[str]:
    """The fluents about one object (held, pointed, moved, ...): the planner's own facts."""
    return frozenset(f.name for f in FLUENTS.values() if f.arity == 1)


def marks_of(act: str) -> tuple[str, ...]:
    """The marks a done action leaves (see `PrimitiveAction.marks`); none for an unknown one."""
    try:
        return action(act).marks
    except UserError:
        return ()


def asp_facts() -> list[Term]:
    """What the world refuses of a stack (`world.stacks`, where the simulator's own refusals
    are declared), as facts for the action models: `no_flat_top(C)` for the percept of each
    shape whose top carries nothing, `max_height(N)`. The planner reads them so that it plans
    no placement the world would refuse (it planned "put the blue box on the cylinder" with
    the yellow box on it, and the world said no after the pick-up)."""
    tops = [fn("no_flat_top", catalog.percept(s)) for s in catalog.SHAPES if s not in stacks.FLAT_TOPS]
    return [*tops, fn("max_height", stacks.MAX_HEIGHT)]
