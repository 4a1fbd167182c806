"""What the tests share: the pcsim command line built beside the module (PCSIM_BIN), the
source tree (PCSIM_SOURCE_DIR), and running the command line into a fresh folder."""

import os
import pathlib
import subprocess

import pytest

SOURCE = pathlib.Path(os.environ.get("PCSIM_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
PCSIM = os.environ.get("PCSIM_BIN", str(SOURCE / "build" / "bin" / "pcsim"))


def pcsim_cli(*args, check=True):
    """Runs the pcsim command line from the source tree; its CompletedProcess."""
    done = subprocess.run([PCSIM, *map(str, args)], cwd=SOURCE, capture_output=True, text=True)
    if check and done.returncode != 0:
        raise AssertionError(f"pcsim {' '.join(map(str, args))}: exit {done.returncode}\n{done.stderr}")
    return done


@pytest.fixture
def source():
    return SOURCE


@pytest.fixture(autouse=True)
def in_source_tree(monkeypatch):
    # Scenario paths are given relative to the source tree, as the command line gets them.
    monkeypatch.chdir(SOURCE)
