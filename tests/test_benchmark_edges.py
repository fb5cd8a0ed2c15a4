"""The benchmark scripts at their edges: bad counts refused on one line, --help that helps,
a p90 never under the median, goals and questions that name only what exists.

The scripts are run as a user runs them (a child process, `python benchmarks/X.py ...`), or
their functions are loaded from the file (benchmarks/ is no package), as tests/test_sme.py does.
"""

from __future__ import annotations

import importlib.util
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path
from types import ModuleType, SimpleNamespace

import pytest

ROOT = Path(__file__).resolve().parent.parent
BENCH = ROOT / "benchmarks"
TIMEOUT = 60  # seconds: a script that ignores a refusal runs its whole benchmark


def _load(name: str) -> ModuleType:
    """benchmarks/NAME.py as a module (named bench_NAME, apart from any package of that name)."""
    spec = importlib.util.spec_from_file_location(f"bench_{name}", BENCH / f"{name}.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # dataclasses look their module up
    spec.loader.exec_module(module)
    return module


def _start(script: str, *args: str) -> subprocess.Popen:
    env = {**os.environ, "PYTHONPATH": str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", "")}
    return subprocess.Popen([sys.executable, str(BENCH / script), *args], cwd=ROOT, env=env, text=True,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)


def _finish(proc: subprocess.Popen) -> tuple[int, str, str]:
    try:
        out, err = proc.communicate(timeout=TIMEOUT)
    except subprocess.TimeoutExpired:
        proc.kill()
        out, err = proc.communicate()
        return -1, out, err + f"\n(still running after {TIMEOUT} s)"
    return proc.returncode, out, err


def _run(script: str, *args: str) -> tuple[int, str, str]:
    return _finish(_start(script, *args))


def _refused(rc: int, err: str, *needles: str) -> str | None:
    """None when the run was refused as bad input (exit 2, one line on stderr naming every
    needle, no traceback); else what went wrong."""
    lines = err.strip().splitlines()
    if rc != 2 or len(lines) != 1 or "Traceback" in err or not all(n in err for n in needles):
        return f"exit {rc}, stderr {err.strip()[-300:]!r}"
    return None


# Every count a script takes, each below its least (a count of 0 timed nothing: inf, nan, or a
# traceback deep inside).
COUNTS = [
    ("sme.py", "--repeat", "0"),
    ("agent.py", "--repeat", "0"),
    ("asp.py", "--repeat", "0"),
    ("teacher_sim.py", "--trials", "0"),
    ("grain_frontier.py", "--trials", "0"),
    ("assimilation.py", "--trials", "0"),
    ("memory.py", "--repeat", "0"),
    ("perception.py", "--repeats", "0"),
    ("permanence.py", "--scenes", "0"),
    ("world.py", "--renders", "3"),
    ("sweep.py", "--workers", "0"),
    ("soar.py", "--react-tasks", "-1"),
]


def test_a_count_below_its_least_is_refused_on_one_line() -> None:
    procs = [(case, _start(case[0], case[1], case[2])) for case in COUNTS]  # side by side: a few s each
    wrong = []
    for (script, flag, value), proc in procs:
        rc, _out, err = _finish(proc)
        why = _refused(rc, err, flag)
        if why:
            wrong.append(f"{script} {flag} {value}: {why}")
    assert not wrong, "\n".join(wrong)


def test_asp_refuses_a_scene_too_small_for_its_goals() -> None:
    rc, _out, err = _run("asp.py", "--objects", "3", "--repeat", "1")
    assert _refused(rc, err, "--objects", "3") is None, err


def test_asp_goal_points_at_an_object_of_the_scene() -> None:
    asp = _load("asp")
    assert asp.pointed_object(10) == "o5"
    assert asp.pointed_object(5) == "o5"
    assert asp.pointed_object(4) == "o4"
    for n in range(asp.MIN_OBJECTS, asp.MAX_OBJECTS + 1):
        assert 1 <= int(asp.pointed_object(n)[1:]) <= n


def test_asp_runs_with_four_objects() -> None:
    rc, out, err = _run("asp.py", "--objects", "4", "--repeat", "1")
    assert rc == 0, err
    assert "pointed(o4)" in out


def test_p90_is_never_under_the_median() -> None:
    agent = _load("agent")
    for times in ([1.0, 2.0], [5.0], [3.0, 1.0, 2.0], [1.0] * 9 + [100.0]):
        assert agent.p90(times) >= statistics.median(times)
    assert agent.p90([1.0, 2.0]) == pytest.approx(1.9)


class _Interp:
    """Lessons 'run' by sleeping, each result with its `correct`: True, False or None (the
    trainer could not judge)."""

    def __init__(self, plan: list[tuple[float, bool | None]]) -> None:
        self.plan = plan

    def run(self, lesson, *, index: int, seed: int) -> SimpleNamespace:
        pause, correct = self.plan[index - 1]
        time.sleep(pause)
        return SimpleNamespace(correct=correct)


def test_timed_counts_right_of_the_judged_and_its_p90_is_not_the_fastest() -> None:
    agent = _load("agent")
    plan = [(0.0, True), (0.03, None), (0.0, False)]
    median, p90, right, judged = [c.strip() for c in agent.timed(_Interp(plan), [None] * 3, 0).split("|")]
    assert right == "1/2" and judged == "2/3"
    assert float(p90) >= float(median)
    median, p90, _r, _j = agent.timed(_Interp([(0.0, True), (0.03, True)]), [None] * 2, 0).split("|")
    assert float(p90) >= float(median) > 0.0  # of two times, the p90 is no longer the faster one


def test_agent_asks_only_about_words_it_was_taught() -> None:
    agent = _load("agent")
    from aileen.experiments.protocol import lesson_words, make_trial

    trial = make_trial("spatial", 0)
    taught = agent.taught_words(trial.prerequisites + trial.lessons)
    assert {"red", "box", "left of"} <= taught and "capsule" not in taught
    for n in (1, 2, 4):
        lessons = agent.lessons_with(n, 40, 7, taught)
        assert len(lessons) == 40
        for lesson in lessons:
            assert lesson_words(lesson) <= taught, lesson.content
            assert all(o.shape != "capsule" for o in lesson.objects)


@pytest.mark.skipif(importlib.util.find_spec("soar_sml") is not None, reason="the soar extra is installed")
def test_soar_without_its_extra_says_how_to_install_it() -> None:
    from aileen.soar.kernel import INSTALL_HINT

    rc, _out, err = _run("soar.py", "--react-tasks", "0")
    assert _refused(rc, err, INSTALL_HINT) is None, err


def test_teacher_sim_says_n_a_for_a_family_without_samples() -> None:
    teacher_sim = _load("teacher_sim")
    assert teacher_sim.show(teacher_sim.ratio(0.0, 0.0)) == "n/a"
    assert teacher_sim.show(teacher_sim.ratio(1.0, 4.0)) == "0.2"
    for script, args in (("teacher_sim.py", ("--trials", "3")), ("grain_frontier.py", ("--trials", "1"))):
        rc, out, err = _run(script, *args)
        assert rc == 0, err
        assert err == "", f"{script}: {err}"  # no RuntimeWarning
        assert "nan" not in out, out


def test_sentences_help_describes_it_instead_of_running() -> None:
    rc, out, err = _run("sentences.py", "--help")
    assert rc == 0, err
    assert out.startswith("usage:") and "sentence length" in out
    assert "words:" not in out  # no figure ("parse    2 words: ..."): the benchmark did not run


def test_original_scripts_names_a_missing_folder() -> None:
    missing = ROOT / "no-such-folder-of-scripts"
    rc, _out, err = _run("original_scripts.py", str(missing))
    assert _refused(rc, err, str(missing)) is None, err


def test_memory_files_alone_below_its_sizes_is_refused() -> None:
    """`--largest 500 --only files` printed an empty table of the memory files and exit 0: part 5
    reads part 1's memories of 1,000 concepts or more (probe p3)."""
    rc, _out, err = _run("memory.py", "--largest", "500", "--only", "files")
    assert _refused(rc, err, "--only files", "1000") is None, err


def test_memory_measure_load_of_a_missing_file_is_refused_on_one_line(tmp_path) -> None:
    """`memory.py --measure-load /nonexist x` (part 5's child process) ended in a traceback, exit 1."""
    missing = tmp_path / "nonexist.json"
    rc, _out, err = _run("memory.py", "--measure-load", str(missing), "x")
    assert _refused(rc, err, str(missing), "no such memory file") is None, err


def test_sweep_refuses_an_address_that_is_no_address_before_any_work() -> None:
    """`sweep.py --address nonsense` ran the local sweeps first (39 s), then a traceback, exit 1."""
    rc, _out, err = _run("sweep.py", "--address", "nonsense", "--trials", "16", "--lessons", "1", "--repeat", "1")
    assert _refused(rc, err, "Ray") is None, (rc, err[-300:])


def test_perception_refuses_a_bad_detector_backend_on_one_line(monkeypatch) -> None:
    """`AILEEN_DETECTOR_BACKEND=bogus python benchmarks/perception.py`: a traceback, exit 1
    (`aileen run` says it on one line, exit 2)."""
    monkeypatch.setenv("AILEEN_DETECTOR_BACKEND", "bogus")
    rc, _out, err = _run("perception.py", "--repeats", "1", "--brief")
    assert _refused(rc, err, "AILEEN_DETECTOR_BACKEND", "bogus", "opencv") is None, (rc, err[-300:])


def test_sweep_says_a_line_under_noise_measures_nothing(monkeypatch, capsys) -> None:
    """One run per size, the Ray sweep of 16 trials faster than that of 8 (noise): the script
    printed "-2.615 s per trial" and "-1336.5 % (target <= 10 %)"."""
    bench = _load("sweep")
    assert bench.fit([15.83], [17.53], 8, 16).why is not None  # one run per size: noise unknown
    assert "no longer" in bench.fit([80.61, 81.0], [59.68, 60.0], 8, 16).why
    assert "differ by" in bench.fit([10.0, 13.0], [12.0, 12.5], 8, 16).why
    # the local pool's line at a load average of 5: "fixed -0.34 s + 0.579 s per trial"
    assert "below 0" in bench.fit([4.29, 8.81], [13.56, 18.14], 8, 24).why
    good = bench.fit([10.0, 10.1], [12.0, 12.2], 8, 16)
    assert good.why is None and abs(good.per - 0.25) < 1e-9 and abs(good.fixed - 8.0) < 1e-9
    walls = {("local", 8): 15.83, ("local", 16): 17.53, ("ray", 8): 80.61, ("ray", 16): 59.68}
    monkeypatch.setattr(bench, "_run", lambda backend, n, *a: (walls[backend, n], b"same"))
    from aileen.experiments import ray_backend

    monkeypatch.setattr(ray_backend, "preflight", lambda address: None)
    monkeypatch.setattr(sys, "argv", ["sweep.py", "--trials", "16", "--repeat", "1"])
    bench.main()
    out = capsys.readouterr().out
    assert "-2.615" not in out and "%" not in out and "target <= 10" not in out, out
    assert out.count("not measurable at this size (noise)") == 3 and "(best of 1 repeat)" in out, out


def test_memory_times_the_steady_state_not_the_first_call(monkeypatch) -> None:
    """With `--repeat 1` the first query after building a memory (122 ms: its index and caches
    filled) was printed as the query's time (0.3-0.45 ms after)."""
    memory = _load("memory")
    clock = [0.0]
    calls: list[int] = []

    def call() -> None:  # the first call costs 100 "seconds", every later one 1
        clock[0] += 100.0 if not calls else 1.0
        calls.append(1)

    monkeypatch.setattr(memory.time, "perf_counter", lambda: clock[0])
    assert memory.timed(call, 1) == 1.0 and len(calls) == 2
    calls.clear()
    assert memory.timed(call, 1, warm=False) == 100.0  # a first time on purpose


def test_memory_prints_its_parts_in_order(monkeypatch, capsys) -> None:
    """Part 5 (the memory file, measured on part 1's memories) was printed right after part 1."""
    memory = _load("memory")
    monkeypatch.setattr(memory, "bench_concepts", lambda sizes, repeat, keep=(): print("part 1") or {})
    monkeypatch.setattr(memory, "bench_files", lambda kept, repeat, say=print: say("part 5"))
    for part, name in ((2, "bench_cycle"), (3, "bench_examples"), (4, "bench_scene")):
        monkeypatch.setattr(memory, name, lambda sizes, repeat, part=part: print(f"part {part}"))
    monkeypatch.setattr(sys, "argv", ["memory.py", "--quick", "--repeat", "1"])
    memory.main()
    said = [line for line in capsys.readouterr().out.splitlines() if line.startswith("part")]
    assert said == ["part 1", "part 2", "part 3", "part 4", "part 5"]


def test_memory_cycle_says_the_size_it_was_asked_for(capsys) -> None:
    """docs/concept-memory.md's table read 16/106/1,006 visual concepts, the script 14/104/1004
    for the same sizes: it counted after the cycles, whose informs add a word each."""
    import warnings

    memory = _load("memory")
    with warnings.catch_warnings():  # (a growth exponent of one size: numpy says it is ill-posed)
        warnings.simplefilter("ignore")
        memory.bench_cycle([10], 1)
    rows = [line for line in capsys.readouterr().out.splitlines() if line.split(" ")[0].isdigit()]
    assert rows and rows[0].startswith("10 |"), rows


def test_assimilation_keeps_its_columns_in_line_on_long_rows() -> None:
    """The rows of lessons/relations.toml ("r_larger_than same sector") pushed their figures
    out of the columns the other rows kept."""
    assim = _load("assimilation")
    lines = assim.table([("spatial (wide)", "other sector", [0.3, 0.4]),
                         ("visual + spatial (wide, visual trials)", "visual", [0.75]),
                         ("lessons/relations.toml", "r_larger_than same sector", [0.398])])
    assert len({line.index("pairs") for line in lines}) == 1 and len({line.index("median") for line in lines}) == 1


def test_teacher_sim_blind_observer_finds_the_axis_from_its_examples() -> None:
    """The diagnostic learner not told a word's axis: examples about west (within 20 degrees)
    are read as a word about west, held on the axis and refused east and north; a near miss
    just past 30 degrees bounds it on that side."""
    teacher_sim = _load("teacher_sim")
    learner = teacher_sim.MixtureIdeal(teacher_sim.blind_hypotheses(step=0.5))
    assert not learner.says(180.0)  # nothing seen: no
    for a in (168.0, 175.0, 186.0, 193.0):
        learner.inform(a)
    assert learner.says(180.0) and learner.says(200.0)
    assert not learner.says(0.0) and not learner.says(90.0) and not learner.says(135.0)
    learner.near_miss(215.0)
    assert not learner.says(212.0)
    generic = teacher_sim.MixtureIdeal(teacher_sim.symmetric_hypotheses(8, 90.0))
    for a in (40.0, 47.0, 52.0):  # about the north-east diagonal
        generic.inform(a)
    assert generic.says(45.0) and not generic.says(180.0) and not generic.says(225.0)


def test_teacher_sim_off_axis_adds_a_family_the_run_reports() -> None:
    rc, out, err = _run("teacher_sim.py", "--trials", "2", "--off-axis", "--symmetric", "8", "90")
    assert rc == 0, err
    assert "off-axis=" in out and "TEACHER=" in out, out


def test_perception_breakdown_times_its_parts_inside_the_same_calls(monkeypatch) -> None:
    """The breakdown timed perceive(), detect() and the forward pass in separate loops: under
    load the rest of perceive() (10.46 ms) contradicted a detector of 10.74 ms around a 9.62 ms
    forward pass. Timed inside the same calls (a clock that calls advance), the parts add up."""
    bench = _load("perception")
    now = [0.0]

    class Det:
        def raw(self) -> None:
            now[0] += 0.009 if len(calls) % 2 else 0.003  # a busy moment every other call

        def detect(self) -> None:
            self.raw()
            now[0] += 0.001

    det = Det()
    calls: list[int] = []

    def perceive_once() -> None:
        calls.append(1)
        det.detect()
        now[0] += 0.0005

    monkeypatch.setattr(bench, "time", SimpleNamespace(perf_counter=lambda: now[0]))
    parts = bench.parts_in_the_same_calls(perceive_once, det, 3)
    assert parts["raw"] == pytest.approx(9.0)
    assert parts["detect"] == pytest.approx(10.0)
    assert parts["total"] == pytest.approx(10.5)
    assert parts["rest"] == pytest.approx(1.5)
    assert "raw" not in vars(det) and "detect" not in vars(det)  # the detector is left as it was


def test_assimilation_counts_examples_without_a_direction_in_no_sector() -> None:
    """Two examples of "near" that hold no CDC fact (as lessons/relations.toml's stored before
    345bd93) were printed as a pair in the same sector; a pair in which either has none is in
    no sector, and examples with their CDC facts are still told apart by them."""
    assim = _load("assimilation")
    from aileen.terms import as_terms

    near1 = as_terms(["r_near(o1,o2)", "qd_close(o1,o2)"])
    near2 = as_terms(["r_near(o3,o4)", "qd_close(o3,o4)", "dc(o3,o4)"])
    west = as_terms(["r_left_of(o1,o2)", "w(o1,o2)", "e(o2,o1)"])
    west2 = as_terms(["r_left_of(o3,o4)", "w(o3,o4)", "e(o4,o3)", "dc(o3,o4)"])
    south_west = as_terms(["r_left_of(o1,o2)", "sw(o1,o2)", "ne(o2,o1)"])
    assert assim.sectors(near1, near2) == "no sector"
    assert assim.sectors(near1, west) == "no sector"
    assert assim.sectors(west, west2) == "same sector"
    assert assim.sectors(west, south_west) == "other sector"


def test_the_scale_benchmarks_say_the_hosts_speed_before_their_figures(monkeypatch, capsys) -> None:
    """The same code timed 2.0x slower on the same host from one day to the next: the sweep
    benchmark (and memory.py, perception.py) print the host's cores, load and the time of a
    fixed piece of work first, so a figure is read beside the speed it was measured at."""
    import re

    bench = _load("sweep")
    monkeypatch.setattr(bench, "_run", lambda backend, n, *a: ({8: 10.0, 16: 11.0}[n], b"same"))
    from aileen.experiments import ray_backend

    monkeypatch.setattr(ray_backend, "preflight", lambda address: None)
    monkeypatch.setattr(sys, "argv", ["sweep.py", "--trials", "16", "--repeat", "1"])
    bench.main()
    first = capsys.readouterr().out.splitlines()[0]
    found = re.fullmatch(r"host: (\d+) cores, load average [\d.]+, reference work (\d+) ms \(.*\)", first)
    assert found is not None, first
    assert int(found.group(1)) == os.cpu_count() and int(found.group(2)) > 0
