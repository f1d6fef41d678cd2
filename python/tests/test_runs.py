"""Runs, studies and reports from Python against the command line."""

import json
import time

import numpy as np
import pytest
from conftest import SHORT_THESIS, interrupt_after

import covga


def _summary(folder):
    s = json.loads((folder / "summary.json").read_text())
    s.pop("wall_s")
    return s


def test_run_from_python_writes_the_clis_files(tmp_path, cli, short_thesis):
    cli("run", short_thesis, "--seed", 9, "--quiet", "--out", tmp_path / "cli")
    result = covga.run(short_thesis, seed=9, out=tmp_path / "py")
    for name in ["history.csv", "best_path.csv", "best_genome.csv", "config.toml"]:
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    assert _summary(tmp_path / "py") == _summary(tmp_path / "cli")
    assert (tmp_path / "py" / "path.png").is_file()
    assert result.dir == tmp_path / "py"
    assert result.summary["seed"] == 9
    assert np.array_equal(result.path, result.plan[0]) and result.path.shape[1] == 2
    assert result.path[0].tolist() == [1.3, 1.3]


def test_a_folder_with_another_runs_files_is_refused_as_the_cli_refuses_it(tmp_path, cli, short_thesis):
    covga.run(short_thesis, seed=9, out=tmp_path / "py")
    before = sorted(p.name for p in (tmp_path / "py").iterdir())
    # The same experiment again is the same run: the folder is its own.
    covga.run(short_thesis, seed=9, out=tmp_path / "py")
    # Another seed is another run: refused, and the folder keeps the first run's files alone.
    with pytest.raises(covga.ConfigError, match="holds files of another run"):
        covga.run(short_thesis, seed=10, out=tmp_path / "py")
    assert sorted(p.name for p in (tmp_path / "py").iterdir()) == before
    (tmp_path / "cli").mkdir()
    (tmp_path / "cli" / "notes.txt").write_text("mine")
    with pytest.raises(covga.ConfigError, match="holds files of another run"):
        covga.run(short_thesis, out=tmp_path / "cli")
    assert [p.name for p in (tmp_path / "cli").iterdir()] == ["notes.txt"]


def test_text_dict_and_file_give_the_same_run(tmp_path, short_thesis):
    from_file = covga.run(short_thesis)
    from_text = covga.run(SHORT_THESIS)
    from_dict = covga.run(
        {
            "seed": 5,
            "planner": "thesis",
            "map": {"source": "thesis-1"},
            "thesis": {"pop_min": 30, "init_actions": 30},
            "budget": {"iterations": 40},
        }
    )
    for other in (from_text, from_dict):
        assert np.array_equal(other.path, from_file.path)
        assert other.summary["score"] == from_file.summary["score"]
    assert from_file.dir is None
    history = from_file.history
    assert list(history["iteration"]) == list(range(41))
    assert history["best_fitness"].dtype == np.float64


def test_a_dict_takes_numpy_numbers_and_paths_and_names_a_bad_value(tmp_path):
    plain = {"planner": "spiral", "map": {"source": "thesis-2"}, "robot": {"width": 0.6}, "seed": 3}
    numpy_typed = {
        "planner": "spiral",
        "map": {"source": "thesis-2"},
        "robot": {"width": np.float64(0.6)},
        "seed": np.int64(3),
        "stations": {"start": np.array([1.3, 1.3])},
    }
    a = covga.run(dict(plain, stations={"start": [1.3, 1.3]}), figures=False)
    b = covga.run(numpy_typed, figures=False)
    assert np.array_equal(a.path, b.path)
    (tmp_path / "m.pgm").write_bytes(b"P5\n20 20\n255\n" + bytes([254]) * 400)
    from_path = covga.run(
        {"planner": "spiral", "map": {"source": tmp_path / "m.pgm", "resolution": 0.2}, "stations": {"start": [1.0, 1.0]}},
        figures=False,
    )
    assert from_path.summary["score"]["executable"] is True
    with pytest.raises(covga.ConfigError, match="`robot.width` = nan: expected a finite number"):
        covga.run({"planner": "spiral", "robot": {"width": float("nan")}})
    with pytest.raises(covga.ConfigError, match="`thesis.pop_min` = .* of type object"):
        covga.run({"thesis": {"pop_min": object()}})


def test_patterns_and_fleets_run_with_one_path_per_agent(tmp_path):
    spiral = covga.run({"planner": "spiral", "map": {"source": "thesis-2"}}, figures=False)
    assert len(spiral.plan) == 1 and spiral.summary["score"]["executable"] is True
    fleet = covga.run(
        {
            "planner": "thesis",
            "map": {"source": "thesis-1"},
            "robots": [{"name": "a", "start": [1.3, 1.3]}, {"name": "b", "start": [9.7, 9.7]}],
            "fleet": {"mode": "central"},
            "thesis": {"pop_min": 20, "init_actions": 20},
            "budget": {"iterations": 5},
        }
    )
    assert len(fleet.plan) == 2
    assert fleet.plan[1][0].tolist() == [9.7, 9.7]


@pytest.mark.parametrize(
    "text,message",
    [
        ('planner = "thesis"\n[thesis]\np_ma = 2.0\n', "thesis.p_ma"),
        ('planner = "thesis"\n[thesis]\nbogus = 1\n', "unknown field `bogus`"),
        ('planner = "nope"\n', "unknown variant `nope`"),
        ('planner = "thesis"\n[map]\nsource = "nowhere.yaml"\n', "nowhere.yaml"),
        ("planner = ", "bad.toml:1: the TOML is incomplete at column 11"),
    ],
)
def test_bad_experiments_raise_the_clis_message(tmp_path, cli, text, message):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    done = cli("run", path, "--quiet", "--out", tmp_path / "never", check=False)
    assert done.returncode == 2
    with pytest.raises(covga.ConfigError) as e:
        covga.run(path, out=tmp_path / "never")
    assert message in str(e.value)
    assert str(e.value) in done.stderr
    assert not (tmp_path / "never").exists()


def test_bad_run_arguments_raise_config_error(short_thesis):
    with pytest.raises(covga.ConfigError, match="seed = -1 is out of range"):
        covga.run(short_thesis, seed=-1)
    with pytest.raises(covga.ConfigError, match="expected a TOML path, TOML text or a dict"):
        covga.run(42)
    with pytest.raises(covga.ConfigError, match="cannot read experiment file"):
        covga.run("no/such/file.toml")
    with pytest.raises(covga.ConfigError, match="experiment dict"):
        covga.run({"planner": "thesis", "map": {"source": None}})


def test_ignored_keys_warn(short_thesis):
    text = SHORT_THESIS.replace("init_actions = 30", "init_actions = 30\nkeep = 2")
    with pytest.warns(UserWarning, match="`thesis.keep` is ignored"):
        covga.run(text)


def test_a_renamed_key_warns_and_runs_as_its_new_name(tmp_path):
    old = SHORT_THESIS.replace("pop_min = 30", "pop_min = 30\nprojection = \"f1\"")
    new = SHORT_THESIS + '[scorer]\nprojection = "f1"\n'
    with pytest.warns(UserWarning, match="`thesis.projection` is now `scorer.projection`"):
        a = covga.run(old, out=tmp_path / "old", figures=False)
    b = covga.run(new, out=tmp_path / "new", figures=False)
    assert a.config == b.config and "[scorer]" in b.config
    assert a.summary["score"] == b.summary["score"]


def test_ctrl_c_stops_a_run_and_leaves_no_folder(tmp_path):
    long_run = {"planner": "thesis", "map": {"source": "thesis-1"}, "budget": {"iterations": 100000}}
    timer = interrupt_after(0.5)
    with pytest.raises(KeyboardInterrupt):
        covga.run(long_run, out=tmp_path / "stopped")
    timer.join()
    assert not (tmp_path / "stopped").exists()
    # The interpreter and the library go on as before.
    assert covga.run(SHORT_THESIS).summary["iterations"] == 40


GRID = """\
seed = 3
seeds = 2
[base]
planner = "thesis"
[base.map]
source = "thesis-1"
[base.thesis]
pop_min = 30
init_actions = 30
[base.budget]
iterations = 60
[axes]
"thesis.selection" = ["elite", "tournament"]
"scorer.projection" = ["f1", "f2"]
"""


def test_grid_report_and_read_study_match_the_cli(tmp_path, cli):
    grid_file = tmp_path / "tiny.toml"
    grid_file.write_text(GRID)
    cli("grid", grid_file, "--out", tmp_path / "cli", "--jobs", 2)
    runs = covga.grid(grid_file, jobs=2, out=tmp_path / "py")
    assert _same_rows_but_wall_time(tmp_path)
    seeds = covga.grid(grid_file, jobs=2, out=tmp_path / "seeds", order="seeds")
    assert seeds.drop(columns="wall_s").equals(runs.drop(columns="wall_s")), "the order changes no result"
    with pytest.raises(covga.ConfigError, match="not one of"):
        covga.grid(grid_file, jobs=2, out=tmp_path / "bad", order="shortest-first")
    assert len(runs) == 8
    assert all(isinstance(i, str) and len(i) == 16 for i in runs["run_id"]) and str(runs["seed"].dtype) == "UInt64"
    assert str(runs["executable"].dtype) == "boolean" and runs["cov_final_reach"].dtype == np.float64
    assert list(runs.columns).count("planner") == 1
    assert sorted(set(runs["thesis.selection"])) == ["elite", "tournament"]
    summary = covga.report(tmp_path / "py", by="thesis.selection", where={"scorer.projection": "f2"})
    assert summary.name == "summary.md" and "elite" in summary.read_text()
    # A comparison paired by seed, the same file the command line writes.
    covga.report(
        tmp_path / "py", compare={"thesis.selection": "elite"}, compare_every_plan={"thesis.selection": "elite"}
    )
    cli("report", tmp_path / "cli", "--compare", "thesis.selection=elite", "--compare-every-plan", "thesis.selection=elite")
    every = "compare-thesis.selection-every-plan.csv"
    assert (tmp_path / "py/report" / every).read_bytes() == (tmp_path / "cli/report" / every).read_bytes()
    table = covga.read_table(tmp_path / "py" / "report" / "compare-thesis.selection.csv")
    assert set(table["metric"]) == {"executable", "cov_final_reach", "time_s"}
    assert (tmp_path / "py/report/compare-thesis.selection.csv").read_bytes() == (
        tmp_path / "cli/report/compare-thesis.selection.csv"
    ).read_bytes()
    # The condensed analysis of variance, as the command line writes it.
    covga.report(tmp_path / "py", name="anova", anova_condensed=True)
    cli("report", tmp_path / "cli", "--name", "anova", "--anova-condensed")
    condensed = "report-anova/anova-condensed.md"
    assert (tmp_path / "py" / condensed).read_bytes() == (tmp_path / "cli" / condensed).read_bytes()
    assert "| residual |" in (tmp_path / "py" / condensed).read_text()
    # The plans and the seed-to-seed tables, as the command line writes them.
    covga.report(tmp_path / "py", name="plans", plans=True, seed_to_seed=True)
    cli("report", tmp_path / "cli", "--name", "plans", "--plans", "--seed-to-seed")
    for made in ("plans.md", "plans.csv", "seed-to-seed.md"):
        assert (tmp_path / "py/report-plans" / made).read_bytes() == (tmp_path / "cli/report-plans" / made).read_bytes()
    assert "| 0 vs 1 |" in (tmp_path / "py/report-plans/seed-to-seed.md").read_text()
    # Figures the runs record, per group, as the command line tabulates them.
    measures = ["time_s", "executable", "history.best_coverage@0", "objectives.cov_final"]
    covga.report(tmp_path / "py", name="measures", by="thesis.selection", measures=measures)
    cli("report", tmp_path / "cli", "--name", "measures", "--by", "thesis.selection",
        *[a for m in measures for a in ("--measure", m)])
    assert (tmp_path / "py/report-measures/measures.md").read_bytes() == (
        tmp_path / "cli/report-measures/measures.md").read_bytes()
    assert "| thesis.selection=elite | 4 |" in (tmp_path / "py/report-measures/measures.md").read_text()
    with pytest.raises(covga.ConfigError, match="--measure objectives.nothing: no run of"):
        covga.report(tmp_path / "py", name="measures", measures=["objectives.nothing"])
    with pytest.raises(covga.ConfigError, match="a list of keys"):
        covga.report(tmp_path / "py", name="measures", measures="time_s")
    with pytest.raises(covga.ConfigError, match="two plans for map"):
        covga.report(tmp_path / "py", name="plans", plans=True, reference=tmp_path / "py" / "runs.csv")
    with pytest.raises(covga.ConfigError, match="needs --plans"):
        covga.report(tmp_path / "py", name="plans", reference=tmp_path / "py" / "runs.csv")
    with pytest.raises(covga.ConfigError, match="expected True or False"):
        covga.report(tmp_path / "py", name="plans", plans="yes")  # type: ignore[arg-type]
    # Two baselines of one key: a file each, named by its baseline.
    covga.report(tmp_path / "py", name="both", compare={"thesis.selection": ["elite", "tournament"]})
    for baseline in ("elite", "tournament"):
        both = covga.read_table(tmp_path / "py" / "report-both" / f"compare-thesis.selection-{baseline}.csv")
        assert set(both["value"]) == {"elite", "tournament"} - {baseline}
    with pytest.raises(covga.ConfigError, match="no run has that value"):
        covga.report(tmp_path / "py", name="bad", compare={"thesis.selection": "rrws"})
    assert not (tmp_path / "py" / "report-bad").exists()
    with pytest.raises(covga.ConfigError, match="not a study folder"):
        covga.report(tmp_path / "nothing")
    with pytest.raises(covga.ConfigError, match="not a study folder"):
        covga.read_study(tmp_path / "nothing")


def _same_rows_but_wall_time(tmp_path):
    """runs.csv rows of the two folders, equal in every column but `wall_s`."""
    py, cli_runs = (covga.read_study(tmp_path / d).drop(columns="wall_s") for d in ("py", "cli"))
    return py.equals(cli_runs)


def test_ctrl_c_stops_a_study_which_then_resumes(tmp_path):
    grid_file = tmp_path / "slow.toml"
    grid_file.write_text(GRID.replace("iterations = 60", "iterations = 2000"))
    timer = interrupt_after(0.5)
    with pytest.raises(KeyboardInterrupt):
        covga.grid(grid_file, jobs=1, out=tmp_path / "study")
    timer.join()
    recorded = (tmp_path / "study" / "runs.csv").read_text().splitlines()
    assert 1 <= len(recorded) < 9, "stopped part-way, with the header and the finished runs"
    runs = covga.grid(grid_file, jobs=2, out=tmp_path / "study")
    assert len(runs) == 8 and runs["run_id"].is_unique


def test_ctrl_c_stops_the_runs_in_progress_without_recording_them(tmp_path):
    grid_file = tmp_path / "long.toml"
    grid_file.write_text(GRID.replace("iterations = 60", "iterations = 1000000"))
    started = time.monotonic()
    timer = interrupt_after(1.0)
    with pytest.raises(KeyboardInterrupt):
        covga.grid(grid_file, jobs=2, out=tmp_path / "study")
    timer.join()
    # Each run would take minutes; Ctrl-C ends the two in progress at their next generation.
    assert time.monotonic() - started < 10.0
    assert (tmp_path / "study" / "runs.csv").read_text().count("\n") == 1, "the header only"
    assert not any((tmp_path / "study" / "runs").iterdir()), "no interrupted run leaves a folder"


FAILING_GRID = """
[base]
planner = "thesis"
[base.thesis]
pop_min = 10
init_actions = 10
[base.budget]
iterations = 2
[[base.robots]]
name = "a"
start = [1.3, 1.3]
[[base.robots]]
name = "b"
start = [9.7, 9.5]
end = [1.6, 1.3]
[axes]
"fleet.mode" = ["central", "divide"]
"""


def test_a_run_that_fails_while_planning_is_recorded_and_raises_after_the_others(tmp_path):
    grid_file = tmp_path / "fails.toml"
    grid_file.write_text(FAILING_GRID)
    with pytest.raises(covga.ConfigError, match="1 of 2 runs failed while running"):
        covga.grid(grid_file, jobs=1, out=tmp_path / "out")
    runs = covga.read_study(tmp_path / "out")
    assert sorted(runs["stop"]) != [] and list(runs["stop"]).count("failed") == 1
    failed = runs[runs["stop"] == "failed"]
    assert "lies outside its region" in failed["violations"].iloc[0]


def _write_runs(folder, cam, size, fleet):
    folder.mkdir()
    header = "run_id,config_id,replicate,seed,thesis.tournament_size,planner,map,planner_feasible,executable,cam_walls_free,turns,stop,fleet_name,fleet_robots,union_reach,negotiation_settled\n"
    rows = [
        f"0123,4567,0,18446744073709551615,{size},thesis,thesis-1,true,true,{cam},12,iterations,{fleet},,,\n",
        "89ab,cdef,1,7,,thesis,thesis-1,false,false,0,3,failed,,,,\n",
    ]
    (folder / "runs.csv").write_text(header + "".join(rows))


def test_read_study_dtypes_do_not_depend_on_the_values(tmp_path):
    pd = pytest.importorskip("pandas")
    # One study whose camera share happens to be whole, whose fleet columns are empty and whose
    # swept integer key is set in one row; another with other values: the same dtypes.
    _write_runs(tmp_path / "a", "0", "3", "")
    _write_runs(tmp_path / "b", "0.25", "7", "pair")
    a, b = covga.read_study(tmp_path / "a"), covga.read_study(tmp_path / "b")
    assert list(a.dtypes) == list(b.dtypes)
    assert a["cam_walls_free"].dtype == np.float64
    assert a["turns"].dtype == pd.Int64Dtype() and a["replicate"].dtype == pd.Int64Dtype()
    assert a["seed"].dtype == pd.UInt64Dtype() and a["seed"][0] == 2**64 - 1
    assert a["executable"].dtype == pd.BooleanDtype() and bool(a["executable"][0])
    assert a["run_id"].dtype == pd.StringDtype() and a["run_id"][0] == "0123"
    assert a["fleet_name"].dtype == pd.StringDtype() and a["fleet_name"][1] == ""
    assert a["fleet_robots"].dtype == pd.Int64Dtype() and a["fleet_robots"].isna().all()
    assert a["union_reach"].dtype == np.float64 and a["union_reach"].isna().all()
    assert a["negotiation_settled"].dtype == pd.BooleanDtype() and a["negotiation_settled"].isna().all()
    # A swept key's column is typed by its values: whole numbers with a gap stay integers.
    assert a["thesis.tournament_size"].dtype == pd.Int64Dtype()
    assert a["thesis.tournament_size"].isna().tolist() == [False, True]


@pytest.mark.filterwarnings("ignore:.*is ignored")
def test_every_registered_planner_runs_by_name():
    names = covga.planners()
    assert names[:6] == ["thesis", "waypoint", "random_search", "boustrophedon", "spiral", "cell_order"]
    for name in names:
        result = covga.run(
            {
                "planner": name,
                "map": {"source": "thesis-2"},
                "stations": {"start": [1.3, 1.3]},
                "thesis": {"pop_min": 10, "init_individuals": 10, "init_actions": 10},
                "waypoint": {"population": 10},
                "cell_order": {"population": 10},
                "budget": {"evaluations": 200},
            },
            seed=3,
        )
        assert result.summary["planner"] == name
        assert result.plan[0][0].tolist() == [1.3, 1.3], name
