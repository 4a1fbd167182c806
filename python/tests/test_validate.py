"""pcsim.validate against `pcsim validate --json`: the same cases and errors."""

import json

import pytest

import pcsim
from conftest import SOURCE, pcsim_cli


def cli_cases(tmp_path, *args):
    pcsim_cli("validate", *args, "--json", tmp_path / "v.json", "--report", tmp_path / "v.html")
    return json.loads((tmp_path / "v.json").read_text())


@pytest.mark.parametrize("args,kwargs", [
    (["--profile", "paper"], {"profile": "paper"}),
    (["--profile", "linux"], {"profile": "linux"}),
    (["--profile", "linux", "--switch", "background_writeback=false"], {"profile": "linux", "switch": {"background_writeback": False}}),
], ids=["paper", "linux", "linux-no-background-writeback"])
def test_the_cases_are_pcsim_validates(tmp_path, args, kwargs):
    theirs = cli_cases(tmp_path, *args)
    ours = pcsim.validate(**kwargs)
    assert list(ours["case"]) == [c["case"] for c in theirs]
    for (_, row), case in zip(ours.iterrows(), theirs):
        for key, value in case.items():
            if key in ("case", "profile"):
                assert row[key] == value
            else:
                assert row[key] == pytest.approx(value, abs=5e-5), (case["case"], key)  # the JSON keeps 4 decimals
    figures = ours.attrs["figures"]
    assert set(figures["case"]) == set(ours["case"])
    assert (figures["real_s"] > 0).all()


def test_a_folder_without_the_data_is_named(tmp_path):
    with pytest.raises(pcsim.InputError, match=r"exp1_real_phase_times\.csv: cannot open the data file"):
        pcsim.validate(data=tmp_path, scenarios=SOURCE / "scenarios" / "paper")
    with pytest.raises(pcsim.InputError, match="true or false"):
        pcsim.validate(switch={"background_writeback": "no"})
