"""pcsim: a discrete-event simulator of the Linux page cache, in Python.

    import pcsim
    result = pcsim.run("scenarios/paper/exp2.toml", set={"pipelines.count": 8})
    result.timeline                 # a pandas DataFrame: timeline.csv's columns
    result.write("out")             # the files `pcsim run --out out` writes

`run` and `show` take a scenario as a path (TOML, or a WfFormat / WRENCH workflow instance
.json with `platform`), TOML text, a WfCommons instance as a dict (`json.load` of one), or
None for the embedded default; and the options of `pcsim run`. `validate` is `pcsim validate`,
`sweep` is `pcsim sweep run` and `merge` (a DataFrame of the runs, run on threads).
Errors are InputError (the input is wrong) and SimulationError (the model cannot proceed).
"""

from __future__ import annotations

import os
from typing import Any, Iterable, Mapping, Optional, Union

from . import _core
from ._errors import Error, InputError, InvariantError, SimulationError
from ._result import Result
from ._sweep import sweep
from ._validate import validate
from ._scenario import ScenarioLike, load as _load, with_request as _with_request

__version__ = _core.__version__
__all__ = ["run", "show", "sweep", "validate", "Result", "Error", "InputError", "SimulationError", "InvariantError", "__version__"]

PathLike = Union[str, "os.PathLike[str]"]


def run(scenario: ScenarioLike = None, *, profile: Optional[str] = None, set: Optional[Mapping[str, Any]] = None,
        platform: Optional[PathLike] = None, files_host: Optional[str] = None, hosts: Optional[Iterable[str]] = None,
        trace: bool = False, cache_contents: bool = True) -> Result:
    """Runs a scenario to its end, as `pcsim run` does, and returns its Result.

    scenario: a path, TOML text, a WfCommons instance (dict), or None (the embedded default).
    profile: "linux" or "paper" (else the scenario's). set: {dotted key: value}, as --set.
    platform, files_host, hosts: as --platform, --files-host, --hosts. trace: record trace.json
    for Result.write. cache_contents: record the cache contents (Result.cache).
    The GIL is released while it runs; Ctrl-C stops it with KeyboardInterrupt.
    """
    run = _with_request(scenario, lambda request: _core.run(request, trace, cache_contents), profile=profile, set=set,
                        platform=platform, files_host=files_host, hosts=hosts)
    return Result(run)


def show(scenario: ScenarioLike = None, *, profile: Optional[str] = None, set: Optional[Mapping[str, Any]] = None,
         platform: Optional[PathLike] = None, files_host: Optional[str] = None, hosts: Optional[Iterable[str]] = None) -> str:
    """The scenario resolved, every default written out, as TOML (`pcsim show`)."""
    return _load(scenario, profile=profile, set=set, platform=platform, files_host=files_host, hosts=hosts).to_toml()
