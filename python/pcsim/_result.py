"""Result: a finished run, its tables as pandas DataFrames."""

from __future__ import annotations

import html
import json
import os
from typing import Any, Dict, List, Optional, Union

import numpy as np
import pandas as pd

from . import _core


def _names(codes: np.ndarray, categories: List[str]) -> Union[pd.Categorical, np.ndarray]:
    # Categorical when the names are distinct (they are, but for files of one name on two hosts).
    if len(set(categories)) == len(categories):
        return pd.Categorical.from_codes(codes, categories=categories)
    return np.asarray(categories, dtype=object)[codes]


def _frame(columns: Dict[str, Any], order: List[str]) -> pd.DataFrame:
    data = {}
    for name in order:
        if f"{name}_codes" in columns:
            data[name] = _names(columns[f"{name}_codes"], columns[f"{name}_categories"])
        else:
            data[name] = columns[name]
    return pd.DataFrame(data, copy=False)


TIMELINE_COLUMNS = ["app", "task", "host", "phase", "start_s", "end_s", "bytes", "cache_bytes", "disk_bytes"]
MEMORY_COLUMNS = ["host", "time_s", "total_bytes", "free_bytes", "anonymous_bytes", "cached_bytes", "dirty_bytes",
                  "writeback_bytes", "active_bytes", "inactive_bytes"]
CACHE_COLUMNS = ["app", "task", "phase", "file", "cached_bytes"]


class Result:
    """A finished run. Its tables hold what `pcsim run` writes in timeline.csv, memory.csv and
    cache.csv, with the same columns (names as categoricals; times in seconds, not rounded to
    the microsecond as the CSV files are); `summary` is summary.json's content."""

    def __init__(self, run: "_core.Run"):
        self._run = run
        self._summary: Optional[Dict[str, Any]] = None
        self._timeline: Optional[pd.DataFrame] = None
        self._memory: Optional[pd.DataFrame] = None
        self._cache: Optional[pd.DataFrame] = None
        self._report: Optional[str] = None

    @property
    def summary(self) -> Dict[str, Any]:
        """summary.json's content: the scenario, the makespan, the bytes read from disk and
        cache, written back and evicted, the simulator's events."""
        if self._summary is None:
            self._summary = json.loads(self._run.summary_json())
        return self._summary

    @property
    def timeline(self) -> pd.DataFrame:
        """A row per phase (read, compute, write) of every task: timeline.csv's columns."""
        if self._timeline is None:
            self._timeline = _frame(self._run.timeline_columns(), TIMELINE_COLUMNS)
        return self._timeline

    @property
    def memory(self) -> pd.DataFrame:
        """Each host's memory over time: memory.csv's columns."""
        if self._memory is None:
            self._memory = _frame(self._run.memory_columns(), MEMORY_COLUMNS)
        return self._memory

    @property
    def cache(self) -> pd.DataFrame:
        """Each file's cached bytes after every I/O phase: cache.csv's columns (no rows if
        the cache contents were not recorded: cache_not_recorded says why)."""
        if self._cache is None:
            self._cache = _frame(self._run.cache_columns(), CACHE_COLUMNS)
        return self._cache

    @property
    def cache_not_recorded(self) -> str:
        """Empty if `cache` holds the cache contents; else why they were not recorded."""
        return self._run.cache_not_recorded()

    @property
    def warnings(self) -> List[str]:
        """What loading the scenario warned of (`pcsim run` prints them)."""
        return self._run.warnings()

    def write(self, folder: Union[str, "os.PathLike[str]"]) -> List[str]:
        """Writes the files `pcsim run --out FOLDER` writes, through the same writers and the
        same folder rules (only a folder pcsim made, or an empty one, is replaced). Once per
        Result. Returns warnings for a person."""
        return self._run.write(os.fspath(folder))

    def report_html(self) -> str:
        """report.html's text."""
        if self._report is None:
            self._report = self._run.report_html()
        return self._report

    def _repr_html_(self) -> str:
        # The report is a whole page: in a frame of its own, its style stays its own.
        return ('<iframe style="width: 100%; height: 900px; border: 0" srcdoc="' + html.escape(self.report_html(), quote=True)
                + '"></iframe>')

    def __repr__(self) -> str:
        s = self.summary
        return f"<pcsim.Result {s.get('scenario', '')!r}: makespan {s.get('makespan_s', float('nan')):.2f} s, {len(self.timeline)} phases>"

    def __str__(self) -> str:
        return self._run.readable_summary()
