#pragma once
// Errors raised by the pcsim library.
//
// Everything the library throws derives from pagecache::Error. The library never prints and
// never exits; the `pcsim` command line maps the three kinds below to exit codes:
// ConfigError -> 2 (the input is wrong), SimulationError -> 1 (the model cannot proceed),
// InvariantError -> 3 (a bug in pcsim: a model invariant broke).

#include <stdexcept>
#include <string>

namespace pagecache {

/// Base of every exception thrown by the library.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Invalid input: a malformed scenario, a negative size, an unknown key. The message names
/// the file, line or key at fault.
class ConfigError : public Error {
 public:
  using Error::Error;
};

/// The simulation cannot continue (e.g. a task needs more memory than the host has). The
/// message states the simulated time and the reason.
class SimulationError : public Error {
 public:
  using Error::Error;
};

/// A model invariant was violated. Always a bug in pcsim, never the user's fault.
class InvariantError : public Error {
 public:
  using Error::Error;
};

}  // namespace pagecache
