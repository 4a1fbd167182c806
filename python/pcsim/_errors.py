"""pcsim's exceptions: what the C++ library throws, as Python raises it."""

from __future__ import annotations

import re
from typing import Optional


class Error(Exception):
    """Base of every exception pcsim raises."""


class InputError(Error, ValueError):
    """Invalid input: a malformed scenario, a negative size, an unknown key (the command line's
    exit status 2). The message names the file, line and key at fault; `file`, `line` and `key`
    give them apart where the reader knew them (else None)."""

    def __init__(self, message: str, file: Optional[str] = None, line: Optional[int] = None, key: Optional[str] = None):
        super().__init__(message)
        self.file = file
        self.line = line
        self.key = key


class SimulationError(Error, RuntimeError):
    """The simulation cannot continue, e.g. a task needs more memory than its host has (the
    command line's exit status 1). `time` is the simulated time in seconds the message states
    (None if it states none)."""

    def __init__(self, message: str):
        super().__init__(message)
        found = re.search(r"t = ([0-9]+(?:\.[0-9]+)?) s", message)
        self.time: Optional[float] = float(found.group(1)) if found else None


class InvariantError(Error, RuntimeError):
    """A model invariant broke: always a bug in pcsim, never the user's fault (exit status 3)."""
