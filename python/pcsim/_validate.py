"""pcsim.validate: `pcsim validate` as DataFrames."""

from __future__ import annotations

import os
import pathlib
from typing import Any, Mapping, Optional, Union

import pandas as pd

from . import _core
from ._errors import InputError
from ._scenario import _overrides

PathLike = Union[str, "os.PathLike[str]"]

# pcsim's data beside a build tree's module: <build>/python/pcsim -> <build>/share/pcsim.
_SHIPPED = pathlib.Path(__file__).resolve().parent.parent.parent / "share" / "pcsim"


def validate(*, profile: Optional[str] = None, set: Optional[Mapping[str, Any]] = None, switch: Optional[Mapping[str, bool]] = None,
             data: Optional[PathLike] = None, scenarios: Optional[PathLike] = None) -> pd.DataFrame:
    """`pcsim validate`: the paper's experiments run with its scenarios and compared with its
    measurements. A row per case: its mean errors (%, the paper's metric), WRENCH-cache's, and
    its other figures; `.attrs["figures"]` holds every compared duration (case, figure, real_s,
    simulated_s, wrench_s). `switch`: page-cache switches forced on every host, e.g.
    {"background_writeback": False}. `data` and `scenarios`: the folders validation/paper and
    scenarios/paper (found beside a build tree's module; give them to an installed one)."""
    if data is None or scenarios is None:
        if not (_SHIPPED / "validation" / "paper").is_dir():
            raise InputError(f"validate: no validation data beside this module (looked in {_SHIPPED}): give data= and scenarios= "
                             "(validation/paper and scenarios/paper of pcsim's sources)")
        data = data if data is not None else _SHIPPED / "validation" / "paper"
        scenarios = scenarios if scenarios is not None else _SHIPPED / "scenarios" / "paper"
    switches = []
    for name, value in (switch or {}).items():
        if not isinstance(value, bool):
            raise InputError(f"switch {name}: true or false, not {value!r}")
        switches.append((str(name), value))
    cases = _core.validate_cases(os.fspath(data), os.fspath(scenarios), profile or "", _overrides(set), switches)
    rows = [{**{k: v for k, v in c.items() if k not in ("extra", "figures")}, **c["extra"]} for c in cases]
    table = pd.DataFrame(rows)
    table.attrs["figures"] = pd.DataFrame(
        [{"case": c["case"], "figure": f["label"], "real_s": f["real"], "simulated_s": f["simulated"], "wrench_s": f["wrench"]}
         for c in cases for f in c["figures"]])
    return table
