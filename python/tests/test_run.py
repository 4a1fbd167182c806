"""pcsim.run: its tables against the files `pcsim run` writes, its options against the command
line's, and Result.write against `pcsim run --out`."""

import filecmp
import json
import pathlib

import numpy as np
import pandas as pd
import pytest

import pcsim
from conftest import SOURCE, pcsim_cli

# The scenarios scripts/check-outputs runs (scenarios/sweeps/ holds sweep plans, not scenarios).
SHIPPED = sorted(str(p.relative_to(SOURCE)) for pattern in ("scenarios/paper/*.toml", "scenarios/examples/*.toml", "tests/apps/golden/*.toml")
                 for p in SOURCE.glob(pattern))


def cli_tables(tmp_path, *args):
    out = tmp_path / "cli"
    pcsim_cli("run", *args, "--out", out, "--quiet")
    return {name: pd.read_csv(out / f"{name}.csv", keep_default_na=False, float_precision="round_trip")
            for name in ("timeline", "memory", "cache") if (out / f"{name}.csv").exists()}


def assert_same_table(ours, theirs):
    """Our DataFrame holds what the CSV file holds: the same columns and rows, names as the CSV
    writes them (no name here starts a formula), times equal to the microsecond the CSV keeps."""
    assert list(ours.columns) == list(theirs.columns)
    assert len(ours) == len(theirs)
    for column in ours.columns:
        a, b = ours[column], theirs[column]
        if isinstance(a.dtype, pd.CategoricalDtype) or a.dtype == object:
            assert a.astype(str).tolist() == b.astype(str).tolist(), column
        elif np.issubdtype(a.dtype, np.floating):
            assert np.abs(a.to_numpy() - b.to_numpy(dtype=float)).max(initial=0.0) <= 5e-7, column
        else:
            assert a.dtype == np.int64, column
            assert (a.to_numpy() == b.to_numpy(dtype=np.int64)).all(), column


@pytest.mark.parametrize("profile", ["paper", "linux"])
@pytest.mark.parametrize("scenario", SHIPPED + [None])
def test_tables_equal_the_command_lines_files(tmp_path, scenario, profile):
    args = ([scenario] if scenario else []) + ["--profile", profile]
    cli = pcsim_cli("run", *args, "--out", tmp_path / "cli", "--quiet", check=False)
    if cli.returncode == 1:
        # A scenario that runs out of memory on purpose: the same error, its time apart.
        with pytest.raises(pcsim.SimulationError) as failed:
            pcsim.run(scenario, profile=profile)
        assert cli.stderr == f"pcsim: simulation failed: {failed.value}\n"
        assert failed.value.time == float(str(failed.value).split("t = ")[1].split(" s")[0])
        return
    assert cli.returncode == 0, cli.stderr
    result = pcsim.run(scenario, profile=profile)
    for name in ("timeline", "memory", "cache"):
        if (tmp_path / "cli" / f"{name}.csv").exists():
            theirs = pd.read_csv(tmp_path / "cli" / f"{name}.csv", keep_default_na=False, float_precision="round_trip")
            assert_same_table(getattr(result, name), theirs)
    assert json.loads((tmp_path / "cli" / "summary.json").read_text()) == result.summary


def test_names_are_categoricals_and_numbers_are_typed():
    t = pcsim.run("scenarios/paper/exp2.toml", set={"pipelines.count": 2}).timeline
    for column in ("app", "task", "host", "phase"):
        assert isinstance(t[column].dtype, pd.CategoricalDtype)
    # Each column has its own categories: the applications' names are not the tasks'.
    assert len(t["app"].cat.categories) == 2 and len(t["task"].cat.categories) == 3
    assert list(t["phase"].cat.categories) == ["read", "compute", "write"]
    assert list(t["host"].cat.categories) == ["node", "storage"]
    assert t["start_s"].dtype == np.float64 and t["bytes"].dtype == np.int64


def test_options_are_the_command_lines(tmp_path):
    # --set, --profile and --platform give the same run as the same options of pcsim run.
    platform = "platforms/paper-cluster.toml"
    theirs = cli_tables(tmp_path, "scenarios/paper/exp2.toml", "--set", "pipelines.count=3", "--set", "pipelines.file_size=2 GB",
                        "--profile", "linux", "--platform", platform)
    ours = pcsim.run("scenarios/paper/exp2.toml", set={"pipelines.count": 3, "pipelines.file_size": "2 GB"}, profile="linux",
                     platform=pathlib.Path(platform))
    assert_same_table(ours.timeline, theirs["timeline"])
    assert ours.timeline["bytes"].max() == 2_000_000_000


def test_toml_text_runs_as_its_file(tmp_path):
    text = (SOURCE / "tests/apps/golden/two_readers.toml").read_text()
    ours = pcsim.run(text)
    theirs = cli_tables(tmp_path, "tests/apps/golden/two_readers.toml")
    assert_same_table(ours.timeline, theirs["timeline"])
    assert ours.summary["scenario"] == "<text>"


def test_a_100000_row_timeline(tmp_path):
    # 11,112 pipelines of three tasks: 100,008 phases, each as the command line writes it.
    args = {"pipelines.count": 11112, "pipelines.file_size": "10 MB", "pipelines.chunk_size": "10 MB", "pipelines.cpu_time": "1 s",
            "memory_sample_interval": "1000 s"}
    ours = pcsim.run("scenarios/paper/exp2.toml", set=args, cache_contents=False)
    assert len(ours.timeline) == 100_008
    theirs = cli_tables(tmp_path, "scenarios/paper/exp2.toml", *[x for k, v in args.items() for x in ("--set", f"{k}={v}")],
                        "--no-cache-contents")
    assert_same_table(ours.timeline, theirs["timeline"])
    assert len(ours.cache) == 0


def test_write_gives_the_command_lines_files(tmp_path):
    pcsim_cli("run", "scenarios/paper/exp1.toml", "--out", tmp_path / "cli", "--quiet", "--trace")
    result = pcsim.run("scenarios/paper/exp1.toml", trace=True)
    assert result.write(tmp_path / "py") == []
    names = sorted(p.name for p in (tmp_path / "cli").iterdir())
    assert names == sorted(p.name for p in (tmp_path / "py").iterdir())
    same, different, _ = filecmp.cmpfiles(tmp_path / "cli", tmp_path / "py", [n for n in names if n != "timing.json"], shallow=False)
    assert different == [] and len(same) == len(names) - 1
    with pytest.raises(pcsim.InputError, match="written once"):
        result.write(tmp_path / "again")


def test_write_refuses_a_folder_pcsim_did_not_write(tmp_path):
    (tmp_path / "mine").mkdir()
    (tmp_path / "mine" / "notes.txt").write_text("mine")
    with pytest.raises(pcsim.InputError, match="mine"):
        pcsim.run(set={"pipelines.count": 1}).write(tmp_path / "mine")
    assert (tmp_path / "mine" / "notes.txt").read_text() == "mine"


def test_the_report_inline():
    result = pcsim.run()
    page = result._repr_html_()
    assert page.startswith("<iframe") and "srcdoc=" in page
    assert "&lt;svg" in page and "<svg" not in page  # the whole page, escaped into the frame
    assert result.report_html().startswith("<!DOCTYPE html>")


def test_show_is_the_command_lines():
    assert pcsim.show("scenarios/paper/exp3.toml", profile="linux") == pcsim_cli("show", "scenarios/paper/exp3.toml", "--profile", "linux").stdout
    assert pcsim.show() == pcsim_cli("show").stdout
