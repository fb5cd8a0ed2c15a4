"""Running the paper's learning-curve experiments (DESIGN.md section 10).

A trial is one fresh agent taken through one `protocol.Trial`: the prerequisites are taught
first (not scored: spatial starts with the visual words known, action with visual and spatial
known, all of them *taught*, never injected), then for every training lesson the agent is
informed, and the trial's fixed generality and specificity exams (5 verify lessons each) are
given. Per lesson we record the create/store commands the inform lesson cost, both exam
scores, and the one-shot oracle (the generality items whose words have all been taught so
far), which is the ceiling: an honest learner can never beat it.

Trials are independent and seeded from (seed, trial index) alone, so they run in parallel
processes (`jobs`) and give the same numbers whatever `jobs` is. Exams never change what the
agent knows: `verify` must not store, and every trial checks that the concept and semantic
memories are byte-identical before and after each exam (a violation is an error, not a
number).
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import replace

import numpy as np

from aileen.agent.records import ABLATIONS, ablation_params  # noqa: F401  (re-exported)
from aileen.errors import UserError
from aileen.experiments.output import write_experiment  # noqa: F401  (re-exported)
from aileen.experiments.protocol import (
    EXPERIMENTS,
    PROTOCOL_EXPERIMENTS,
    PROTOCOLS,
    Trial,
    lesson_words,
    make_trial,
    not_in_protocol,
    oracle_curve,
)
from aileen.experiments.results import (  # noqa: F401  (the records and reports, re-exported)
    EXAM_ITEMS,
    ExperimentResult,
    GroupRecord,
    Headline,
    LessonRecord,
    LessonSummary,
    TrialResult,
    headline,
    headline_dict,
    holds_from,
    summarise,
    summary_csv,
    trial_words_check,
    trials_csv,
    update_summary_json,
    write_bytes,
    write_text,
)
from aileen.world.camera import DEFAULT_CAMERA

PERCEPTIONS: tuple[str, ...] = ("detector", "truth")
# The learners that perceive with the agent's senses (and so take `--senses`): ours and the
# baselines that learn from its facts; the paper's learner keeps the paper's 8 sectors.
SENSING = frozenset({"asp", "nearest", "cobweb", "trestle"})
DEFAULT_TRIALS: dict[str, int] = {"visual": 10, "spatial": 10, "action": 5, "repertoire": 10}
Progress = Callable[[int], None]  # called with the number of lessons just finished


def trial_seed(seed: int, trial: int) -> int:
    """The seed of trial `trial` (0-based) of a run with seed `seed`: a function of the two
    alone, so a trial gives the same result in any process and in any order."""
    return int(np.random.SeedSequence([int(seed), int(trial)]).generate_state(1)[0])


def _memory_digest_of(memory, semantic) -> str:  # noqa: ANN001
    """A digest of everything learned (concept + semantic memory), to prove exams store nothing."""
    data = {"concepts": memory.to_dict(), "words": semantic.to_dict()}
    return hashlib.sha1(json.dumps(data, sort_keys=True).encode()).hexdigest()


def _memory_digest(agent) -> str:  # noqa: ANN001 - Agent, imported lazily
    own = getattr(agent, "digest", None)  # a baseline learner keeps its own memory
    extra = own() if own is not None else ""
    return _memory_digest_of(agent.memory, agent.semantic) + extra


# Our agent, the paper's learner in Soar, and the baselines of experiments/baselines.py.
from aileen.experiments.protocol import AGENT_KINDS  # noqa: E402


def _make_agent(perception: str, seed: int, without: Sequence[str] = (), agent_kind: str = "asp",
                sage=None, senses: str | None = None):  # noqa: ANN001, ANN202
    """A fresh agent and its interpreter with the chosen vision (and mechanisms switched off);
    `agent_kind` "soar" is the paper's learner as Soar productions (aileen.soar), or a baseline
    (experiments/baselines.py); `sage` (a `SageParams`) sets the concept memory's thresholds (a
    sweep), else the agent's own (`AgentParams.sage`); `senses` the sense of direction of our
    agent and of the baselines that learn from its facts (`--senses`; None: the default)."""
    agent, interp, _replayer = _make_agent_replayable(perception, seed, without, agent_kind, sage, senses)
    return agent, interp


def senses_of(without: Sequence[str] = (), senses: str | None = None) -> str:
    """The sense of direction an agent run with `--without` and `--senses` has."""
    from aileen.agent import AgentParams

    return AgentParams(**ablation_params(without, senses)).senses_of_direction


def _make_agent_replayable(perception: str, seed: int, without: Sequence[str] = (), agent_kind: str = "asp",
                           sage=None, senses: str | None = None):  # noqa: ANN001, ANN202
    """`_make_agent`, plus the agent's perceiver as an `exams.Replayer` (recorded exam scenes
    are served through it; live scenes go to the chosen vision)."""
    from aileen.agent import Agent, AgentParams
    from aileen.curriculum.interpreter import Interpreter
    from aileen.experiments.exams import Replayer
    from aileen.experiments.vision_cache import vision as live_vision
    from aileen.memory.concept import ConceptMemory

    params = AgentParams(seed=seed, **ablation_params(without, senses))  # type: ignore[arg-type]
    if agent_kind not in AGENT_KINDS:
        raise UserError(f"unknown agent {agent_kind!r}; expected one of {', '.join(AGENT_KINDS)}")
    if perception not in PERCEPTIONS:
        raise UserError(f"unknown perception {perception!r}; expected one of {', '.join(PERCEPTIONS)}")
    truth = None
    if perception == "truth":
        from aileen.perception.truth import TruthVision

        truth = TruthVision()
    replayer = Replayer(truth if truth is not None else live_vision(DEFAULT_CAMERA))
    memory = ConceptMemory(sage if sage is not None else params.sage())
    if agent_kind == "soar":
        from aileen.soar.learner import soar_agent

        agent = soar_agent(memory if sage is not None else None, without=without, perceiver=replayer, seed=seed)
    elif agent_kind != "asp":
        from aileen.experiments import baselines

        agent = baselines.make(agent_kind, seed, replayer, senses)
    else:
        agent = Agent(memory, params=params, perceiver=replayer)
    return agent, Interpreter(agent, on_frame=truth.see_frame if truth is not None else None), replayer


def teach(interp, lessons: Sequence, seed: int, on_result: Callable | None = None) -> int:  # noqa: ANN001
    """Run inform lessons (not scored); return the create/store commands they cost.
    `on_result` sees each lesson's result (the evaluation reads the trainer's tables)."""
    total = 0
    for i, lesson in enumerate(lessons):
        r = interp.run(lesson, index=i + 1, seed=seed + i)
        total += r.answer.commands
        if on_result is not None:
            on_result(r)
    return total


def _exam(interp, items: Sequence, seeds: Sequence[int], index: int) -> list[bool]:  # noqa: ANN001
    """Give the exam items live (lay out, render, perceive); per item, whether it was answered
    as a correct learner would. `run_trial` replays recorded items instead (`exams`); this is
    the reference it is checked against."""
    out = []
    for item, s in zip(items, seeds):
        r = interp.run(item, index=index, seed=s)
        if r.answer.commands:
            raise RuntimeError(f"verify lesson {item.content!r} sent {r.answer.commands} create/store commands")
        if r.expected is None:
            raise RuntimeError(f"the trainer cannot grade exam item {item.content!r}")
        out.append(r.answer.result == r.expected)
    return out


def _replay_exam(agent, replayer, tapes: Sequence) -> list[bool]:  # noqa: ANN001
    """Give the recorded exam items; per item, whether it was answered as a correct learner would."""
    out = []
    for tape in tapes:
        answer = tape.replay(agent, replayer)
        if answer.commands:
            raise RuntimeError(f"verify lesson {tape.lesson.content!r} sent {answer.commands} create/store commands")
        out.append(answer.result == tape.expected)
    return out


def run_trial(experiment: str, trial: int, seed: int, *, perception: str = "detector",
              lessons: int | None = None, progress: Progress | None = None,
              without: Sequence[str] = (), agent_kind: str = "asp", protocol: str = "paper",
              live_exams: bool = False, sage=None, senses: str | None = None) -> TrialResult:  # noqa: ANN001
    """One trial of `experiment`: a fresh agent, prerequisites taught, then per training lesson
    inform + both exams. `lessons` limits the number of training lessons (for tests); `sage`
    (a `SageParams`) sets the concept memory's thresholds (default: the agent's own); `senses`
    the agent's sense of direction (`--senses`; default: the agent's own).

    The exam items are recorded once (`exams.record`) and replayed after every lesson; when a
    lesson left the agent's memory as it was, the last exam's answers are the answers (the
    agent is a function of its memory: checked by `live_exams=True`, which lays out, renders,
    perceives and asks every item after every lesson, as before).

    A trial with its own relations (the teacher protocol) runs inside `relations.scope`, and
    the ideal observer (`ideal.py`) learns from the same lessons, from the trainer's tables."""
    from aileen.domain import relations

    ts = trial_seed(seed, trial)
    spec: Trial = make_trial(experiment, ts, protocol)
    with relations.scope(*spec.relations):
        return _run_trial(spec, experiment, trial, seed, ts, perception=perception, lessons=lessons,
                          progress=progress, without=without, agent_kind=agent_kind, protocol=protocol,
                          live_exams=live_exams, sage=sage, senses=senses)


def _observe(observer, r) -> None:  # noqa: ANN001 - IdealObserver, LessonResult
    """The ideal observer sees a lesson as the trainer laid it out: its visual words, and for a
    relation the direction of the said pair, as an example (inform, or a verify the trainer
    grades true) or a near miss (a verify it grades false)."""
    from aileen.curriculum.sentences import read_content
    from aileen.experiments.ideal import said_direction

    lesson = r.lesson
    rel = read_content(lesson.content).relation
    observer.learn_words(lesson_words(lesson) - {rel})
    if rel is None or lesson.action is not None or (lesson.signal == "verify" and r.expected is None):
        return
    if lesson.signal in ("inform", "verify"):
        observer.see(rel, said_direction(lesson, r.setup), lesson.signal == "inform" or r.expected == "success")


def _run_trial(spec: Trial, experiment: str, trial: int, seed: int, ts: int, *, perception: str,
               lessons: int | None, progress: Progress | None, without: Sequence[str], agent_kind: str,
               protocol: str, live_exams: bool, sage, senses: str | None) -> TrialResult:  # noqa: ANN001
    from aileen.curriculum import trainer
    from aileen.curriculum.interpreter import CAMERA_NOISE
    from aileen.curriculum.sentences import read_content
    from aileen.experiments import exams, ideal

    t0 = time.perf_counter()
    agent, interp, replayer = _make_agent_replayable(perception, ts, without, agent_kind, sage, senses)
    try:
        # Layout seeds: prerequisites, lessons and exam items each get their own, fixed per trial,
        # so an exam item shows the same scene after every lesson: only the learner changes.
        rng = np.random.default_rng([ts, 1])
        base = int(rng.integers(1 << 30))
        gen_seeds = [base + 10_000 + k for k in range(len(spec.generality))]
        spec_seeds = [base + 20_000 + k for k in range(len(spec.specificity))]
        tapes_g = tapes_s = None
        if not live_exams:
            rec = {"camera": interp.camera, "noise": CAMERA_NOISE, "on_frame": interp.on_frame}
            tapes_g = exams.record_all(spec.generality, gen_seeds, replayer.live, **rec)
            tapes_s = exams.record_all(spec.specificity, spec_seeds, replayer.live, **rec)
        from aileen.experiments import ceiling as sector_ceiling

        observer = None
        if spec.teacher is not None:
            observer = ideal.IdealObserver(ideal.priors(spec.teacher.family_of()))
            if tapes_g is not None and tapes_s is not None:
                dirs_g = [t.direction for t in tapes_g]
                dirs_s = [t.direction for t in tapes_s]
            else:
                dirs_g = [ideal.said_direction(x, trainer.layout(x, seed=s)) for x, s in zip(spec.generality, gen_seeds)]
                dirs_s = [ideal.said_direction(x, trainer.layout(x, seed=s))
                          for x, s in zip(spec.specificity, spec_seeds)]

        pre_sectors: list[str | None] = []

        def pre_seen(r) -> None:  # noqa: ANN001
            pre_sectors.append(sector_ceiling.sector_of(r.lesson, r.setup))
            if observer is not None:
                _observe(observer, r)

        pre = teach(interp, spec.prerequisites, base + 30_000, pre_seen)
        oracle = oracle_curve(spec)
        # The ceilings speak of colour and shape words and of directions: the repertoire (sizes,
        # distance, contact, comparatives) has neither, so its curve stands against the oracle.
        repertoire = experiment == "repertoire"
        ceiling = list(oracle) if repertoire else cross_situational_curve(spec)
        todo = spec.lessons if lessons is None else spec.lessons[:lessons]
        # Groups of exam items (the teacher protocol's families of words), and what each
        # learner got right per item after each lesson (for the groups' figures).
        family = spec.teacher.family_of() if spec.teacher is not None else {}
        group_g = [family.get(read_content(x.content).relation or "") for x in spec.generality]
        group_s = [family.get(read_content(x.content).relation or "") for x in spec.specificity]
        groups: dict[str, list] = {g: [] for g in sorted(set(group_g + group_s) - {None})}
        taught: set[str] = set()
        for lesson in spec.prerequisites:
            taught |= lesson_words(lesson)
        lesson_sectors: list[str | None] = []
        records: list[LessonRecord] = []
        run = len(spec.prerequisites)
        last: tuple[str, list[bool], list[bool]] | None = None
        ideal_last: tuple[list[bool], list[bool]] | None = None
        reused = 0
        for i, lesson in enumerate(todo):
            r = interp.run(lesson, index=i + 1, seed=base + i)
            taught |= lesson_words(lesson)
            lesson_sectors.append(sector_ceiling.sector_of(lesson, r.setup))
            before = _memory_digest(agent)
            if live_exams:
                gi = _exam(interp, spec.generality, gen_seeds, i + 1)
                si = _exam(interp, spec.specificity, spec_seeds, i + 1)
            elif last is not None and last[0] == before:
                gi, si = last[1], last[2]
                reused += 1
            else:
                gi, si = _replay_exam(agent, replayer, tapes_g), _replay_exam(agent, replayer, tapes_s)
            g, s = sum(gi), sum(si)
            last = (before, gi, si)
            if _memory_digest(agent) != before:
                raise RuntimeError(f"trial {trial}, lesson {i + 1}: an exam changed the agent's memory")
            ig = isp = -1
            if observer is not None:
                _observe(observer, r)
                ideal_last = ([observer.says_yes(x, d) for x, d in zip(spec.generality, dirs_g)],
                              [not observer.says_yes(x, d) for x, d in zip(spec.specificity, dirs_s)])
                ig, isp = sum(ideal_last[0]), sum(ideal_last[1])
            run += 1 + len(spec.generality) + len(spec.specificity)
            records.append(LessonRecord(trial, i + 1, lesson.content, r.answer.commands, g, s, oracle[i], ceiling[i],
                                        ideal_generality=ig, ideal_specificity=isp))
            orc = [lesson_words(x) <= taught for x in spec.generality]
            for name, rows in groups.items():
                rows.append(_group_record(name, group_g, group_s, gi, si, orc, ideal_last, spec.specificity))
            if progress is not None:
                progress(1)
        if protocol == "wide" and not repertoire:  # the 8-sector learner's curve, from the trainer's own tables
            items = ([t.sector for t in tapes_g] if tapes_g is not None
                     else [sector_ceiling.sector(x, s) for x, s in zip(spec.generality, gen_seeds)])
            curve = sector_ceiling.sector_ceiling_curve(spec, pre_sectors, lesson_sectors, items)
            records = [replace(r, sector_ceiling=c) for r, c in zip(records, curve)]
        by_kind = _by_kind(spec.specificity, last[2]) if last is not None else {}
        ideal_kind = _by_kind(spec.specificity, ideal_last[1]) if ideal_last is not None else {}
        return TrialResult(experiment, trial, seed, records, pre, time.perf_counter() - t0, run,
                           final_specificity=by_kind, exams_reused=reused,
                           exam_items=(len(spec.generality), len(spec.specificity)), groups=groups,
                           ideal_final_specificity=ideal_kind)
    finally:
        from aileen.curriculum.interpreter import close_agent

        close_agent(agent)


def _by_kind(items: Sequence, right: Sequence[bool]) -> dict[str, list[int]]:
    """Per kind of specificity item (its note): [right, items]."""
    out: dict[str, list[int]] = {}
    for item, ok in zip(items, right):
        k = out.setdefault(item.note or "specificity", [0, 0])
        k[0] += int(ok)
        k[1] += 1
    return out


def _group_record(name: str, group_g: Sequence, group_s: Sequence, gi: Sequence[bool], si: Sequence[bool],
                  orc: Sequence[bool], ideal_last: tuple[list[bool], list[bool]] | None,
                  items_s: Sequence) -> GroupRecord:
    """One lesson's figures over the exam items of group `name`."""
    from aileen.experiments.teacher import EDGE

    g = [k for k, x in enumerate(group_g) if x == name]
    s = [k for k, x in enumerate(group_s) if x == name]
    edge = [k for k in s if items_s[k].note == EDGE]
    ig, isp = ideal_last if ideal_last is not None else (None, None)
    return GroupRecord(sum(gi[k] for k in g), len(g), sum(si[k] for k in s), len(s), sum(orc[k] for k in g),
                       sum(ig[k] for k in g) if ig is not None else -1,
                       sum(isp[k] for k in s) if isp is not None else -1,
                       sum(si[k] for k in edge), len(edge),
                       sum(isp[k] for k in edge) if isp is not None else -1)


def cross_situational_curve(trial: Trial) -> list[int]:
    """Per lesson, the generality score of an ideal learner that, unlike the one-shot oracle,
    must find out which percept each word names (it has no prior that colour words name
    colours): a word's candidates are the percepts common to every object it was said of, and
    a word pinned to one percept removes it from every other word's candidates (mutual
    exclusivity), to a fixpoint. An exam item counts when it is true under every meaning the
    learner cannot yet rule out: each of its words' candidates is among the item's percepts
    (so "blue sphere" taught once already passes the exam item "blue sphere").

    "blue sphere" as the first lesson pins neither word; "blue box" later pins both "blue" and
    then "sphere". The gap between `oracle_curve` and this curve is what the curriculum leaves
    ambiguous, not what a learner gets wrong. Visual words only: relations and actions come
    from their own lessons (each names one relation of two already-known objects) and are
    pinned once taught, as in the oracle.
    """
    from aileen.curriculum.sentences import read_content

    cands: dict[str, set[str]] = {}
    pinned_other: set[str] = set()  # relation/action words: pinned when taught

    def learn(lesson) -> None:  # noqa: ANN001
        info = read_content(lesson.content)
        if info.relation is not None:
            pinned_other.update(w for w in lesson_words(lesson) if w in (info.relation, info.verb))
        for phrase_spec, obj in zip(info.phrases, lesson.objects):
            percepts = {f"c:{obj.colour}", f"s:{obj.shape}"}
            for w in (phrase_spec.colour, phrase_spec.shape):
                if w:
                    cands[w] = cands[w] & percepts if w in cands else set(percepts)
        changed = True
        while changed:
            changed = False
            for w, cs in cands.items():
                if len(cs) == 1:
                    p = next(iter(cs))
                    for v, other in cands.items():
                        if v != w and p in other and len(other) > 1:
                            other.discard(p)
                            changed = True

    def sure(item) -> bool:  # noqa: ANN001
        info = read_content(item.content)
        for phrase_spec, obj in zip(info.phrases, item.objects):
            percepts = {f"c:{obj.colour}", f"s:{obj.shape}"}
            for w in (phrase_spec.colour, phrase_spec.shape):
                if w and not (w in cands and cands[w] <= percepts):
                    return False
        return all(w in pinned_other for w in lesson_words(item) if w in (info.relation, info.verb))

    for lesson in trial.prerequisites:
        learn(lesson)
    out = []
    for lesson in trial.lessons:
        learn(lesson)
        out.append(sum(1 for item in trial.generality if sure(item)))
    return out


def _trial_job(args: tuple) -> TrialResult:
    experiment, trial, seed, perception, lessons, without, agent_kind, protocol, senses, queue = args
    tick = (lambda n: queue.put(n)) if queue is not None else None
    return run_trial(experiment, trial, seed, perception=perception, lessons=lessons, progress=tick,
                     without=without, agent_kind=agent_kind, protocol=protocol, senses=senses)


# --------------------------------------------------------------------------- many trials

def run_experiment(experiment: str, *, trials: int | None = None, seed: int = 0, jobs: int = 1,
                   perception: str = "detector", lessons: int | None = None,
                   progress: bool = False, without: Sequence[str] = (), agent_kind: str = "asp",
                   protocol: str = "paper", senses: str | None = None) -> ExperimentResult:
    """All trials of one experiment, in `jobs` processes; results in trial order, identical
    for any `jobs`. `senses`: the agent's sense of direction (None: the default)."""
    if experiment not in EXPERIMENTS:
        raise UserError(f"unknown experiment {experiment!r}; expected one of {', '.join(EXPERIMENTS)}")
    n = DEFAULT_TRIALS[experiment] if trials is None else trials
    if n < 1:
        raise UserError(f"--trials must be at least 1, got {n}")
    if jobs < 1:
        raise UserError(f"--jobs must be at least 1, got {jobs}")
    if lessons is not None and lessons < 1:
        raise UserError(f"--lessons must be at least 1, got {lessons}")
    if perception not in PERCEPTIONS:
        raise UserError(f"unknown perception {perception!r}; expected one of {', '.join(PERCEPTIONS)}")
    without = tuple(without)
    _make_agent("truth", 0, without, senses=senses)  # reject an unknown --without or --senses before any work
    if agent_kind != "asp":
        probe = _make_agent("truth", 0, without, agent_kind)[0]  # and a missing extra
        if hasattr(probe, "close"):
            probe.close()
    if protocol not in PROTOCOLS:
        raise UserError(f"unknown protocol {protocol!r}; expected one of {', '.join(PROTOCOLS)}")
    if experiment not in PROTOCOL_EXPERIMENTS[protocol]:
        raise UserError(f"{not_in_protocol(experiment, protocol)}; expected one of "
                        f"{', '.join(PROTOCOL_EXPERIMENTS[protocol])}")
    per_trial = len(make_trial(experiment, 0, protocol).lessons)
    if lessons is not None:
        per_trial = min(per_trial, lessons)
    t0 = time.perf_counter()
    bar = _bar(n * per_trial, experiment) if progress else None
    results = _map_trials(experiment, n, seed, jobs, perception, lessons, bar, without, agent_kind, protocol, senses)
    if bar is not None:
        bar.close()
    res = ExperimentResult(experiment, perception, seed, results, without=without, protocol=protocol,
                           senses=senses_of(without, senses) if agent_kind in SENSING else "")
    res.summary = summarise(results)
    res.headline = headline(res, time.perf_counter() - t0)
    return res


def _bar(total: int, what: str):  # noqa: ANN202
    import sys

    from tqdm import tqdm

    return tqdm(total=total, desc=what, unit="lesson", file=sys.stderr, leave=True, dynamic_ncols=True)


def _map_trials(experiment: str, n: int, seed: int, jobs: int, perception: str, lessons: int | None,
                bar, without: tuple[str, ...] = (), agent_kind: str = "asp",
                protocol: str = "paper", senses: str | None = None) -> list[TrialResult]:  # noqa: ANN001
    if (jobs == 1 or n == 1) and agent_kind not in HASH_ORDER_SENSITIVE:
        tick = bar.update if bar is not None else None
        return [run_trial(experiment, t, seed, perception=perception, lessons=lessons, progress=tick,
                          without=without, agent_kind=agent_kind, protocol=protocol, senses=senses)
                for t in range(n)]
    return _pool_map(_trial_job, [(experiment, t, seed, perception, lessons, without, agent_kind, protocol, senses)
                                  for t in range(n)], jobs, bar)


_SHARED_POOL: list = []  # the pool `shared_pool` holds open, if any
# Learners whose results depend on the order Python iterates sets of strings (COBWEB in
# concept_formation): their trials always run in worker processes started with a fixed
# PYTHONHASHSEED, so the same seed gives the same numbers in every run and for any --jobs.
HASH_ORDER_SENSITIVE = frozenset({"cobweb", "trestle"})


def _fixed_hash_seed() -> None:
    """Spawned workers inherit the environment: fix their string hashing (see above)."""
    os.environ.setdefault("PYTHONHASHSEED", "0")


@contextlib.contextmanager
def shared_pool(jobs: int) -> Iterator[None]:
    """Run every `_pool_map` inside on one pool of `jobs` worker processes: `aileen experiment
    all` starts (and loads vision in) its workers once, not once per experiment and baseline,
    and they share what vision saw (`vision_cache`: every learner sees a trial's images)."""
    import multiprocessing as mp
    from concurrent.futures import ProcessPoolExecutor

    if jobs <= 1:
        yield
        return
    _fixed_hash_seed()
    from aileen.experiments import vision_cache
    from aileen.experiments.local_backend import one_thread, stop_on_interrupt

    with vision_cache.shared(), ProcessPoolExecutor(max_workers=jobs, mp_context=mp.get_context("spawn"),
                                                    initializer=one_thread) as pool, stop_on_interrupt(pool):
        _SHARED_POOL.append(pool)
        try:
            yield
        finally:
            _SHARED_POOL.remove(pool)


def _pool_map(func: Callable, jobs_args: Sequence[tuple], jobs: int, bar) -> list:  # noqa: ANN001
    """`func(args + (queue,))` for each args tuple in `jobs` spawned processes, results in
    input order. Workers put lesson counts on the queue; this process moves the bar."""
    import multiprocessing as mp
    import queue as queue_mod
    from concurrent.futures import ProcessPoolExecutor, wait

    from aileen.experiments.local_backend import one_thread, stop_on_interrupt

    ctx = mp.get_context("spawn")  # clingo and cv2 hold threads: never fork them
    _fixed_hash_seed()
    with contextlib.ExitStack() as stack:
        manager = stack.enter_context(ctx.Manager()) if bar is not None else None
        q = manager.Queue() if manager is not None else None
        pool = _SHARED_POOL[-1] if _SHARED_POOL else stack.enter_context(
            ProcessPoolExecutor(max_workers=min(jobs, len(jobs_args)), mp_context=ctx, initializer=one_thread))
        if not _SHARED_POOL:  # a stop signal ends our own pool's workers at once
            stack.enter_context(stop_on_interrupt(pool))
        futures = [pool.submit(func, tuple(a) + (q,)) for a in jobs_args]
        if q is None:
            wait(futures)
            return [f.result() for f in futures]
        pending = set(futures)
        while pending:
            pending = {f for f in pending if not f.done()}
            try:
                while True:
                    bar.update(q.get(timeout=0.2))
            except queue_mod.Empty:
                pass
        while not q.empty():
            bar.update(q.get())
        return [f.result() for f in futures]


# --------------------------------------------------------------------------- summaries

__all__ = [
    "DEFAULT_TRIALS", "PERCEPTIONS", "LessonRecord", "TrialResult", "LessonSummary", "Headline",
    "ExperimentResult", "trial_seed", "run_trial", "run_experiment", "summarise", "holds_from", "headline",
    "write_experiment", "update_summary_json", "trials_csv", "summary_csv", "trial_words_check", "teach",
    "lesson_words",
]
