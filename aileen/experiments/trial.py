"""One trial of a learning-curve experiment: a fresh learner taken through one `protocol.Trial`.

The prerequisites are taught first (not scored: spatial starts with the visual words known,
action with visual and spatial known, all of them *taught*, never injected), then for every
training lesson the agent is informed, and the trial's fixed generality and specificity exams
(5 verify lessons each) are given. Per lesson we record the create/store commands the inform
lesson cost, both exam scores, and the one-shot oracle (the generality items whose words have
all been taught so far), which is the ceiling: an honest learner can never beat it.

A trial is seeded from (seed, trial index) alone (`trial_seed`), so it gives the same numbers
in any process and in any order. Exams never change what the agent knows: `verify` must not
store, and every trial checks that the concept and semantic memories are byte-identical before
and after each exam (a violation is an error, not a number).

Why a module of its own: running one trial is a job apart from running many of them
(`runner`: checks, worker processes, progress) and from the records it returns (`results`);
a sweep (`sweep.run_job`) runs trials one at a time from here.
"""

from __future__ import annotations

import hashlib
import json
import time
from collections.abc import Callable, Sequence
from dataclasses import replace

import numpy as np

from aileen.experiments import ceiling as sector_ceiling
from aileen.experiments.learners import make_agent_replayable
from aileen.experiments.protocol import Trial, lesson_words, make_trial, oracle_curve
from aileen.experiments.results import GroupRecord, LessonRecord, TrialResult

__all__ = ["Progress", "trial_seed", "memory_digest_of", "teach", "run_trial"]

Progress = Callable[[int], None]  # called with the number of lessons just finished


def trial_seed(seed: int, trial: int) -> int:
    """The seed of trial `trial` (0-based) of a run with seed `seed`: a function of the two
    alone, so a trial gives the same result in any process and in any order."""
    return int(np.random.SeedSequence([int(seed), int(trial)]).generate_state(1)[0])


def memory_digest_of(memory, semantic, common: frozenset | None = None) -> str:  # noqa: ANN001
    """A digest of everything learned (concept + semantic memory), to prove exams store nothing.
    With `common` (the lexicon's common percepts, `agent/seen.py`), the lexicon's counts of the
    objects taught on are left out and `common` put in: the counts change with every inform, the
    answers only through what is common."""
    data = memory.to_dict()  # its annotations are the live memory's own: not changed here
    extra = {}
    if common is not None:
        notes = data.get("annotations") or {}
        lex = notes.get("lexicon")
        if isinstance(lex, dict) and "seen" in lex:
            data = {**data, "annotations": {**notes, "lexicon": {k: v for k, v in lex.items() if k != "seen"}}}
        extra = {"common": sorted(map(str, common))}
    text = json.dumps({"concepts": data, "words": semantic.to_dict(), **extra}, sort_keys=True)
    return hashlib.sha1(text.encode()).hexdigest()


def _memory_digest(agent) -> str:  # noqa: ANN001 - Agent, imported lazily
    """What the agent's answers depend on (`memory_digest_of`, with what is common): an exam is
    given again only when something that can change its answers changed."""
    own = getattr(agent, "digest", None)  # a baseline learner keeps its own memory
    extra = own() if own is not None else ""
    lexicon = getattr(agent, "lexicon", None)
    common = lexicon.seen.common() if lexicon is not None else None
    return memory_digest_of(agent.memory, agent.semantic, common) + extra


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

    Every trial's random draws take the paper's four shapes (`catalog.drawing`). A trial with
    its own relations (the teacher protocol) runs inside `relations.scope`, and
    the ideal observer (`ideal.py`) learns from the same lessons, from the trainer's tables."""
    from aileen.domain import relations
    from aileen.world import catalog

    ts = trial_seed(seed, trial)
    spec: Trial = make_trial(experiment, ts, protocol)
    with relations.scope(*spec.relations), catalog.drawing(catalog.PAPER_SHAPES):
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
    agent, interp, replayer = make_agent_replayable(perception, ts, without, agent_kind, sage, senses)
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
        ceiling = list(oracle) if repertoire else sector_ceiling.cross_situational_curve(spec)
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
