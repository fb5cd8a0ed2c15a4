"""Planning (asp/actions.lp + asp/planning.lp through planner.py): shortest plans, no plan.

Besides the table, a small breadth-first reference model of the same action semantics,
written in Python, checks on random goals that every plan is valid and as short as BFS.
"""

from __future__ import annotations

from collections import deque

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from aileen.domain import actions, calculi
from aileen.errors import UserError
from aileen.reasoning import asp
from aileen.reasoning.planner import NoPlan, Plan, plan, planning_facts
from aileen.terms import Term, parse, parse_many

CONVERSE = {"n": "s", "ne": "sw", "e": "w", "se": "nw", "cdc_eq": "cdc_eq", "dc": "dc", "ec": "ec", "po": "po",
            "eq": "eq", "tpp": "tppi", "ntpp": "ntppi"}
CONVERSE.update({v: k for k, v in CONVERSE.items()})


def pairwise(cdc: dict[tuple[str, str], str]) -> str:
    """Both directions of each cardinal relation plus dc: what perception would give."""
    out = []
    for (a, b), d in cdc.items():
        out += [f"{d}({a},{b}).", f"{CONVERSE[d]}({b},{a}).", f"dc({a},{b}).", f"dc({b},{a})."]
    return " ".join(out)


# o1 east of o2, o3 north of both, o4 south of all three
SCENE = pairwise({("o1", "o2"): "e", ("o3", "o1"): "n", ("o3", "o2"): "n",
                  ("o4", "o1"): "s", ("o4", "o2"): "s", ("o4", "o3"): "s"})


def acts(p: Plan) -> list[str]:
    return [str(a) for a in p.actions]


TABLE = [
    # goal, expected actions (None: only the depth is fixed), depth
    ("w(o1,o2). dc(o1,o2).", ["pick_up(o1)", "place(o1,goal)"], 2),
    ("held(o1).", ["pick_up(o1)"], 1),
    ("e(o1,o2). dc(o1,o2).", [], 0),
    ("pointed(o2).", ["point(o2)"], 1),
    ("e(o2,o1).", ["pick_up(o2)", "place(o2,goal)"], 2),
    ("w(o1,o2). pointed(o3).", None, 3),
    ("w(o1,o2). s(o3,o2).", ["pick_up(o2)", "place(o2,goal)"], 2),  # one move serves both
    ("w(o1,o2). n(o4,o3).", None, 4),
    ("w(o1,o2). n(o4,o3). pointed(o3).", None, 5),
    ("near(o1,o2).", ["pick_up(o1)", "place(o1,goal)"], 2),
]


@pytest.mark.parametrize("goal,expected,depth", TABLE)
def test_shortest_plans(goal, expected, depth):
    p = plan(parse_many(SCENE), parse_many(goal))
    assert p.depth == depth == len(p.steps)
    if expected is not None:
        assert acts(p) == expected
    assert simulate(parse_many(SCENE), parse_many(goal), p)


def test_place_steps_carry_the_region_relations():
    p = plan(parse_many(SCENE), parse_many("w(o1,o2). dc(o1,o2)."))
    place = p.steps[1]
    assert place.name == "place" and place.obj == Term("o1")
    assert [str(r) for r in place.relations] == ["w(o1,o2)", "dc(o1,o2)"]
    assert p.steps[0].relations == []


@pytest.mark.parametrize(
    "goal,relations",
    [
        ("dc(o1,o2). w(o1,o2).", ["dc(o1,o2)", "w(o1,o2)"]),
        ("e(o2,o1). dc(o1,o2). n(o3,o1).", ["w(o1,o2)", "dc(o1,o2)", "s(o1,o3)"]),
        ("near(o2,o1). w(o1,o2).", ["near(o2,o1)", "w(o1,o2)"]),
    ],
)
def test_region_relations_follow_the_goal_order(goal, relations):
    state = [f for f in parse_many(SCENE) if Term("o1") not in f.args] + parse_many("held(o1).")
    p = plan(state, parse_many(goal))
    assert [str(s.action) for s in p.steps] == ["place(o1,goal)"]
    assert [str(r) for r in p.steps[0].relations] == relations


def test_region_relations_are_seen_from_the_placed_object():
    # o1 held; the goal is written from o2's side: e(o2,o1) means o1 must go west of o2
    p = plan(parse_many("held(o1). isa(o2,cv_red)."), parse_many("e(o2,o1)."))
    assert acts(p) == ["place(o1,goal)"]
    assert [str(r) for r in p.steps[0].relations] == ["w(o1,o2)"]


def test_something_held_must_be_put_down_first():
    p = plan(parse_many(SCENE.replace("o4", "o9") + " held(o4). isa(o4,cv_box)."), parse_many("held(o1)."))
    assert acts(p) == ["place(o4,free)", "pick_up(o1)"]
    assert p.steps[0].relations == []


@pytest.mark.parametrize(
    "goal,depth",
    [
        ("held(o1). w(o1,o2).", 6),  # a held object is off the table
        ("w(o1,o2). n(o4,o3).", 3),  # needs 4
        ("held(o1).", 0),
    ],
)
def test_no_plan(goal, depth):
    with pytest.raises(NoPlan) as err:
        plan(parse_many(SCENE), parse_many(goal), max_depth=depth)
    assert str(err.value).startswith(f"no plan within depth {depth}")
    assert err.value.max_depth == depth and err.value.never is None


@pytest.mark.parametrize(
    "goal,why",
    [
        ("w(o1,o2). e(o1,o2).", "w(o1,o2) and e(o1,o2) cannot both hold"),  # contradictory directions
        ("w(o1,o2). w(o2,o1).", "w(o1,o2) and w(o2,o1) cannot both hold"),  # through the converse
        ("dc(o1,o2). ec(o2,o1).", "dc(o1,o2) and ec(o2,o1) cannot both hold"),  # contradictory RCC8
        ("held(o1). held(o2).", "the hand holds one object at most"),
        ("sz_larger(o1,o2).", "no action changes it"),  # static, and not so now
    ],
)
def test_a_goal_that_can_never_hold_says_so(goal, why):
    """It said "no plan within depth 6", as if a deeper search might find one."""
    with pytest.raises(NoPlan) as err:
        plan(parse_many(SCENE), parse_many(goal), max_depth=6)
    assert "can never hold" in str(err.value) and why in str(err.value) and err.value.never is not None


def test_a_static_goal_that_holds_already_is_no_step():
    assert plan(parse_many(SCENE + " sz_larger(o1,o2)."), parse_many("sz_larger(o1,o2). dc(o1,o2). dc(o2,o1).")).depth == 0


def test_a_state_with_two_objects_in_the_hand_is_refused():
    with pytest.raises(UserError, match="in the hand at once"):
        plan(parse_many("held(o1). held(o2). obj(o3)."), parse_many("held(o3)."))


def test_the_whole_search_is_held_to_the_solving_limit(monkeypatch):
    """Each clingo call was held to --rules-timeout, the search was not: --max-depth 1000000
    on a goal no plan reaches ran for minutes under --rules-timeout 5. The clock is moved on
    by hand (no timed assert)."""
    from aileen.reasoning import planner

    ticks = iter(range(0, 10_000, 2))
    monkeypatch.setattr(planner, "_clock", lambda: float(next(ticks)))
    asp.set_solve_limit(5.0, "my-rules")
    try:
        with pytest.raises(asp.RulesTimeout, match="my-rules: planning took longer than 5 s: no plan of up to 2 steps"):
            plan(parse_many(STACKED), parse_many("st_on(o1,o2)."), max_depth=1_000_000)
    finally:
        asp.set_solve_limit(None)


def test_goal_naming_an_unseen_object_is_a_user_error():
    with pytest.raises(UserError, match="o9"):
        plan(parse_many(SCENE), parse_many("w(o1,o9)."))


def test_negative_depth_is_a_user_error():
    with pytest.raises(UserError):
        plan(parse_many(SCENE), parse_many("held(o1)."), max_depth=-1)


def test_ten_objects_two_steps():
    names = [f"o{i}" for i in range(10)]
    scene = []
    for i, a in enumerate(names):
        scene.append(f"isa({a},cv_box).")
        for j, b in enumerate(names):
            if i != j:
                scene.append(f"{'e' if i > j else 'w'}({a},{b}). dc({a},{b}).")
    p = plan(parse_many(" ".join(scene)), parse_many("w(o5,o2). dc(o5,o2)."))
    assert acts(p) == ["pick_up(o5)", "place(o5,goal)"]


def test_planning_facts_reify_relations():
    facts = {str(f) for f in planning_facts(parse_many("w(o1,o2). held(o3). isa(o4,cv_red)."), parse_many("e(o1,o2)."))}
    domain = {str(f) for f in [*calculi.asp_facts(), *actions.asp_facts()]}
    assert {"calculus(cdc,w)", "converse(w,e)", "converse(e,w)", "static(sz_larger)", "converse(sz_smaller,sz_larger)"} <= domain
    assert facts - domain == {"init(rel(w,o1,o2))", "init(held(o3))", "isa(o4,cv_red)", "goal(rel(e,o1,o2))",
                     "obj(o1)", "obj(o2)", "obj(o3)", "obj(o4)"}


# the blue box o1 free; the yellow box o4 rests on the green cylinder o3; o2 a blue sphere
STACKED = ("isa(o1,cv_box). isa(o2,cv_sphere). isa(o3,cv_cylinder). isa(o4,cv_box). "
           + pairwise({("o1", "o3"): "w", ("o1", "o4"): "w", ("o1", "o2"): "e", ("o2", "o3"): "w"})
           + " st_on(o4,o3). st_under(o3,o4). po(o4,o3). po(o3,o4).")


def test_a_place_onto_a_loaded_object_takes_what_rests_on_it_off_first():
    """"move the blue box on the green cylinder" with the yellow box on it: the plan was
    pick_up, place, which the world refuses after the pick-up; a person takes the yellow box
    off first."""
    p = plan(parse_many(STACKED), parse_many("st_on(o1,o3). po(o1,o3)."))
    assert acts(p) == ["pick_up(o4)", "place(o4,free)", "pick_up(o1)", "place(o1,goal)"]


@pytest.mark.parametrize("goal", ["st_on(o1,o2).", "st_under(o2,o1).", "st_on(o1,o4)."])
def test_no_place_the_world_refuses_is_planned(goal):
    """Onto a sphere (no flat top), onto an object up on a stack (at most two high), and never
    by putting the lower object under the upper one: the world refuses each."""
    with pytest.raises(NoPlan):
        plan(parse_many(STACKED), parse_many(goal), max_depth=3)


def test_no_place_puts_three_objects_in_directions_that_cannot_all_hold():
    """o1 east of o2 and of o3, o2 east of o3; goal o1 west of o2, o2 west of o3: o2 was put
    east of o1 and west of o3 while o1 stayed east of o3, which no point of the table has."""
    chain = ("isa(o1,cv_box). isa(o2,cv_box). isa(o3,cv_box). "
             + pairwise({("o1", "o2"): "e", ("o1", "o3"): "e", ("o2", "o3"): "e"}))
    goal = parse_many("w(o1,o2). w(o2,o3).")
    p = plan(parse_many(chain), goal)
    assert simulate(parse_many(chain), goal, p)
    assert p.depth == bfs_depth(parse_many(chain), goal, [Term("o1"), Term("o2"), Term("o3")])


def test_an_object_up_on_a_stack_is_taken_down_before_another_goes_on_it():
    p = plan(parse_many(STACKED), parse_many("st_on(o1,o4)."))
    assert acts(p) == ["pick_up(o4)", "place(o4,free)", "pick_up(o1)", "place(o1,goal)"]


# ---- the encodings with raw facts, one horizon at a time ------------------------------

RAW = [
    # facts, horizon of the first model, occurs atoms in it
    ("obj(a). obj(b). init(held(a)). goal(held(b)).", 2, {"occurs(place(a,free),1)", "occurs(pick_up(b),2)"}),
    ("obj(a). goal(pointed(a)).", 1, {"occurs(point(a),1)"}),
    ("obj(a). obj(b). init(rel(e,a,b)). init(rel(w,b,a)). goal(rel(w,a,b)).", 2,
     {"occurs(pick_up(a),1)", "occurs(place(a,goal),2)"}),
    ("obj(a). init(held(a)). goal(pointed(a)).", 2, {"occurs(place(a,free),1)", "occurs(point(a),2)"}),
    ("obj(a). obj(b). init(rel(e,a,b)). goal(rel(e,a,b)).", 0, set()),
]


@pytest.mark.parametrize("facts,horizon,occurs", RAW)
def test_planning_lp_on_raw_facts(facts, horizon, occurs):
    search = asp.Incremental(asp.rule_paths(["actions.lp", "planning.lp"]), parse_many(facts))
    for t in range(horizon):
        assert search.horizon(t) is None
    model = search.horizon(horizon)
    assert {str(a) for a in model if a.name == "occurs"} == occurs


def test_horizons_must_come_in_order():
    search = asp.Incremental(asp.rule_paths(["actions.lp", "planning.lp"]), parse_many("obj(a)."))
    with pytest.raises(ValueError):
        search.horizon(2)


# ---- reference model: BFS over the same semantics ---------------------------------------

def _regions(goal: list[Term], o: Term) -> list[frozenset]:
    rels = set()
    for g in goal:
        if len(g.args) == 2 and g.name not in ("held", "pointed"):
            a, b = g.args
            if a == o and b != o:
                rels.add((g.name, a, b))
            elif b == o and a != o:
                rels.add((CONVERSE.get(g.name, g.name), o, a) if g.name in CONVERSE else (g.name, a, b))
    out = [frozenset()]
    if rels:
        cdc = {"n", "ne", "e", "se", "s", "sw", "w", "nw", "cdc_eq"}
        rcc = {"dc", "ec", "po", "eq", "tpp", "ntpp", "tppi", "ntppi"}
        bad = any(p != q and x == y and ((p in cdc and q in cdc) or (p in rcc and q in rcc))
                  for p, _, x in rels for q, _, y in rels if _ == o)
        if not bad:
            out.append(frozenset(rels))
    return out


_CARDINAL = {"n", "ne", "e", "se", "s", "sw", "w", "nw"}


def _composes_badly(rels, reg, o) -> bool:
    """The region puts x p of o and o p of y (p a direction: it composes), so x p of y, where
    another cardinal relation holds of x and y."""
    return any(CONVERSE[q] == p and p in _CARDINAL and x != y
               and any(r[0] in _CARDINAL | {"cdc_eq"} and r[0] != p and r[1:] == (x, y) for r in rels)
               for q, o1, x in reg if q in CONVERSE and o1 == o for p, o2, y in reg if o2 == o)


def _successors(state, objs, goal):
    rels, held, pointed = state
    for o in objs:
        if held != o:
            yield ("point", o), (rels, held, pointed | {o})
        if held is None:
            yield ("pick_up", o), (frozenset(r for r in rels if o not in r[1:]), o, pointed)
            yield ("push", o), (frozenset(r for r in rels if o not in r[1:]), None, pointed)
    if held is not None:
        for reg in _regions(goal, held):
            if _composes_badly(rels, reg, held):
                continue
            new = {r for r in rels if held not in r[1:]} | set(reg)
            new |= {(CONVERSE[p], b, a) for p, a, b in reg if p in CONVERSE}
            yield ("place", held), (frozenset(new), None, pointed)


def _satisfied(state, goal) -> bool:
    rels, held, pointed = state
    for g in goal:
        if g.name == "held" and held != g.args[0]:
            return False
        if g.name == "pointed" and g.args[0] not in pointed:
            return False
        if len(g.args) == 2 and (g.name, *g.args) not in rels:
            return False
    return True


def _initial(state_facts):
    rels = frozenset((f.name, *f.args) for f in state_facts if len(f.args) == 2 and f.name != "isa")
    held = next((f.args[0] for f in state_facts if f.name == "held"), None)
    return (rels, held, frozenset())


def bfs_depth(state_facts, goal, objs, max_depth=6):
    start = _initial(state_facts)
    seen = {start}
    queue = deque([(start, 0)])
    while queue:
        s, d = queue.popleft()
        if _satisfied(s, goal):
            return d
        if d == max_depth:
            continue
        for _, n in _successors(s, objs, goal):
            if n not in seen:
                seen.add(n)
                queue.append((n, d + 1))
    return None


def simulate(state_facts, goal, p: Plan) -> bool:
    """Replay `p` in the reference model; place steps use their reported relations."""
    rels, held, pointed = _initial(state_facts)
    for step in p.steps:
        kind, o = step.name, step.obj
        if kind == "point":
            assert held != o
            pointed = pointed | {o}
        elif kind == "pick_up":
            assert held is None
            rels, held = frozenset(r for r in rels if o not in r[1:]), o
        elif kind == "push":
            assert held is None
            rels = frozenset(r for r in rels if o not in r[1:])
        elif kind == "place":
            assert held == o
            reg = {(r.name, *r.args) for r in step.relations}
            assert not _composes_badly(rels, reg, o)
            new = {r for r in rels if o not in r[1:]} | reg | {(CONVERSE[q], b, a) for q, a, b in reg if q in CONVERSE}
            rels, held = frozenset(new), None
    return _satisfied((rels, held, pointed), goal)


_OBJS = ["o1", "o2", "o3"]
_goal_fact = st.one_of(
    st.builds(lambda p, a, b: f"{p}({a},{b})", st.sampled_from(["n", "s", "e", "w", "dc", "ec"]),
              st.sampled_from(_OBJS), st.sampled_from(_OBJS)).filter(lambda s: s[-4:-2] != s[-7:-5]),
    st.builds(lambda a: f"held({a})", st.sampled_from(_OBJS)),
    st.builds(lambda a: f"pointed({a})", st.sampled_from(_OBJS)),
)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(_goal_fact, min_size=1, max_size=3, unique=True), st.sampled_from([None, "o1", "o3"]))
def test_plans_match_breadth_first_search(goal_texts, held):
    state = parse_many(SCENE + (f" held({held})." if held else ""))
    if held:
        state = [f for f in state if not (len(f.args) == 2 and Term(held) in f.args)]
    goal = [parse(g) for g in goal_texts]
    objs = [Term(o) for o in [*_OBJS, "o4"]]
    expected = bfs_depth(state, goal, objs, max_depth=5)
    try:
        p = plan(state, goal, max_depth=5)
    except NoPlan:
        assert expected is None
        return
    assert p.depth == expected
    assert simulate(state, goal, p)


SLIDE = """
#program base.
action(slide(O,R)) :- region(O,R), R != free.
moves(slide(O,R),O) :- action(slide(O,R)).
#program step(t).
poss(slide(O,R),t) :- action(slide(O,R)), not busy(t-1).
del(rel(P,O,X),t) :- occurs(slide(O,_),t), holds(rel(P,O,X),t-1).
del(rel(P,X,O),t) :- occurs(slide(O,_),t), holds(rel(P,X,O),t-1).
add(F,t) :- occurs(slide(O,R),t), region_fact(O,R,F).
add(rel(Q,X,O),t) :- occurs(slide(O,R),t), region_fact(O,R,rel(P,O,X)), converse(P,Q).
"""


def test_new_primitive_action_by_editing_only_lp_files(tmp_path):
    """The worked example of docs/asp.md: a `slide` action, added in a user's actions.lp."""
    (tmp_path / "actions.lp").write_text(asp.rule_path("actions.lp").read_text() + SLIDE)
    p = plan(parse_many(SCENE), parse_many("w(o1,o2). dc(o1,o2)."), rules=tmp_path)
    assert acts(p) == ["slide(o1,goal)"]
    assert [str(r) for r in p.steps[0].relations] == ["w(o1,o2)", "dc(o1,o2)"]
    # the shipped rules are untouched
    assert acts(plan(parse_many(SCENE), parse_many("w(o1,o2). dc(o1,o2)."))) == ["pick_up(o1)", "place(o1,goal)"]
