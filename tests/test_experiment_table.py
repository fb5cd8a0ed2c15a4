"""`aileen experiment`'s printed table: the balanced headline never read alone as good where
generality is far below the oracle, an undefined figure spelled one way, and what ran said."""

from __future__ import annotations

from aileen.experiments.commands import format_table
from aileen.experiments.results import all_no_pct_oracle

ROW = {"experiment": "visual", "trials": 1, "lessons": 2, "holds_from": None, "final_generality": 0.0,
       "lowest_specificity": 5.0, "commands_per_trial": 4.0, "area_pct_of_oracle": 0.0,
       "balanced_pct_oracle": 80.0, "balanced_pct_ideal": None, "wall_s": 1.0, "oracle_area": 2.5,
       "exam_items": [5, 5]}


def test_a_learner_that_says_no_to_everything_scores_100_over_one_plus_the_oracle() -> None:
    assert all_no_pct_oracle(2.5, 2, 5) == 80.0  # the oracle at a quarter of full marks
    assert all_no_pct_oracle(10.0, 2, 5) == 50.0  # at full marks from the first lesson


def test_a_balanced_headline_high_from_specificity_alone_is_said_under_the_table() -> None:
    # a --without size-principle row with generality 0 % of the oracle showed balanced 80 %
    # with nothing beside it to say why
    table = format_table([ROW])
    head, row, note = table.splitlines()
    cells = [c.strip() for c in row.split("|")]
    assert cells[head.split(" | ").index("area % oracle")] == "0.0"  # generality beside balanced
    assert cells[head.split(" | ").index("balanced % oracle")] == "80.0"
    assert note == ("note: visual: balanced 80.0 % is high from specificity alone (generality 0.0 % of the "
                    "oracle): a learner that says no to everything scores 80.0 % here")
    fine = format_table([{**ROW, "area_pct_of_oracle": 95.0, "balanced_pct_oracle": 97.0}])
    assert "note:" not in fine and len(fine.splitlines()) == 2


def test_an_undefined_figure_is_a_dash_in_the_table() -> None:
    # it printed None in the table, nan in the plot's title and nothing in areas.csv
    table = format_table([{**ROW, "area_pct_of_oracle": None, "final_generality": None,
                           "balanced_pct_oracle": None}])
    assert "None" not in table and "nan" not in table
    assert "| - | 5.0 | 4.0 | - | - | - |" in table


def test_the_table_says_the_protocol_and_perception_when_not_the_defaults() -> None:
    assert format_table([ROW], protocol="paper", perception="truth").splitlines()[0] == \
        "(paper protocol, perception truth)"
    assert format_table([ROW]).startswith("experiment |")


def test_an_undefined_figure_is_n_a_in_the_plots_title_and_a_dash_in_the_sweeps_table() -> None:
    # the plot's title read "nan", the sweep's table "nan"
    from aileen.experiments import runner, sweep
    from aileen.experiments.grid import Point
    from aileen.experiments.plots import curve_title

    res = runner.run_experiment("visual", trials=1, lessons=1, perception="truth")
    assert res.headline is not None
    res.headline = runner.Headline(**{**res.headline.__dict__, "area_pct_of_oracle": float("nan")})
    title = curve_title(res)
    assert "generality only: n/a % of the oracle" in title and "nan" not in title
    nan = float("nan")
    p = Point("visual", ("size-principle",), 0.8, 0.2, 0.75)
    table = sweep.format_summary([sweep.PointSummary(p, 1, nan, 4.0, 5.0, 0.0, nan),
                                  sweep.PointSummary(p, 1, 0.0, 4.0, 5.0, 0.0, 80.0)])
    assert "nan" not in table and "| - | - |" in table
    assert table.splitlines()[-1].startswith("note: visual (size-principle): balanced 80.0 % is high from "
                                             "specificity alone (generality 0.0 % of the oracle)")


def test_the_cpu_line_counts_this_process_and_its_workers_user_and_system() -> None:
    import os

    from aileen.experiments.commands import _cpu_line

    before = os.times_result((1.0, 0.5, 10.0, 1.0, 100.0))
    after = os.times_result((3.0, 1.0, 50.0, 3.0, 130.0))  # 2 + 0.5 own, 40 + 2 of the workers
    assert _cpu_line(before, after, 30.0, 2) == ("CPU time: 44.5 s in 30.0 s of wall time (this process and its "
                                                 "workers; 1.48 cores busy on average, 2 jobs)")
