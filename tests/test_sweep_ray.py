"""The Ray backend gives the same result files as the local one (Ray started locally for the
run, as `--backend ray` without `--address` does). Needs the `ray` extra."""

from __future__ import annotations

import pytest

pytest.importorskip("ray")

from aileen.errors import UserError  # noqa: E402
from aileen.experiments import sweep  # noqa: E402
from aileen.experiments.grid import load_grid  # noqa: E402

# A 2 x 1 grid, one trial each, the smallest protocol: the first lesson of a visual trial.
GRID = """experiment = "visual"
trials = 1
seeds = [0]
perception = "truth"
lessons = 1
[params]
assimilation = [0.01, 0.6]
match = [0.75]
"""


@pytest.mark.slow  # starts a local Ray (a few seconds on an idle machine)
def test_ray_and_local_backends_write_identical_files(tmp_path) -> None:
    files = {}
    for backend, jobs in (("local", 1), ("ray", 2)):
        out = tmp_path / backend
        out.mkdir()
        (out / "grid.toml").write_text(GRID)
        rep = sweep.run_sweep(load_grid(out / "grid.toml"), out, backend=backend, jobs=jobs, plot=False)
        assert rep.ran == 2 and not rep.failures, rep.failures
        files[backend] = [(out / n).read_bytes() for n in ("sweep.csv", "sweep-summary.csv")]
    assert files["ray"] == files["local"]
    assert files["local"][0].count(b"\n") == 3  # header + 2 trials


def test_an_unreachable_cluster_is_one_clear_error(tmp_path) -> None:
    (tmp_path / "grid.toml").write_text(GRID)
    with pytest.raises(UserError, match="cannot reach the Ray cluster at '127.0.0.1:1'"):
        sweep.run_sweep(load_grid(tmp_path / "grid.toml"), tmp_path, backend="ray", address="127.0.0.1:1",
                        plot=False)
    assert not (tmp_path / "sweep.csv").exists()  # nothing ran
