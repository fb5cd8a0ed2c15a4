"""The output-link reader refuses malformed commands (issue 24): every command a Soar agent
writes is checked in full, so a bad one gets `^status error` with a message and never a stored
fact that would break the saved memory file. Also: answers go when their commands go, and the
kernel's buffers stay bounded."""

from __future__ import annotations

import pytest

pytest.importorskip("soar_sml")

from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from aileen.memory.concept import ConceptMemory  # noqa: E402
from aileen.soar import wm  # noqa: E402
from aileen.soar.bridge import ConceptMemoryBridge  # noqa: E402
from aileen.soar.kernel import PRINT_LIMIT, SoarKernel, WMNode  # noqa: E402
from aileen.terms import Term, parse  # noqa: E402

# Each case: the RHS a Soar agent writes (the command is <c>, on the output-link), and what
# the error message says.
MALFORMED = {
    "cycle": ("(<c> ^command store ^concept r_red ^fact <f>) (<f> ^predicate isa ^arg1 <f> ^arg2 r_red)",
              "cycle"),
    "12 deep": ("(<c> ^command store ^concept r_red ^fact <f>) (<f> ^predicate isa ^arg1 <a1> ^arg2 r_red) "
                + " ".join(f"(<a{i}> ^predicate g ^arg1 <a{i + 1}>)" for i in range(1, 12))
                + " (<a12> ^predicate g ^arg1 |o1|)", "nested deeper"),
    "numeric predicate": ("(<c> ^command store ^concept r_red ^fact <f> ^fact <m>) (<f> ^predicate 5 ^arg1 |o1|) "
                          "(<m> ^predicate isa ^arg1 |o1| ^arg2 r_red)", "^predicate 5 is not"),
    "empty predicate": ("(<c> ^command store ^concept r_red ^fact <f> ^fact <m>) (<f> ^predicate || ^arg1 |o1|) "
                        "(<m> ^predicate isa ^arg1 |o1| ^arg2 r_red)", "^predicate || is not"),
    "spaced constant": ("(<c> ^command store ^concept r_red ^fact <f>) (<f> ^predicate isa ^arg1 |o 1| ^arg2 r_red)",
                        "|o 1| is not a lowercase ASP constant"),
    "capital constant": ("(<c> ^command store ^concept r_red ^fact <f>) (<f> ^predicate isa ^arg1 |O1| ^arg2 r_red)",
                         "O1 is not a lowercase ASP constant"),
    "bare fact": ("(<c> ^command store ^concept r_red ^fact foo)", "found the constant foo"),
    "float argument": ("(<c> ^command store ^concept r_red ^fact <f>) (<f> ^predicate isa ^arg1 |o1| ^arg2 1.5)",
                       "float"),
    "two first arguments": ("(<c> ^command store ^concept r_red ^fact <f>) (<f> ^predicate isa ^arg1 |o1| ^arg1 |o2| "
                            "^arg2 r_red)", "^arg1 has 2 values"),
    "gap in arguments": ("(<c> ^command store ^concept r_red ^fact <f>) (<f> ^predicate isa ^arg2 r_red)",
                         "^arg2 without ^arg1"),
    "concept named isa": ("(<c> ^command create ^concept isa ^kind visual)", "reserved name"),
    "concept named for a relation": ("(<c> ^command create ^concept cone_w ^kind spatial)", "reserved name"),
    "concept not a symbol": ("(<c> ^command create ^concept 7 ^kind visual)", "not a lowercase ASP constant"),
    "store without membership": ("(<c> ^command store ^concept r_red ^fact <f>) "
                                 "(<f> ^predicate isa ^arg1 |o1| ^arg2 cv_red)", "membership"),
    "plan without goal": ("(<c> ^command plan ^fact <f>) (<f> ^predicate held ^arg1 |o1|)", "no ^goal"),
}


def _agent(tmp_path, rhs: str) -> SoarKernel:
    rules = tmp_path / "write.soar"
    rules.write_text("sp {write*propose\n   (state <s> ^superstate nil -^done)\n-->\n"
                     "   (<s> ^operator <o> +)\n   (<o> ^name write)}\n"
                     "sp {write*apply\n   (state <s> ^operator.name write ^io.output-link <ol>)\n-->\n"
                     f"   (<ol> ^concept-memory <c>) {rhs}\n   (<s> ^done yes)}}\n")
    k = SoarKernel()
    k.source(rules)
    return k


@pytest.mark.parametrize("case", sorted(MALFORMED))
def test_a_malformed_command_is_refused_and_the_memory_still_saves(tmp_path, case) -> None:
    rhs, why = MALFORMED[case]
    mem = ConceptMemory()
    mem.create("r_red", "visual")
    mem.store([parse("isa(o1,cv_red)"), parse("isa(o1,r_red)")], "r_red")
    before = mem.to_dict()
    with _agent(tmp_path, rhs) as k:
        bridge = ConceptMemoryBridge(k, mem)
        k.run(3)
        served = bridge.serve()
        assert [s.status for s in served] == ["error"], served
        assert why in served[0].message
        (res,) = bridge.answers()
        assert res.get("status") == "error" and why in str(res.get("message"))
        assert [n.get("status") for a, n in k.output() if a == "concept-memory"] == ["error"]
    assert mem.to_dict() == before  # nothing stored, nothing created
    mem.save(tmp_path / "m.json")
    assert ConceptMemory.load(tmp_path / "m.json").to_dict() == before


def test_a_well_formed_store_is_served_and_saves(tmp_path) -> None:
    """The control for the cases above: the same shapes, well formed, are stored."""
    rhs = ("(<c> ^command store ^concept r_red ^fact <f> ^fact <m>) (<f> ^predicate isa ^arg1 |o7| ^arg2 cv_red) "
           "(<m> ^predicate isa ^arg1 |o7| ^arg2 r_red)")
    mem = ConceptMemory()
    mem.create("r_red", "visual")
    with _agent(tmp_path, rhs) as k:
        bridge = ConceptMemoryBridge(k, mem)
        k.run(3)
        assert [s.status for s in bridge.serve()] == ["success"]
    assert mem.examples("r_red") == [["isa(o7,cv_red)", "isa(o7,r_red)"]]
    mem.save(tmp_path / "m.json")
    assert ConceptMemory.load(tmp_path / "m.json").examples("r_red") == mem.examples("r_red")


# ---------------------------------------------------------------------------- any structure

NAMES = st.sampled_from(["isa", "w", "r_red", "o1", "o2", "cv_red", "t0", "o 1", "", "O1", "not", "a-b", "h"])
LEAF = st.one_of(NAMES, st.integers(-5, 99), st.floats(allow_nan=False, allow_infinity=False, width=32))


def _tree(depth: int) -> st.SearchStrategy:
    if depth == 0:
        return LEAF
    node = st.fixed_dictionaries(
        {"predicate": st.one_of(NAMES, st.integers(0, 9))},
        optional={"arg1": _tree(depth - 1), "arg2": _tree(depth - 1), "arg3": _tree(depth - 1)},
    )
    return st.one_of(LEAF, node)


def _put(k: SoarKernel, parent, attr: str, value) -> None:  # noqa: ANN001
    if isinstance(value, dict):
        ident = k.add(parent, attr)
        for a, v in value.items():
            _put(k, ident, a, v)
    else:
        k.add(parent, attr, value)


RELAY = """
sp {relay*propose
   (state <s> ^superstate nil ^io.input-link.issue <c>)
  -(<s> ^sent <c>)
-->
   (<s> ^operator <o> + =)
   (<o> ^name relay ^cmd <c>)}
sp {relay*apply
   (state <s> ^operator <o> ^io.output-link <ol>)
   (<o> ^name relay ^cmd <c>)
-->
   (<ol> ^concept-memory <c>)
   (<s> ^sent <c>)}
"""


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(fact=_tree(3))
def test_any_structure_is_stored_whole_or_refused(tmp_path_factory, fact) -> None:
    """Whatever a `^fact` holds, the bridge stores a fact that the memory file reads back as
    the same fact, or answers `^status error`; nothing raises."""
    folder = tmp_path_factory.mktemp("any")
    (folder / "relay.soar").write_text(RELAY)
    mem = ConceptMemory()
    mem.create("r_red", "visual")
    with SoarKernel() as relay:
        relay.source(folder / "relay.soar")
        bridge = ConceptMemoryBridge(relay, mem)
        c = relay.add(relay.input_link, "issue")
        relay.add(c, "command", "store")
        relay.add(c, "concept", "r_red")
        _put(relay, c, "fact", fact)
        m = relay.add(c, "fact")
        for a, v in (("predicate", "isa"), ("arg1", "o9"), ("arg2", "r_red")):
            relay.add(m, a, v)
        relay.commit()
        relay.run(2)
        served = bridge.serve()
    assert len(served) == 1 and served[0].status in ("success", "error")
    if served[0].status == "success":
        assert _valid(fact)
        mem.save(folder / "m.json")
        assert ConceptMemory.load(folder / "m.json").to_dict() == mem.to_dict()
    else:
        assert not _valid(fact) and not mem.examples("r_red") and served[0].message


def _valid(v) -> bool:  # noqa: ANN001
    """Is this structure a fact the memory file reads back (the bridge's rule, restated)?"""
    if not isinstance(v, dict):
        return False
    args = [v[a] for a in ("arg1", "arg2", "arg3") if a in v]
    keys = [a for a in ("arg1", "arg2", "arg3") if a in v]
    if keys != ["arg1", "arg2", "arg3"][: len(keys)]:
        return False
    p = v["predicate"]
    if not (isinstance(p, str) and wm.is_constant(p)):
        return False
    return all(_valid(a) if isinstance(a, dict) else
               (isinstance(a, int) or (isinstance(a, str) and wm.is_constant(a))) for a in args)


@given(t=st.recursive(st.sampled_from(["o1", "r_red", "cv_box", "t0", "start"]).map(Term)
                      | st.integers(0, 50).map(Term),
                      lambda inner: st.tuples(st.sampled_from(["isa", "h", "w", "r_left_of"]),
                                              st.lists(inner, min_size=1, max_size=3))
                      .map(lambda x: Term(x[0], tuple(x[1]))), max_leaves=8))
@settings(max_examples=80, deadline=None)
def test_a_term_goes_onto_working_memory_and_back(t: Term) -> None:
    """`wm.put` and `wm.term` are inverses on the facts the memory holds."""
    if not t.args:
        t = Term("isa", (t,))
    with SoarKernel() as k:
        node = k.tree(wm.put(k, k.input_link, "fact", t))
        assert wm.fact(node) == t


# ---------------------------------------------------------------------------- bounded

CLEANUP = RELAY + """
sp {relay*propose*drop
   (state <s> ^superstate nil ^io.output-link <ol> ^io.input-link.drop yes)
   (<ol> ^concept-memory <c>)
   (<c> ^status complete)
-->
   (<s> ^operator <o> + =)
   (<o> ^name drop ^cmd <c>)}
sp {relay*apply*drop
   (state <s> ^operator <o> ^io.output-link <ol>)
   (<o> ^name drop ^cmd <c>)
-->
   (<ol> ^concept-memory <c> -)}
"""


def test_an_answer_goes_when_its_command_goes(tmp_path) -> None:
    rules = tmp_path / "cleanup.soar"
    rules.write_text(CLEANUP)
    mem = ConceptMemory()
    with SoarKernel() as k:
        k.source(rules)
        bridge = ConceptMemoryBridge(k, mem)
        for n in range(3):
            c = k.add(k.input_link, "issue")
            k.add(c, "command", "create")
            k.add(c, "concept", f"r_w{n}")
            k.add(c, "kind", "visual")
        k.commit()
        k.run(5)
        assert len(bridge.answers()) == 3 and len(bridge.serve()) == 3
        k.add(k.input_link, "drop", "yes")  # the agent cleans up its completed commands
        k.commit()
        k.run(10)
        assert not [n for a, n in k.output() if a == "concept-memory"]
        assert bridge.answers() == []  # and their answers went with them
        assert all(mem.has(f"r_w{n}") for n in range(3))


def test_the_print_trace_is_bounded(tmp_path) -> None:
    rules = tmp_path / "chatty.soar"
    rules.write_text("sp {chatty*init (state <s> ^superstate nil -^count) --> (<s> ^operator <o> +) (<o> ^name init)}\n"
                     "sp {chatty*start (state <s> ^operator.name init) --> (<s> ^count 0)}\n"
                     "sp {chatty (state <s> ^superstate nil ^count <n>) -->\n"
                     "   (<s> ^operator <o> +) (<o> ^name say ^n <n>)}\n"
                     "sp {chatty*apply (state <s> ^operator <o>) (<o> ^name say ^n <n>) -->\n"
                     "   (<s> ^count <n> - ^count (+ <n> 1)) (write |hello| (crlf))}\n")
    with SoarKernel() as k:
        k.source(rules)
        k.run(PRINT_LIMIT + 500)
        out = k.printed()
        assert len(out) == PRINT_LIMIT  # the latest messages: the first 500 decisions' are gone
        assert any(f"{PRINT_LIMIT + 500}:" in m for m in out) and not any(" 1:    O:" in m for m in out)
        assert k.printed() == []


def test_a_read_node_keeps_its_error_rather_than_a_truncated_tree(tmp_path) -> None:
    with _agent(tmp_path, MALFORMED["12 deep"][0]) as k:
        k.run(3)
        ((_attr, node),) = k.output()
        assert isinstance(node, WMNode) and node.error and "nested deeper" in node.error
        assert node.get("command") == "store" and node.get("fact") is None  # no fact cut short
