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


def many_pipelines(count):
    """A scenario's TOML text: `count` pipelines on a host scaled for 20,000 of them; thousands
    take the simulator a good fraction of a second or more."""
    return f"""
title = "{count} pipelines"
[[hosts]]
name = "node"
cores = 20000
memory = "200 TB"
memory_read_bw = "3000 GB/s"
memory_write_bw = "3000 GB/s"
[[hosts.disks]]
name = "ssd"
read_bw = "300 GB/s"
write_bw = "300 GB/s"
capacity = "100 PB"
[pipelines]
count = {count}
file_size = "1 GB"
tasks = 3
cpu_time = "4 s"
chunk_size = "100 MB"
"""
