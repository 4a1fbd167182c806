"""What pcsim.run takes: a WfCommons instance as a dict, and the errors of bad input."""

import json
import os
import signal
import threading
import time

import pytest

import pcsim
from conftest import many_pipelines, SOURCE, pcsim_cli

INSTANCES = sorted((SOURCE / "inputs/wfcommons/instances").glob("*.json"))
CHAMELEON = "platforms/wfcommons-chameleon.xml"


@pytest.mark.parametrize("instance", INSTANCES[:3], ids=lambda p: p.stem)
def test_a_wfcommons_instance_as_a_dict_runs_as_its_file(tmp_path, instance):
    with open(instance) as f:
        loaded = json.load(f)
    ours = pcsim.run(loaded, platform=CHAMELEON)
    pcsim_cli("run", instance, "--platform", CHAMELEON, "--out", tmp_path / "cli", "--quiet")
    theirs = json.loads((tmp_path / "cli" / "summary.json").read_text())
    # The same run; only the scenario's name differs: the instance's, not a file's.
    assert ours.summary["scenario"] == f"<instance {loaded['name']}>"
    assert {k: v for k, v in ours.summary.items() if k != "scenario"} == {k: v for k, v in theirs.items() if k != "scenario"}
    assert len(ours.timeline) == 3 * len(loaded["workflow"]["specification"]["tasks"])


def test_a_broken_instance_names_the_instance_not_a_file():
    with open(INSTANCES[0]) as f:
        loaded = json.load(f)
    loaded["workflow"]["specification"]["tasks"][0]["inputFiles"] = ["no-such-file"]
    with pytest.raises(pcsim.InputError) as e:
        pcsim.run(loaded, platform=CHAMELEON)
    assert "no-such-file" in str(e.value)
    assert "instance.json" not in str(e.value) and f"<instance {loaded['name']}>" in str(e.value)
    assert e.value.file in (None, f"<instance {loaded['name']}>")


def test_an_input_error_names_file_line_and_key(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('title = "x"\nplatform = "%s"\n\n[pipelines]\ncount = 2\nfile_size = "1 GB"\ncpu_time = "-3 s"\n'
                   % (SOURCE / "platforms/paper-cluster.toml"))
    with pytest.raises(pcsim.InputError) as e:
        pcsim.run(bad)
    assert (e.value.file, e.value.line, e.value.key) == (str(bad), 7, "pipelines.cpu_time")
    cli = pcsim_cli("run", bad, "--out", tmp_path / "out", check=False)
    assert cli.returncode == 2 and cli.stderr == f"pcsim: {e.value}\n"


def test_an_unknown_key_and_a_bad_set_value(tmp_path):
    with pytest.raises(pcsim.InputError) as e:
        pcsim.run("scenarios/paper/exp2.toml", set={"pipelines.colour": 3})
    assert "unknown key 'pipelines.colour'" in str(e.value) and e.value.key == "pipelines.colour"
    with pytest.raises(pcsim.InputError) as e:
        pcsim.run("scenarios/paper/exp2.toml", set={"pipelines.count": -1})
    assert e.value.key == "pipelines.count" and e.value.file is None  # the value came from `set`
    with pytest.raises(pcsim.InputError, match="finite"):
        pcsim.run("scenarios/paper/exp2.toml", set={"pipelines.cpu_time": float("nan")})
    with pytest.raises(pcsim.InputError, match="cannot open|no such|not found"):
        pcsim.run("no/such/scenario.toml")
    with pytest.raises(pcsim.InputError):
        pcsim.run('title = "x"\n[pipelines\n')  # TOML text that does not parse
    assert issubclass(pcsim.InputError, ValueError)


def test_a_simulation_error_has_its_time():
    with pytest.raises(pcsim.SimulationError) as e:
        pcsim.run("scenarios/examples/file-no-longer-fits.toml", profile="paper")
    assert e.value.time == pytest.approx(8.2)
    assert "too-big.dat" in str(e.value)


def test_ctrl_c_stops_a_run(monkeypatch):
    # 20,000 pipelines on a host scaled for them take the simulator seconds; SIGINT a quarter
    # of a second in stops the run within the next few thousand events. (Debug builds check
    # the cache's invariants after every change, which at this size takes hours: not here.)
    monkeypatch.setenv("PAGECACHE_CHECK_INVARIANTS", "0")
    scenario = many_pipelines(20000)
    sent = []
    timer = threading.Timer(0.25, lambda: (sent.append(time.monotonic()), os.kill(os.getpid(), signal.SIGINT)))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            pcsim.run(scenario, cache_contents=False)
    finally:
        timer.cancel()
    # Within seconds of the signal, though a sanitized debug build may still be loading then.
    assert sent and time.monotonic() - sent[0] < 5.0


def test_a_path_holding_a_nul_is_said_to_hold_one():
    # A C string ends at the NUL: the file named would be another; the message says why.
    for path in ("\0", "a\0b", "scenarios/paper/exp2.toml\0.json"):
        with pytest.raises(pcsim.InputError, match="holds a NUL character") as e:
            pcsim.run(path)
        assert str(e.value).strip() != "" and "\\u0000" in str(e.value)
    with pytest.raises(pcsim.InputError, match="--platform .*holds a NUL character"):
        pcsim.run(INSTANCES[0], platform="platforms/wfcommons-chameleon.xml\0")
