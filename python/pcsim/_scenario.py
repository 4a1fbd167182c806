"""Turning what a caller hands pcsim.run and pcsim.show into a loaded scenario."""

from __future__ import annotations

import json
import math
import os
import tempfile
from typing import Any, Callable, Iterable, Mapping, Optional, TypeVar, Union

from . import _core
from ._errors import InputError

ScenarioLike = Union[None, str, "os.PathLike[str]", Mapping[str, Any]]
T = TypeVar("T")


def toml_value(value: Any) -> str:
    """A Python value as the TOML value text --set takes (a str is taken as --set takes it:
    as TOML if it is a TOML value, else as text)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            raise InputError(f"set: {value!r} is not a finite number")
        return repr(value)
    if isinstance(value, str):
        return value
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(json.dumps(v, ensure_ascii=False) if isinstance(v, str) else toml_value(v) for v in value) + "]"
    raise InputError(f"set: a value must be a str, int, float, bool or list, not {type(value).__name__}")


def _overrides(set: Optional[Mapping[str, Any]]) -> list:
    if set is None:
        return []
    if not isinstance(set, Mapping):
        raise InputError("set: a dict of {dotted key: value}, e.g. {'pipelines.count': 16}")
    return [(str(key), toml_value(value)) for key, value in set.items()]


def looks_like_toml(text: str) -> bool:
    """What pcsim.run takes as TOML text rather than a path: a line break, an '=' or a leading '['."""
    return "\n" in text or "=" in text or text.lstrip().startswith("[")


def load(scenario: ScenarioLike, **options) -> "_core.Scenario":
    """The scenario as `pcsim run` would load it; raises InputError naming what is wrong.
    Options: profile, set, platform, files_host, hosts (pcsim.run's)."""
    return with_request(scenario, _core.load, **options)


def with_request(scenario: ScenarioLike, use: Callable[["_core.LoadRequest"], T], *, profile: Optional[str] = None,
                 set: Optional[Mapping[str, Any]] = None, platform: Union[None, str, "os.PathLike[str]"] = None,
                 files_host: Optional[str] = None, hosts: Optional[Iterable[str]] = None) -> T:
    """`use` applied to the request that loads the scenario with these options (a dict's
    instance is in a file only while `use` runs)."""
    request = _core.LoadRequest()
    request.overrides = _overrides(set)
    request.profile = profile or ""
    request.platform = os.fspath(platform) if platform is not None else ""
    request.files_host = files_host or ""
    request.hosts = list(hosts) if hosts is not None else []
    if scenario is None:
        request.kind = "default"
        return use(request)
    if isinstance(scenario, Mapping):
        return _with_instance(scenario, request, use)
    if isinstance(scenario, os.PathLike) or (isinstance(scenario, str) and not looks_like_toml(scenario)):
        path = os.fspath(scenario)
        request.kind = "workflow" if path.endswith(".json") else "file"
        request.source = path
        return use(request)
    if isinstance(scenario, str):
        request.kind = "text"
        request.source = scenario
        return use(request)
    raise InputError(f"scenario: a path, TOML text or a WfCommons instance (dict), not {type(scenario).__name__}")


def _with_instance(instance: Mapping[str, Any], request: "_core.LoadRequest", use: Callable[["_core.LoadRequest"], T]) -> T:
    # The C++ reader reads an instance from a file: the dict is handed over in one, and
    # messages and outputs name the instance instead of that file.
    name = f"<instance {instance.get('name')}>" if isinstance(instance.get("name"), str) else "<instance>"
    with tempfile.TemporaryDirectory(prefix="pcsim-instance-") as folder:
        path = os.path.join(folder, "instance.json")
        with open(path, "w", encoding="utf-8") as f:
            json.dump(instance, f, ensure_ascii=False)
        request.kind = "workflow"
        request.source = path
        request.name = name
        try:
            return use(request)
        except InputError as e:
            raise InputError(str(e).replace(path, name), name if e.file == path else e.file, e.line, e.key) from None
