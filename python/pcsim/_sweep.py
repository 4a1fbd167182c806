"""pcsim.sweep: `pcsim sweep run` + `merge` as a DataFrame, the runs on threads."""

from __future__ import annotations

import io
import json
import numbers
import os
import re
import tempfile
from typing import Any, Iterable, Mapping, Optional, Sequence, Tuple, Union

import pandas as pd

from . import _core
from ._scenario import looks_like_toml
from ._errors import InputError

PathLike = Union[str, "os.PathLike[str]"]
Axes = Union[Mapping[str, Any], Iterable[Tuple[str, Any]]]

# The name the sweep made from pcsim.sweep's arguments goes by in messages.
_ORIGIN = "<pcsim.sweep>"


def _string(text: str) -> str:
    # A TOML basic string: quotes, backslashes and control characters escaped, the rest as is.
    out = []
    for ch in text:
        if ch in '"\\':
            out.append("\\" + ch)
        elif ord(ch) < 0x20 or ord(ch) == 0x7F:
            out.append(f"\\u{ord(ch):04X}")
        else:
            out.append(ch)
    return '"' + "".join(out) + '"'


def _value(value: Any, where: str) -> str:
    """A Python value as a sweep file's TOML value (a str is a TOML string, as in a sweep file)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        return repr(float(value))  # nan and inf are TOML too: the plan refuses them by name
    if isinstance(value, str):
        return _string(value)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_value(v, where) for v in value) + "]"
    raise InputError(f"{where}: a value is a str, int, float, bool or list, not {type(value).__name__}")


def _axis(key: Any, spec: Any) -> str:
    if not isinstance(key, str):
        raise InputError(f"axes: a key is a dotted --set key (str), not {type(key).__name__}")
    where = f"axes[{key!r}]"
    if isinstance(spec, Mapping):  # a range: {"from": 1, "to": 32, "step": 1} or "factor"
        fields = ", ".join(f"{_string(str(k))} = {_value(v, where)}" for k, v in spec.items())
        return f"[[axes]]\nkey = {_string(key)}\nrange = {{ {fields} }}\n"
    if isinstance(spec, (str, bytes)) or not isinstance(spec, Iterable):
        raise InputError(f"{where}: the axis's values (a list) or a range ({{'from': 1, 'to': 32, 'step': 1}}), not {type(spec).__name__}")
    return f"[[axes]]\nkey = {_string(key)}\nvalues = [{', '.join(_value(v, where) for v in spec)}]\n"


def _pairs(axes: Axes) -> Sequence[Tuple[Any, Any]]:
    if isinstance(axes, Mapping):
        return list(axes.items())
    pairs = list(axes)
    if not all(isinstance(p, tuple) and len(p) == 2 for p in pairs):
        raise InputError("axes: a dict {key: values} or a list of (key, values) pairs")
    return pairs


def sweep_text(base: Optional[str], axes: Optional[Axes], points: Optional[Iterable[Mapping[str, Any]]], *, profile: Optional[str],
               platform: Optional[PathLike], files_host: Optional[str], hosts: Optional[Iterable[str]]) -> str:
    """The sweep file pcsim.sweep's arguments stand for (paths made absolute)."""
    lines = []
    if base is not None:
        if base.endswith(".json"):
            lines.append(f"workflow = {_string(os.path.abspath(base))}")
        else:
            lines.append(f"scenario = {_string(os.path.abspath(base))}")
    if platform is not None:
        lines.append(f"platform = {_string(os.path.abspath(os.fspath(platform)))}")
    if files_host is not None:
        lines.append(f"files_host = {_string(files_host)}")
    if hosts is not None:
        lines.append(f"hosts = {_value(list(hosts), 'hosts')}")
    if profile is not None:
        lines.append(f"profile = {_string(profile)}")
    text = "\n".join(lines) + "\n"
    if axes is not None:
        text += "".join("\n" + _axis(key, spec) for key, spec in _pairs(axes))
    for i, point in enumerate(points or []):
        if not isinstance(point, Mapping):
            raise InputError(f"points[{i}]: a dict {{key: value}}, not {type(point).__name__}")
        text += "\n[[points]]\n" + "".join(f"{_string(str(k))} = {_value(v, f'points[{i}]')}\n" for k, v in point.items())
    return text


def sweep(base: Union[None, PathLike, Mapping[str, Any]] = None, axes: Optional[Axes] = None, *,
          points: Optional[Iterable[Mapping[str, Any]]] = None, profile: Optional[str] = None, platform: Optional[PathLike] = None,
          files_host: Optional[str] = None, hosts: Optional[Iterable[str]] = None, jobs: int = 1, force: bool = False) -> pd.DataFrame:
    """Runs a sweep, as `pcsim sweep run` then `pcsim sweep merge` do, and returns its table: a
    row per run in the plan's order with results.csv's columns (id, a column per swept key,
    status, exit_code, the figures, error, wall_s, sim_wall_s), the same values but for the
    two wall times. Nothing is written.

    base: the scenario (a TOML path, not TOML text: each run reads the file again; a
    WfFormat/WRENCH instance as a .json path or a dict, with `platform`), or None for the
    embedded default. axes: {key: values} (or (key, values)
    pairs), swept as a grid, the first axis slowest; values a list, or a range
    {"from": 1, "to": 32, "step": 1} (or "factor" for a log range). points: instead of axes,
    a list of runs, each {key: value}. With neither, `base` is a sweep file, read as `pcsim
    sweep run` reads it. profile, platform, files_host, hosts: the sweep file's keys.
    jobs: runs at a time, each on a thread of this process, the GIL released. force: allow
    more than 10^7 runs. Ctrl-C stops every run (KeyboardInterrupt). Bad input raises
    InputError before anything runs; a run that fails is its row's (status "failed", error).
    """
    if isinstance(jobs, bool) or not isinstance(jobs, numbers.Integral) or not 1 <= jobs <= 1024:
        raise InputError(f"jobs: runs at a time, from 1 to 1024, not {jobs!r}")
    if isinstance(base, Mapping):
        if axes is None and points is None:
            raise InputError("sweep: give axes or points to sweep the instance over")
        return _with_instance(base, axes, points, profile, platform, files_host, hosts, int(jobs), force)
    if base is not None and not isinstance(base, (str, os.PathLike)):
        raise InputError(f"base: a path or a WfCommons instance (dict), or None, not {type(base).__name__}")
    if isinstance(base, str) and looks_like_toml(base) and not os.path.exists(base):
        # Its runs are re-read from the file by each shard and named by its path in results.
        raise InputError("base: this is TOML text, not a path: pcsim.sweep takes a scenario file's path (pcsim.run takes text); "
                         "write the text to a file and pass its path")
    path = os.fspath(base) if base is not None else None
    if axes is None and points is None:
        if path is None:
            raise InputError("sweep: give axes or points (or a sweep file as base)")
        if any(v is not None for v in (profile, platform, files_host, hosts)):
            raise InputError("sweep: a sweep file names its own profile, platform, files_host and hosts")
        return _table(_core.sweep_csv(path, "", "", int(jobs), force))
    text = sweep_text(path, axes, points, profile=profile, platform=platform, files_host=files_host, hosts=hosts)
    try:
        return _table(_core.sweep_csv("", text, _ORIGIN, int(jobs), force))
    except InputError as e:
        # The sweep made of the arguments has no file: its lines and its path mean nothing to
        # the caller, who finds the axis or point named by the message and key.
        ours = e.file in (_ORIGIN, os.path.abspath(_ORIGIN))
        message = re.sub(re.escape(os.path.abspath(_ORIGIN)) + "|" + re.escape(_ORIGIN) + r"(?::\d+){0,2}", "pcsim.sweep", str(e))
        raise InputError(message, None if ours else e.file, None if ours else e.line, e.key) from None


def _with_instance(instance, axes, points, profile, platform, files_host, hosts, jobs, force) -> pd.DataFrame:
    # The C++ readers read an instance from a file: the dict is handed over in one.
    with tempfile.TemporaryDirectory(prefix="pcsim-instance-") as folder:
        path = os.path.join(folder, "instance.json")
        with open(path, "w", encoding="utf-8") as f:
            json.dump(instance, f, ensure_ascii=False)
        return sweep(path, axes, points=points, profile=profile, platform=platform, files_host=files_host, hosts=hosts, jobs=jobs,
                     force=force)


def _table(csv: str) -> pd.DataFrame:
    # As a user reads results.csv: ids stay text (16 hex digits may all be digits).
    return pd.read_csv(io.StringIO(csv), dtype={"id": str})
