"""pcsim.sweep: its table against `pcsim sweep run` + `pcsim sweep merge`'s results.csv, its
threads, Ctrl-C, and its errors."""

import json
import os
import signal
import threading
import time

import pandas as pd
import pytest

import pcsim
from conftest import many_pipelines, SOURCE, pcsim_cli

WALL = ["wall_s", "sim_wall_s"]  # the only columns two sweeps of the same runs may differ in
COUNTS = [2500, 2501, 2502, 2503, 2504, 2505]


def merged(tmp_path, sweep_file, *run_args):
    """results.csv of the command line's sweep, read as pcsim.sweep reads it."""
    out = tmp_path / "cli"
    pcsim_cli("sweep", "run", sweep_file, "--out", out, *run_args)
    pcsim_cli("sweep", "merge", out)
    return pd.read_csv(out / "results.csv", dtype={"id": str})


def assert_same_runs(ours, theirs):
    pd.testing.assert_frame_equal(ours.drop(columns=WALL), theirs.drop(columns=WALL))


def test_a_sweep_file_gives_merge_s_table(tmp_path):
    theirs = merged(tmp_path, "scenarios/sweeps/exp2.toml", "--jobs", "2")
    assert len(theirs) == 128
    assert_same_runs(pcsim.sweep("scenarios/sweeps/exp2.toml", jobs=2), theirs)


def test_axes_are_the_sweep_file_s(tmp_path):
    # The shipped sweep's axes given as arguments: the same runs, ids and figures.
    axes = {"pipelines.count": {"from": 1, "to": 32, "step": 1}, "hosts.0.page_cache.dirty_ratio": [0.2, 0.4],
            "hosts.0.memory": ["128 GB", "256 GB"]}
    ours = pcsim.sweep("scenarios/paper/exp2.toml", axes, jobs=3)
    assert_same_runs(ours, merged(tmp_path, "scenarios/sweeps/exp2.toml"))
    assert list(ours.columns[1:4]) == list(axes)
    assert (ours["status"] == "ok").all()
    assert ours["pipelines.count"].dtype == "int64" and ours["makespan_s"].dtype == "float64"


def test_points_a_profile_and_failed_runs(tmp_path):
    # Under the paper profile the 12 GB file no longer fits a 16 GB host: that run fails (the
    # command line's exit 1, its message), the others run; as in the command line's table.
    sweep_file = tmp_path / "fits.toml"
    sweep_file.write_text('scenario = "%s"\nprofile = "paper"\n\n[[points]]\n"hosts.0.memory" = "16 GB"\n\n[[points]]\n'
                          '"hosts.0.memory" = "32 GB"\n\n[[points]]\n"hosts.0.memory" = "64 GB"\n"hosts.0.cores" = 8\n'
                          % os.path.abspath("scenarios/examples/file-no-longer-fits.toml"))
    ours = pcsim.sweep("scenarios/examples/file-no-longer-fits.toml", profile="paper",
                       points=[{"hosts.0.memory": "16 GB"}, {"hosts.0.memory": "32 GB"}, {"hosts.0.memory": "64 GB", "hosts.0.cores": 8}])
    assert_same_runs(ours, merged(tmp_path, sweep_file))
    assert ours["status"].tolist() == ["failed", "ok", "ok"]
    assert ours["exit_code"].tolist() == [1, 0, 0]
    assert "too-big.dat" in ours["error"][0]


def test_a_workflow_instance_as_a_dict(tmp_path):
    path = "inputs/wfcommons/instances/blast-chameleon-small-001.json"
    platform = "platforms/wfcommons-chameleon.xml"
    axes = {"host_defaults.memory_in_use": ["1 GB", "2 GB"]}
    with open(path) as f:
        instance = json.load(f)
    from_dict = pcsim.sweep(instance, axes, platform=platform, profile="linux")
    sweep_file = tmp_path / "blast.toml"
    sweep_file.write_text(f'workflow = "{os.path.abspath(path)}"\nplatform = "{os.path.abspath(platform)}"\nprofile = "linux"\n\n'
                          '[[axes]]\nkey = "host_defaults.memory_in_use"\nvalues = ["1 GB", "2 GB"]\n')
    assert_same_runs(from_dict, merged(tmp_path, sweep_file))


@pytest.fixture
def big(tmp_path, monkeypatch):
    """The scenario's file. Debug builds check the cache's invariants after every change:
    hours at these sizes, so not here."""
    monkeypatch.setenv("PAGECACHE_CHECK_INVARIANTS", "0")
    path = tmp_path / "many-pipelines.toml"
    path.write_text(many_pipelines(1))
    return path


def test_runs_go_on_threads_with_the_gil_released(big):
    # Runs of 2,500 pipelines take a tenth of a second or more each: while they run, a Python
    # thread keeps running (the GIL is free) and sees the sweep's three worker threads.
    seen = []
    done = threading.Event()

    def watch():
        while not done.is_set():
            seen.append(len(os.listdir("/proc/self/task")))
            time.sleep(0.01)

    before = len(os.listdir("/proc/self/task"))
    watcher = threading.Thread(target=watch)
    watcher.start()
    try:
        table = pcsim.sweep(big, {"pipelines.count": COUNTS}, jobs=3)
    finally:
        done.set()
        watcher.join()
    assert (table["status"] == "ok").all()
    assert len(seen) >= 5, "the watching thread hardly ran: the GIL was held"
    assert max(seen) >= before + 1 + 3, f"threads seen {max(seen)}, {before} before the watcher"
    # The same runs one at a time give the same table.
    assert_same_runs(pcsim.sweep(big, {"pipelines.count": COUNTS}, jobs=1), table)


def test_ctrl_c_stops_a_sweep(big):
    sent = []
    timer = threading.Timer(0.25, lambda: (sent.append(time.monotonic()), os.kill(os.getpid(), signal.SIGINT)))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            pcsim.sweep(big, {"pipelines.count": [20000, 20001, 20002, 20003]}, jobs=2)
    finally:
        timer.cancel()
    # Within a few tenths of a second in a release build; ASan makes each step ten times slower.
    assert sent and time.monotonic() - sent[0] < 3.0


def test_errors_name_the_axis_before_anything_runs(tmp_path):
    with pytest.raises(pcsim.InputError, match=r"^pcsim.sweep: axis 'pipelines.count': step = nan is not a number") as e:
        pcsim.sweep("scenarios/paper/exp2.toml", {"pipelines.count": {"from": 1, "to": 3, "step": float("nan")}})
    assert e.value.file is None and e.value.line is None
    with pytest.raises(pcsim.InputError, match="axis 'nope.key', value 1: .*unknown key 'nope'"):
        pcsim.sweep("scenarios/paper/exp2.toml", {"nope.key": [1]})
    with pytest.raises(pcsim.InputError, match="has no value") as e:
        pcsim.sweep("scenarios/paper/exp2.toml", {"pipelines.count": []})
    assert e.value.key == "axes[0].values"
    with pytest.raises(pcsim.InputError, match=r"points\[1\]: .*expected an integer"):
        pcsim.sweep("scenarios/paper/exp2.toml", points=[{"pipelines.count": 2}, {"pipelines.count": "x"}])
    with pytest.raises(pcsim.InputError, match="more than an axis may have"):
        pcsim.sweep("scenarios/paper/exp2.toml", {"pipelines.count": {"from": 1, "to": 10**9, "step": 1}})
    with pytest.raises(pcsim.InputError, match="jobs"):
        pcsim.sweep("scenarios/paper/exp2.toml", {"pipelines.count": [1]}, jobs=0)
    with pytest.raises(pcsim.InputError, match="axes or points"):
        pcsim.sweep(None)
    # A sweep file's errors name the file and line, as the command line's do.
    bad = tmp_path / "bad.toml"
    bad.write_text('scenario = "x.toml"\n\n[[axes]]\nkey = "pipelines.count"\nvalues = []\n')
    with pytest.raises(pcsim.InputError) as e:
        pcsim.sweep(bad)
    assert e.value.file == str(bad) and e.value.line == 5
    assert str(e.value) in pcsim_cli("sweep", "run", bad, "--out", tmp_path / "o", check=False).stderr


def test_a_base_of_toml_text_is_refused_as_not_a_path(tmp_path):
    text = (SOURCE / "scenarios/paper/exp2.toml").read_text()
    with pytest.raises(pcsim.InputError) as e:
        pcsim.sweep(text, {"pipelines.count": [1, 2]})
    assert str(e.value).startswith("base: this is TOML text, not a path")
    assert text not in str(e.value)  # not printed back as a path
    # A path that holds '=' is still a path.
    odd = tmp_path / "count=2"
    odd.mkdir()
    scenario = odd / "s.toml"
    scenario.write_text(text.replace('"../../platforms/', '"%s/platforms/' % SOURCE))
    assert len(pcsim.sweep(str(scenario), points=[{"pipelines.count": 1}])) == 1
