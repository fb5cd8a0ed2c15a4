"""`aileen experiment sweep`: the grid file, the CSV and its resumption, failures, the heat map."""

from __future__ import annotations

import csv
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from sweep_helpers import flaky as _flaky

from aileen.cli import main
from aileen.errors import UserError
from aileen.experiments import sweep
from aileen.experiments.grid import load_grid, parse_grid
from aileen.experiments.local_backend import run_local

TINY = """experiment = "visual"
trials = 1
seeds = [0]
perception = "truth"
lessons = 1
[params]
match = [0.5, 0.75]
"""


def _rows(path: Path) -> list[dict[str, str]]:
    with path.open(newline="") as fh:
        return list(csv.DictReader(fh))


# --------------------------------------------------------------------------- the grid file

def test_grid_points_are_the_product_of_the_axes() -> None:
    g = parse_grid("""experiment = ["visual", "spatial"]
trials = 2
seeds = [0, 1, 2]
without = [[], ["mutual-exclusivity"]]
[params]
assimilation = [0.01, 0.6]
match = [0.5, 0.65, 0.75]
""")
    pts = g.points()
    assert len(pts) == 2 * 2 * 2 * 3
    assert {p.probability for p in pts} == {0.6}  # not swept: the paper's value
    assert pts[0].sage().assimilation == 0.01 and pts[-1].sage().match == 0.75
    assert len(sweep.jobs_of(g)) == len(pts) * 3 * 2
    assert g.heatmap_axes() == ("assimilation", "match")


@pytest.mark.parametrize(("text", "line", "words"), [
    ('experiment = "visual"\ncolour = 3\n', 2, "unknown key 'colour'"),
    ('experiment = "visual"\n[params]\nassimilation = [0.1]\nthreshold = [0.5]\n', 4, "unknown SAGE parameter"),
    ('experiment = "visual"\n[params]\nmatch = [0.5, 1.5]\n', 3, "out of range"),
    ('experiment = "visual"\n[params]\nmatch = []\n', 3, "non-empty"),
    ('experiment = "visual"\nseeds = []\n', 2, "non-empty"),
    ('experiment = "visual"\nwithout = [["telepathy"]]\n', 2, "unknown mechanism"),
    ('experiment = "chess"\n', 1, "unknown experiment"),
    ('experiment = "repertoire"\n', 1, "the paper protocol has no repertoire"),  # every trial failed
    ('experiment = "visual"\nprotocol = ["wide", "teacher"]\n', 2, "the teacher protocol has no visual"),
    ('experiment = "visual"\nprotocol = "chess"\n', 2, "unknown protocol"),
    ('experiment = ["visual", "visual"]\n', 1, "repeats"),
    ('experiment = "visual"\ntrials = 0\n', 2, "positive integer"),
    # it built its list of trials until the memory ran out
    ('experiment = "visual"\ntrials = 99999999999999999999999\n', 2, "at most 100000"),
    ('experiment = "visual"\n[params]\nmatch = [0.5, 0.5]\n', 3, "repeats"),
    ('experiment = "visual"\n[heatmap]\nx = "match"\ny = "colour"\n', 4, "not an axis"),
    ('experiment = "visual"\ntrials = [\n', 2, "not valid TOML"),
    # the other ways TOML writes a key (they named the file but no line)
    ('experiment = "visual"\nparams.match = [2.0]\n', 2, "out of range"),
    ('experiment = "visual"\nparams = {assimilation = [0.1], match = [2.0]}\n', 2, "out of range"),
    ('experiment = "visual"\n"trials" = 0\n', 2, "positive integer"),
    ('experiment = "visual"\n[[params]]\nmatch = [0.5]\n', 2, "must be a table"),
])
def test_bad_grid_is_a_file_line_error(tmp_path, text, line, words) -> None:
    path = tmp_path / "grid.toml"
    path.write_text(text)
    with pytest.raises(UserError) as err:
        load_grid(path)
    assert err.value.path == str(path) and err.value.line == line, err.value.format()
    assert words in err.value.message


@settings(max_examples=40, deadline=None)
@given(st.lists(st.sampled_from([0.0, 0.01, 0.3, 0.5, 0.75, 1.0]), min_size=1, max_size=4, unique=True),
       st.lists(st.integers(0, 50), min_size=1, max_size=3, unique=True), st.integers(1, 3))
def test_any_valid_grid_parses_to_its_points(values, seeds, trials) -> None:
    g = parse_grid(f"experiment = \"spatial\"\ntrials = {trials}\nseeds = {seeds}\n[params]\nmatch = {values}\n")
    assert [p.match for p in g.points()] == [float(v) for v in values]
    assert len(sweep.jobs_of(g)) == len(values) * len(seeds) * trials


# --------------------------------------------------------------------------- running

@pytest.fixture(scope="module")
def tiny_run(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("sweep")
    (out / "grid.toml").write_text(TINY)
    rep = sweep.run_sweep(load_grid(out / "grid.toml"), out, plot=False)
    assert rep.ran == 2 and not rep.failures
    return out


def test_sweep_writes_one_row_per_trial_and_a_summary_per_point(tiny_run: Path) -> None:
    rows = _rows(tiny_run / "sweep.csv")
    assert [(r["match"], r["seed"], r["trial"]) for r in rows] == [("0.5", "0", "1"), ("0.75", "0", "1")]
    for r in rows:
        assert set(sweep.HEADER) == set(r)
        assert 0 <= float(r["area_pct_oracle"]) <= 100
        assert len(r["generality"].split()) == 1
        assert int(r["min_specificity"]) in range(6)
    summary = _rows(tiny_run / "sweep-summary.csv")
    assert [s["match"] for s in summary] == ["0.5", "0.75"]
    assert all(s["trials"] == "1" for s in summary)


def test_a_sweep_run_again_skips_what_is_done_and_redoes_what_is_missing(tiny_run: Path, tmp_path) -> None:
    before = (tiny_run / "sweep.csv").read_text()
    rep = sweep.run_sweep(load_grid(tiny_run / "grid.toml"), tiny_run, plot=False)
    assert (rep.ran, rep.skipped) == (0, 2)
    assert (tiny_run / "sweep.csv").read_text() == before
    # a run stopped after its first trial (and half a line): only the second trial runs again
    lines = before.splitlines(keepends=True)
    (tmp_path / "grid.toml").write_text(TINY)
    (tmp_path / "sweep.csv").write_text(lines[0] + lines[1] + lines[2][:15])
    rep = sweep.run_sweep(load_grid(tmp_path / "grid.toml"), tmp_path, plot=False)
    assert (rep.ran, rep.skipped) == (1, 1)
    assert (tmp_path / "sweep.csv").read_text() == before


def test_a_foreign_csv_is_refused(tmp_path) -> None:
    (tmp_path / "grid.toml").write_text(TINY)
    (tmp_path / "sweep.csv").write_text("a,b\n1,2\n")
    with pytest.raises(UserError, match="columns differ"):
        sweep.run_sweep(load_grid(tmp_path / "grid.toml"), tmp_path, plot=False)


def _jobs(matches: list[float]) -> list[sweep.Job]:
    grid = parse_grid(f'experiment = "visual"\nperception = "truth"\n[params]\nmatch = {matches}\n')
    return sweep.jobs_of(grid)


def test_a_trial_that_raises_is_reported_with_its_point_and_the_rest_go_on() -> None:
    done, failed = [], []
    run_local(_jobs([0.5, 0.7]), 1, _flaky, lambda j, r: done.append(r), lambda j, why: failed.append((j, why)))
    assert done == [{"match": "0.7"}]
    assert len(failed) == 1 and failed[0][1] == "RuntimeError: no luck"
    assert "match=0.5" in failed[0][0].label() and "trial 1" in failed[0][0].label()


@pytest.mark.slow  # spawns worker processes, and fresh ones to find the trial that killed its worker
def test_a_worker_that_dies_is_reported_and_the_rest_go_on() -> None:
    done, failed = [], []
    run_local(_jobs([0.6, 0.7]), 2, _flaky, lambda j, r: done.append(r["match"]),
              lambda j, why: failed.append((j.point.match, why)))
    assert done == ["0.7"]
    assert failed == [(0.6, "the worker process died")]


def test_heat_map_over_two_axes(tmp_path) -> None:
    pytest.importorskip("matplotlib")
    (tmp_path / "grid.toml").write_text(TINY.replace("match = [0.5, 0.75]",
                                                     "match = [0.5, 0.75]\nassimilation = [0.01, 0.6]"))
    rep = sweep.run_sweep(load_grid(tmp_path / "grid.toml"), tmp_path, plot=True)
    assert rep.ran == 4
    png = tmp_path / "heatmap.png"
    assert png in rep.files and png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_cli_bad_grid_is_one_line_and_exit_2(tmp_path, capsys) -> None:
    path = tmp_path / "g.toml"
    path.write_text('experiment = "visual"\n[params]\nmatch = [2.0]\n')
    assert main(["experiment", "sweep", str(path), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and f"{path}:3:" in err
    assert main(["experiment", "sweep", "--out", str(tmp_path / "o")]) == 2
    assert main(["experiment", "sweep", str(path), "--trials", "3"]) == 2  # the grid file says
    assert main(["experiment", "sweep", str(path), "--perception", "truth"]) == 2
    assert main(["experiment", "visual", str(path)]) == 2


@given(st.integers(0, 300), st.integers(1, 64))
def test_ray_tasks_take_consecutive_trials_in_even_runs(n: int, workers: int) -> None:
    from aileen.experiments.ray_backend import MAX_CHUNK, chunks

    jobs = list(range(n))
    parts = chunks(jobs, workers)
    assert [j for p in parts for j in p] == jobs  # each trial once, in grid order
    assert all(1 <= len(p) <= MAX_CHUNK for p in parts)
    assert all(len(p) == len(parts[0]) for p in parts[:-1])  # only the last may be short
    assert len(parts) >= min(n, workers)  # no worker left without a task it could take


@pytest.mark.parametrize("flag", [["--agent", "soar"], ["--senses", "all"], ["--baselines"]])
def test_a_flag_a_sweep_does_not_take_is_refused(tmp_path, capsys, flag) -> None:
    """These were left out without a word (and --protocol too: every sweep ran the paper's)."""
    path = tmp_path / "grid.toml"
    path.write_text('experiment = "visual"\n')
    assert main(["experiment", "sweep", str(path), "--out", str(tmp_path / "o"), *flag]) == 2
    assert f"{flag[0]} is not for a sweep" in capsys.readouterr().err
    assert main(["experiment", "sweep", str(path), "--out", str(tmp_path / "o"), "--protocol", "wide"]) == 2
    assert "--protocol is set in the grid file" in capsys.readouterr().err


def test_the_protocol_is_an_axis_and_its_trials_follow_it(tmp_path) -> None:
    """`protocol = ["paper", "wide"]`: one point each; the wide protocol's trial is the one
    `aileen experiment visual` (wide) runs, the paper's the paper's."""
    from aileen.experiments.trial import run_trial

    (tmp_path / "grid.toml").write_text(TINY.replace("match = [0.5, 0.75]", "match = [0.75]")
                                        .replace('experiment = "visual"', 'experiment = "visual"\nprotocol = ["paper", "wide"]'))
    rep = sweep.run_sweep(load_grid(tmp_path / "grid.toml"), tmp_path, plot=False)
    rows = _rows(tmp_path / "sweep.csv")
    assert rep.ran == 2 and [r["protocol"] for r in rows] == ["paper", "wide"]
    for r in rows:
        want = run_trial("visual", 0, 0, perception="truth", lessons=1, protocol=r["protocol"])
        assert r["generality"] == " ".join(str(x.generality) for x in want.records)
        assert r["specificity"] == " ".join(str(x.specificity) for x in want.records)


@pytest.mark.parametrize("header", ["HEADER_BEFORE_PROTOCOL", "HEADER_BEFORE_BALANCED"])
def test_an_older_sweep_csv_is_read_and_written_in_todays_columns(tiny_run: Path, tmp_path, header: str) -> None:
    # before the protocol axis (read as the paper's) and before the balanced area (computed
    # from the row's lessons and its protocol's exam sizes): the same file as a sweep run now
    columns = getattr(sweep, header)
    rows = sweep.read_rows(tiny_run / "sweep.csv")
    old = sweep.csv_text([{k: v for k, v in r.items() if k in columns} for r in rows], columns)
    (tmp_path / "sweep.csv").write_text(old)
    (tmp_path / "grid.toml").write_text(TINY)
    rep = sweep.run_sweep(load_grid(tmp_path / "grid.toml"), tmp_path, plot=False)
    assert (rep.ran, rep.skipped) == (0, 2)
    assert (tmp_path / "sweep.csv").read_text() == (tiny_run / "sweep.csv").read_text()


def test_a_sweep_reports_the_balanced_area_beside_generality(tiny_run: Path) -> None:
    # the headline figure: a sweep gave the generality area alone
    from aileen.experiments.results import Areas

    rows = sweep.read_rows(tiny_run / "sweep.csv")
    for r in rows:
        gen = [int(x) for x in r["generality"].split()]
        spec = [int(x) for x in r["specificity"].split()]
        n = len(gen) * 5
        want = Areas(sum(gen) / n, sum(spec) / n, int(r["oracle_sum"]) / n).pct_oracle()
        assert r["exam_items"] == "5 5" and float(r["balanced_pct_oracle"]) == pytest.approx(want, abs=1e-3)
    summary = (tiny_run / "sweep-summary.csv").read_text().splitlines()
    assert summary[0].split(",")[-1] == "balanced_pct_oracle" and all(line.split(",")[-1] for line in summary[1:])



def test_an_out_folder_that_cannot_be_made_is_a_one_line_error(tmp_path, capsys) -> None:
    path = tmp_path / "grid.toml"
    path.write_text('experiment = "visual"\n')
    afile = tmp_path / "afile"
    afile.write_text("x")
    assert main(["experiment", "sweep", str(path), "--out", str(afile / "sub")]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "cannot create the folder" in err


def test_a_row_after_a_cut_line_and_a_row_written_twice_are_each_read_once(tiny_run: Path, tmp_path) -> None:
    """A run stopped mid-line, then resumed: the next row went onto the cut line and was lost
    (when the run stopped again before the final rewrite). Two sweeps into one folder wrote
    trials twice, and the points counted them twice."""
    lines = (tiny_run / "sweep.csv").read_text().splitlines(keepends=True)
    path = tmp_path / "sweep.csv"
    path.write_text(lines[0] + lines[1] + lines[2][:15])
    app = sweep.Appender(path, existing=True)
    app.add(sweep.read_rows(tiny_run / "sweep.csv")[1])
    app.close()
    assert [r["match"] for r in sweep.read_rows(path)] == ["0.5", "0.75"]
    path.write_text(lines[0] + lines[1] + lines[1] + lines[2])
    assert [r["match"] for r in sweep.read_rows(path)] == ["0.5", "0.75"]


def test_a_grid_run_into_another_grids_folder_summarises_its_own_trials(tiny_run: Path, tmp_path) -> None:
    out = tmp_path / "o"
    out.mkdir()
    (out / "sweep.csv").write_text((tiny_run / "sweep.csv").read_text())
    (out / "grid.toml").write_text(TINY.replace("match = [0.5, 0.75]", "match = [0.75]").replace("seeds = [0]",
                                                                                              "seeds = [0, 1]"))
    rep = sweep.run_sweep(load_grid(out / "grid.toml"), out, plot=False)
    assert (rep.ran, rep.skipped) == (1, 1)  # seed 1 ran; seed 0 was done (the 0.5 row is not this grid's)
    assert [s.trials for s in rep.summary] == [2]
    assert rep.others == 1  # said at the command line: the folder holds another grid's trial


def test_an_address_where_something_else_answers_is_one_clear_error() -> None:
    """A web server on the port: Ray retried for minutes; the check asks for HTTP/2 (gRPC),
    which Ray's head speaks, and a server that answers so passes."""
    import http.server
    import socket
    import threading

    from aileen.experiments.ray_backend import check_reachable

    web = http.server.HTTPServer(("127.0.0.1", 0), http.server.BaseHTTPRequestHandler)
    threading.Thread(target=web.serve_forever, daemon=True).start()
    try:
        with pytest.raises(UserError, match="not as a Ray cluster's head"):
            check_reachable(f"127.0.0.1:{web.server_address[1]}")
    finally:
        web.shutdown()
    h2 = socket.create_server(("127.0.0.1", 0))

    def answer() -> None:
        conn, _ = h2.accept()
        with conn:
            conn.recv(64)
            conn.sendall(b"\x00\x00\x00\x04\x00\x00\x00\x00\x00")  # an empty SETTINGS frame

    threading.Thread(target=answer, daemon=True).start()
    check_reachable(f"127.0.0.1:{h2.getsockname()[1]}")
    h2.close()


def test_a_stopped_sweep_says_the_same_command_runs_the_rest(tmp_path, monkeypatch, capsys) -> None:
    from aileen import lifecycle
    from aileen.cli import main

    def stopped(*a, **kw):  # noqa: ANN002, ANN003 - a stop signal in the middle of the trials
        raise lifecycle.Stopped(2)

    monkeypatch.setattr(sweep, "run_sweep", stopped)
    (tmp_path / "grid.toml").write_text(TINY)
    assert main(["experiment", "sweep", str(tmp_path / "grid.toml"), "--out", str(tmp_path / "o"), "--quiet"]) == 130
    err = capsys.readouterr().err
    assert "stopped by SIGINT; the trials that finished are in" in err and "the same command runs the rest" in err


@pytest.mark.parametrize("out", ["", "sj"])
def test_an_out_folder_the_summary_cannot_be_written_in_is_refused_before_any_trial(tmp_path, capsys, monkeypatch,
                                                                                   out) -> None:
    """`--out ''` wrote into the current folder; a summary.json that is a folder was an
    IsADirectoryError once every trial had run."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "sj" / "summary.json").mkdir(parents=True)
    assert main(["experiment", "visual", "--trials", "1", "--lessons", "1", "--out", out, "--no-plot"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "--out" in err and not (tmp_path / "visual").exists()


def test_a_damaged_count_in_sweep_csv_runs_that_trial_again_and_a_foreign_summary_is_written_anew(tmp_path) -> None:
    """A sum edited to "x" was a ValueError traceback; a summary.json holding [1, 2] a TypeError."""
    import json

    from aileen.experiments import sweep_csv
    from aileen.experiments.tables import update_summary_json

    path = tmp_path / "sweep.csv"
    row = {k: "0" for k in sweep_csv.HEADER}
    row.update(experiment="visual", protocol="paper", specificity="5 5", exam_items="5 5", generality="1 2")
    bad = {**row, "trial": "1", "generality_sum": "x"}
    path.write_text(sweep_csv.csv_text([row, bad], sweep_csv.HEADER))
    rows = sweep_csv.read_rows(path)
    assert len(rows) == 1 and rows[0]["generality_sum"] == "0"
    (tmp_path / "summary.json").write_text("[1, 2]")
    update_summary_json(tmp_path, "visual", {"a": 1})
    assert json.loads((tmp_path / "summary.json").read_text()) == {"visual": {"a": 1}}


def test_the_heat_map_shows_the_balanced_area(tmp_path, monkeypatch) -> None:
    """It showed the generality area alone: 100.0 in every cell where the specificity it cost
    differed."""
    from aileen.experiments import plots

    g = parse_grid('experiment = "visual"\ntrials = 1\nseeds = [0]\n[params]\nmatch = [0.5, 0.75]\n'
                   'probability = [0.6, 0.8]\n')
    rows = []
    for k, job in enumerate(sweep.jobs_of(g)):
        row = {h: "0" for h in sweep.HEADER}
        row.update(sweep._key_values(job), generality_sum="10", oracle_sum="10", generality="5 5",
                   specificity=f"{5 - k} {5 - k}", exam_items="5 5")
        rows.append(row)
    seen: dict = {}
    monkeypatch.setattr(plots, "plot_heatmap", lambda cells, x, y, path, title: seen.update(cells=cells, title=title))
    sweep.write_results(g, tmp_path, rows, plot=True)
    sums = sweep.summarise(g.points(), rows)
    assert sorted(seen["cells"].values()) == sorted(s.balanced_pct_oracle for s in sums)
    assert len(set(seen["cells"].values())) == 4 and seen["title"].startswith("balanced")


def test_an_address_that_is_no_address_is_refused_before_anything_runs(tmp_path, capsys) -> None:
    """`--address nonsense` passed the check (no port: left to Ray), and Ray refused it only when
    the trials were to start: the benchmark had run its local sweeps first (39 s), a traceback."""
    from aileen.experiments.ray_backend import check_reachable

    with pytest.raises(UserError, match="expected HOST:PORT"):
        check_reachable("nonsense")
    for fine in ("auto", "local", "ray://head"):
        check_reachable(fine)  # Ray's own to read


def test_a_refused_ray_sweep_leaves_no_folder_and_no_csv(tmp_path, monkeypatch, capsys) -> None:
    """A refused `experiment sweep --backend ray` left its --out folder with a sweep.csv of
    the header alone."""
    from aileen.experiments import ray_backend

    def refused(*a, **kw):  # noqa: ANN002, ANN003 - a Ray that would not start
        raise UserError("cannot start or reach a local Ray: no")

    monkeypatch.setattr(ray_backend, "preflight", lambda address: None)
    monkeypatch.setattr(ray_backend, "run_jobs", refused)
    (tmp_path / "grid.toml").write_text(TINY)
    out = tmp_path / "o"
    assert main(["experiment", "sweep", str(tmp_path / "grid.toml"), "--out", str(out), "--backend", "ray",
                 "--quiet"]) == 2
    assert not out.exists()
    out.mkdir()  # a folder of one's own is kept, and nothing written into it but the lock
    assert main(["experiment", "sweep", str(tmp_path / "grid.toml"), "--out", str(out), "--backend", "ray",
                 "--quiet"]) == 2
    from aileen.experiments.output import LOCK_NAME  # (never removed: another run may hold it, as memory files' locks)

    assert out.is_dir() and [p.name for p in out.iterdir()] in ([], [LOCK_NAME])
