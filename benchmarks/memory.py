"""How the concept memory scales: concepts, examples per concept, objects in a scene, the file.

Run: python benchmarks/memory.py [--quick] [--repeat N] [--largest N] [--only PART]

1. Concepts (10, 100, 1000, 10,000, 100,000 synthetic visual concepts): `query` of one named
   concept on a 4-object scene, "which concepts fit this object" (`ConceptMemory.fitting`,
   MAC/FAC; the exhaustive search beside it up to 1000), and `store`. A concept means two
   percepts of a vocabulary that grows with the number of concepts (every concept a different
   pair, as words of a large lexicon would be); each was stored twice, with a third random
   percept each time. Targets: fitting <= 5 ms at 1000 and <= 30 ms at 10,000 (issue 15),
   <= 30 ms at 100,000 (issue 25).
2. The lesson cycle after a store, with the agent's own memory (a spatial trial taught,
   ground-truth vision) plus synthetic visual concepts up to 10 ... 100,000 visual concepts:
   an inform lesson with a new word (so it stores), then a verify lesson, whose
   concept-memory part includes the lexicon (mutual exclusivity over every visual concept,
   kept up to date). Targets: <= 20 ms at 1000 (issue 15), at 10,000 and at 100,000 (issue
   25), the verify lesson after the store. The first cycle after the synthetic concepts were
   added, where the lexicon reads every concept, is printed apart.
3. Examples per concept (1, 10, 100, 1000), similar (they merge into one generalization)
   and dissimilar (assimilation 0.9: they stay kept examples): `query` with the MAC
   pre-filter, the exhaustive query, `store` (SAGE's exact content filter) and the exhaustive
   store. Target (issue 25): store <= 5 ms at 1000 dissimilar examples.
4. Scene size (4, 10, 20, 40 objects): every visual concept asked of every object and every
   spatial concept of every ordered pair, with the taught memory. Target: <= 0.5 s at 40.
   "Again": asked a second time, worked out (the memory's kept answers dropped); "answers
   kept": the same questions looked up (`query` keeps its answers until a store).
5. The memory file (1000, 10,000, 100,000 concepts: part 1's memories), JSON and compact:
   file size, save, and in a fresh process the load, the RSS the loaded memory adds at rest,
   the first `fitting` (it indexes every concept, so the compact form reads them all) and the
   next ones, and the RSS once every concept is read. Targets (issue 25): load <= 2 s and
   well under 1 KB of RSS per concept at rest at 100,000.

Every query and fitting is timed as worked out, not looked up among the answers `query`
keeps until the concept's next store (`unkept`). Figures are medians over --repeat runs;
growth exponents are least-squares slopes of log(time) over log(size). The machine's other
load shows in them: run it on an idle machine.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from collections.abc import Callable, Sequence
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from aileen.analogy.sage import SageParams  # noqa: E402
from aileen.memory.concept import ConceptMemory  # noqa: E402
from aileen.perception.factindex import FactIndex  # noqa: E402
from aileen.terms import Term, fn  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_args  # noqa: E402
from memory_fixtures import add_synthetic, new_word, obj_facts, scene_facts, taught_agent, vocabulary  # noqa: E402


def timed(f: Callable[[], object], repeat: int, *, warm: bool = True) -> float:
    """Median seconds of `repeat` calls, after one call not timed (`warm`): the first query
    after a memory was built fills its content index and caches (122 ms against 0.3-0.45 ms
    after, at 1,000 concepts), and with `--repeat 1` or 2 it was printed as the steady state.
    `warm=False` for a figure that is the first time on purpose."""
    if warm:
        f()
    ts = []
    for _ in range(repeat):
        t = time.perf_counter()
        f()
        ts.append(time.perf_counter() - t)
    return statistics.median(ts)


def unkept(m: ConceptMemory, f: Callable[[], object]) -> Callable[[], object]:
    """`f` with the memory's kept answers dropped first: a question asked again is timed as
    worked out, not looked up (`ConceptMemory.forget_answers`)."""
    def run() -> object:
        m.forget_answers()
        return f()
    return run


def slope(xs: Sequence[float], ys: Sequence[float]) -> float:
    """The growth exponent: least-squares slope of log y over log x."""
    lx, ly = np.log(np.asarray(xs, float)), np.log(np.maximum(np.asarray(ys, float), 1e-9))
    return float(np.polyfit(lx, ly, 1)[0])


# --------------------------------------------------------------------------- 1. concepts

def bench_concepts(sizes: Sequence[int], repeat: int,
                   keep: Sequence[int] = ()) -> dict[int, tuple[ConceptMemory, list[str]]]:
    """Part 1; returns the memories of the sizes in `keep`, each with a probe object's
    percepts, for the file part."""
    print("\n1. concepts: query one | fitting (MAC/FAC) | fitting exhaustive | store  (ms, median)")
    print("concepts | query | fit object | fit exhaustive | same answers | store")
    q_t, f_t, s_t = [], [], []
    kept: dict[int, tuple[ConceptMemory, list[str]]] = {}
    for n in sizes:
        m = ConceptMemory()
        made = add_synthetic(m, n, seed=n)
        v = vocabulary(n)
        rng = np.random.default_rng(1)
        probes = []
        for _ in range(repeat):
            c, meaning = made[int(rng.integers(n))]
            probes.append((c, obj_facts("o9", [*meaning, f"cv_s{int(rng.integers(v))}"])))
        scene = [Term("isa", (Term(f"o{k + 1}"), f.args[1])) for k in range(4) for f in probes[k % len(probes)][1]]
        it = iter(range(10 ** 9))
        q = timed(unkept(m, lambda: m.query(scene, f"isa(X,{probes[next(it) % len(probes)][0]})")), repeat)
        it2 = iter(range(10 ** 9))
        f = timed(unkept(m, lambda: m.fitting(probes[next(it2) % len(probes)][1], kind="visual")), repeat)
        same = "-"
        fe = float("nan")
        if n <= 1000:
            k = min(repeat, 5)
            fe = timed(unkept(m, lambda: m.fitting(probes[0][1], kind="visual", exhaustive=True)), k)
            agree = sum(
                [(x.fact, x.similarity) for x in m.fitting(p, kind="visual")]
                == [(x.fact, x.similarity) for x in m.fitting(p, kind="visual", exhaustive=True)]
                for _c, p in probes[:k])
            same = f"{agree}/{k}"
        it3 = iter(range(10 ** 9))

        def store() -> None:
            c, meaning = made[next(it3) % n]
            m.store(obj_facts("o1", [*meaning, f"cv_s{int(rng.integers(v))}", c]), c)

        s = timed(store, repeat)
        if n in keep:
            kept[n] = (m, [str(f.args[1]) for f in probes[0][1]])
        q_t.append(q)
        f_t.append(f)
        s_t.append(s)
        print(f"{n} | {q * 1e3:.2f} | {f * 1e3:.2f} | {fe * 1e3:.1f} | {same} | {s * 1e3:.2f}")
    print(f"growth exponents in concepts: query {slope(sizes, q_t):.2f}, fitting {slope(sizes, f_t):.2f}, "
          f"store {slope(sizes, s_t):.2f}")
    return kept


# --------------------------------------------------------------------------- 5. the memory file

def rss_bytes() -> int:
    """This process's resident memory now (Linux), else its peak."""
    try:
        with open("/proc/self/status") as fh:
            for line in fh:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    import resource

    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024


def measure_load(path: str, probe: list[str], repeat: int) -> dict[str, float]:
    """In this (fresh) process: load `path`, the RSS it added once loaded (at rest), the first
    `fitting` (which reads every concept into the retrieval index) and the next ones."""
    import gc

    gc.collect()
    before = rss_bytes()
    t = time.perf_counter()
    m = ConceptMemory.load(path)
    load = time.perf_counter() - t
    gc.collect()
    rest = rss_bytes() - before
    facts = obj_facts("o9", probe)
    t = time.perf_counter()
    m.fitting(facts, kind="visual")
    first = time.perf_counter() - t
    again = timed(lambda: m.fitting(facts, kind="visual"), repeat, warm=False)  # `first` warmed it
    gc.collect()
    return {"concepts": len(m), "load": load, "rest": rest, "first": first, "again": again,
            "read": rss_bytes() - before}


def bench_files(memories: dict[int, tuple[ConceptMemory, list[str]]], repeat: int,
                say: Callable[[str], object] = print) -> None:
    """Part 5, measured on part 1's memories while they are there, its lines given to `say`
    (`main` prints them after part 4: the parts in their order)."""
    import json
    import subprocess
    import sys
    import tempfile

    say("\n5. the memory file: save, load in a fresh process, RSS of the loaded memory at rest and once every "
          "concept is read, the first fitting after loading (it reads every concept) and the next ones")
    say("concepts | form | file MB | save s | load s | RSS at rest MB | at rest per concept | first fitting s | "
          "fitting again ms | RSS every concept read MB")
    for n, (m, probe) in sorted(memories.items()):
        with tempfile.TemporaryDirectory() as folder:
            for form, name in (("json", "m.json"), ("compact", "m.amem")):
                path = os.path.join(folder, name)
                t = time.perf_counter()
                m.save(path)
                save = time.perf_counter() - t
                out = subprocess.run([sys.executable, __file__, "--measure-load", path, ",".join(probe),
                                      "--repeat", str(repeat)], capture_output=True, text=True, check=True)
                r = json.loads(out.stdout.strip().splitlines()[-1])
                say(f"{n} | {form} | {os.path.getsize(path) / 1e6:.1f} | {save:.2f} | {r['load']:.2f} | "
                      f"{r['rest'] / 1e6:.1f} | {r['rest'] / n:.0f} B | {r['first']:.2f} | {r['again'] * 1e3:.2f} | "
                      f"{r['read'] / 1e6:.0f}")


# --------------------------------------------------------------------------- 2. lesson cycle

def bench_cycle(sizes: Sequence[int], repeat: int) -> None:
    from aileen.curriculum.lesson import Lesson, ObjectSpec

    print("\n2. lesson cycle after a store (ms, median): inform with a new word (stores), then verify; "
          "the first cycle after the concepts were added, where the lexicon reads every concept, apart")
    print("visual concepts at the first cycle (each inform adds one) | inform + store | verify after the store | "
          "of which the lexicon brought up to date | first cycle")
    xs, ys = [], []
    for n in sizes:
        agent, interp = taught_agent()
        have = sum(1 for c in agent.memory.concepts() if c.kind == "visual")
        if n > have:
            add_synthetic(agent.memory, n - have, seed=n)
        # the size the cycles start at: counted after them, it grew with --repeat (one word per
        # inform), and read 16/106/1,006 at --repeat 20 (6 cycles) and 14/104/1004 at --repeat 15 or less
        total = sum(1 for c in agent.memory.concepts() if c.kind == "visual")
        inf_t, ver_t, lex_t = [], [], []
        first = 0.0
        for k in range(repeat + 1):
            obj = ObjectSpec("box", "red")
            t = time.perf_counter()
            r = interp.run(Lesson("inform", f"{new_word(k)} box", [obj]), index=1, seed=500 + k)
            t1 = time.perf_counter()
            assert r.answer.stored, "the inform lesson was meant to store"
            agent.lexicon.effective_meanings()  # (what the verify would do first: timed apart)
            t15 = time.perf_counter()
            interp.run(Lesson("verify", "red box", [obj], distractors=2), index=1, seed=900 + k)
            t2 = time.perf_counter()
            if k:  # the first cycle computes every concept's meaning once
                inf_t.append(t1 - t)
                ver_t.append(t2 - t1)
                lex_t.append(t15 - t1)
            else:
                first = t2 - t
        xs.append(total)
        ys.append(statistics.median(ver_t))
        print(f"{total} | {statistics.median(inf_t) * 1e3:.1f} | {statistics.median(ver_t) * 1e3:.1f} | "
              f"{statistics.median(lex_t) * 1e3:.2f} | {first * 1e3:.0f}")
    print(f"growth exponent of the verify after a store, in visual concepts: {slope(xs, ys):.2f}")


# --------------------------------------------------------------------------- 3. examples

def bench_examples(sizes: Sequence[int], repeat: int) -> None:
    print("\n3. examples per concept: query (MAC pre-filter) | query exhaustive | store (content filter) | "
          "store exhaustive  (ms, median)")
    print("examples | kind | descriptions | query | query exhaustive | same answers | store | store exhaustive")
    series: dict[str, list[tuple[int, float, float]]] = {"similar": [], "dissimilar": []}
    for kind in ("similar", "dissimilar"):
        for n in sizes:
            rng = np.random.default_rng(n)
            m = ConceptMemory(SageParams(assimilation=0.01 if kind == "similar" else 0.9))
            m.create("r_w", "visual")

            def example(o: str) -> list[Term]:
                if kind == "similar":
                    return obj_facts(o, ["cv_red", "cv_box", f"cv_x{int(rng.integers(4))}", "r_w"])
                return obj_facts(o, [f"cv_x{j}" for j in rng.choice(200, size=3, replace=False)] + ["r_w"])

            for _ in range(n):
                m.store(example("o1"), "r_w")
            ctx = m.concept("r_w").context
            desc = len(ctx.generalizations) + len(ctx.examples)
            probes = [[f for f in example("o9") if f.args[1] != Term("r_w")] for _ in range(repeat)]
            it = iter(range(10 ** 9))
            q = timed(unkept(m, lambda: m.query(probes[next(it) % repeat], "isa(X,r_w)")), repeat)
            it2 = iter(range(10 ** 9))
            qe = timed(unkept(m, lambda: m.query(probes[next(it2) % repeat], "isa(X,r_w)", exhaustive=True)),
                       min(repeat, 5))
            agree = sum([(x.fact, x.similarity) for x in m.query(p, "isa(X,r_w)")]
                        == [(x.fact, x.similarity) for x in m.query(p, "isa(X,r_w)", exhaustive=True)]
                        for p in probes[:5])
            s = timed(lambda: m.store(example("o1"), "r_w"), repeat)
            se = timed(lambda: m.store(example("o1"), "r_w", exhaustive=True), min(repeat, 5))
            series[kind].append((n, q, s))
            print(f"{n} | {kind} | {desc} | {q * 1e3:.2f} | {qe * 1e3:.2f} | {agree}/{min(5, len(probes))} | "
                  f"{s * 1e3:.2f} | {se * 1e3:.2f}")
    for kind, pts in series.items():
        ns = [p[0] for p in pts]
        print(f"growth exponents in examples ({kind}): query {slope(ns, [p[1] for p in pts]):.2f}, "
              f"store {slope(ns, [p[2] for p in pts]):.2f}")


# --------------------------------------------------------------------------- 4. scene size

def bench_scene(sizes: Sequence[int], repeat: int) -> None:
    print("\n4. every concept asked of every object and ordered pair (s, median), taught memory")
    print("objects | facts | queries | query all, first time | query all, again | again, answers kept | "
          "fact lookup (index) | fact lookup by scan")
    agent, _ = taught_agent()
    m = agent.memory
    visual = [c.symbol for c in m.concepts() if c.kind == "visual"]
    spatial = [c.symbol for c in m.concepts() if c.kind == "spatial"]
    xs, ys = [], []
    for n in sizes:
        ids, facts = scene_facts(n, seed=n)

        def lookups(idx: FactIndex) -> int:
            k = 0
            for a in ids:
                k += len(idx.percepts(a))
                for b in ids:
                    if a != b:
                        k += len(idx.relations(a, b))
            return k

        def scan() -> int:
            k = 0
            for a in ids:
                ta = Term(a)
                k += sum(1 for f in facts if f.name == "isa" and f.args[0] is ta)
                for b in ids:
                    if a != b:
                        tb = Term(b)
                        k += sum(1 for f in facts if f.name != "isa" and len(f.args) == 2
                                 and {f.args[0], f.args[1]} == {ta, tb})
            return k

        def ask_all() -> int:
            idx = FactIndex(facts)
            hits = 0
            for a in ids:
                pa = idx.percepts(a)
                for c in visual:
                    hits += bool(m.query(pa, fn("isa", a, c)))
            for a in ids:
                for b in ids:
                    if a != b:
                        pf = idx.percepts(a) + idx.percepts(b) + idx.relations(a, b)
                        for c in spatial:
                            hits += bool(m.query(pf, fn(c, a, b)))
            return hits

        r = max(1, repeat // 10) if n >= 20 else max(1, repeat // 4)
        first = timed(ask_all, 1, warm=False)  # fills the per-description memos of the query pre-filter
        kept = timed(ask_all, r)  # every answer kept from the first time
        total = timed(unkept(m, ask_all), r)
        look = timed(lambda: lookups(FactIndex(facts)), r)
        sc = timed(scan, 1) if n <= 40 else float("nan")
        queries = n * len(visual) + n * (n - 1) * len(spatial)
        xs.append(n)
        ys.append(total)
        print(f"{n} | {len(facts)} | {queries} | {first:.3f} | {total:.3f} | {kept:.4f} | {look:.4f} | {sc:.3f}")
    print(f"growth exponent in objects (query all, again): {slope(xs, ys):.2f} "
          f"(the ordered pairs alone grow with exponent 2)")


def main() -> None:
    ap = bench_args.Parser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=bench_args.count, default=20, help="timed calls per figure (default 20)")
    ap.add_argument("--quick", action="store_true", help="smaller sizes (a smoke run)")
    # below the smallest size (10 concepts) the parts would build no memory at all
    ap.add_argument("--largest", type=bench_args.at_least(10), default=100_000,
                    help="the most concepts parts 1, 2 and 5 build (default 100,000)")
    ap.add_argument("--only", choices=("concepts", "files", "cycle", "examples", "scene"), action="append",
                    help="run only these parts (repeatable; files builds its memories in part 1)")
    ap.add_argument("--measure-load", nargs=2, metavar=("PATH", "PROBE"), help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.measure_load:  # the fresh process of part 5
        import json

        from aileen.errors import UserError

        try:
            print(json.dumps(measure_load(args.measure_load[0], args.measure_load[1].split(","), args.repeat)))
        except UserError as exc:  # a missing or damaged file: one line, as `aileen run` says it
            ap.exit(2, f"{ap.prog}: {exc.format()}\n")
        return
    parts = set(args.only or ("concepts", "files", "cycle", "examples", "scene"))
    largest = min(args.largest, 1000) if args.quick else args.largest
    concepts = tuple(n for n in (10, 100, 1000, 10_000, 100_000) if n <= largest)
    if args.only and set(args.only) == {"files"} and not any(n >= 1000 for n in concepts):
        # part 5 reads part 1's memories of 1,000 concepts or more: it printed an empty table
        ap.error(f"--only files needs --largest 1000 or more (its memories have 1,000, 10,000 and "
                 f"100,000 concepts), got {largest}")
    print(bench_args.host_line())
    t0 = time.perf_counter()
    files: list[str] = []  # part 5, measured on part 1's memories, printed after part 4
    if parts & {"concepts", "files"}:
        kept = bench_concepts(concepts, args.repeat, keep=[n for n in concepts if n >= 1000] if "files" in parts else ())
        if "files" in parts:
            bench_files(kept, args.repeat, say=files.append)
        del kept
    if "cycle" in parts:
        bench_cycle(concepts, max(3, args.repeat // 4))
    if "examples" in parts:
        bench_examples((1, 10, 100) if args.quick else (1, 10, 100, 1000), args.repeat)
    if "scene" in parts:
        bench_scene((4, 10, 20) if args.quick else (4, 10, 20, 40), args.repeat)
    for line in files:
        print(line)
    print(f"\n({time.perf_counter() - t0:.0f} s)")


if __name__ == "__main__":
    main()
