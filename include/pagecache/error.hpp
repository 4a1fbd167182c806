#pragma once
// Errors raised by the pcsim library.
//
// Everything the library throws derives from pagecache::Error. The library never prints and
// never exits; the `pcsim` command line maps the three kinds below to exit codes:
// ConfigError -> 2 (the input is wrong), SimulationError -> 1 (the model cannot proceed),
// InvariantError -> 3 (a bug in pcsim: a model invariant broke).

#include <memory>
#include <stdexcept>
#include <string>

namespace pagecache {

/// Base of every exception thrown by the library.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Where in its input a ConfigError was found, as far as the reader knew: the file (empty if
/// none, e.g. a command-line option), its line (1-based; 0 if none) and the key's full dotted
/// path (empty if none). The message says the same for a person.
struct InputPlace {
  std::string file;
  int line = 0;
  std::string key;
};

/// Invalid input: a malformed scenario, a negative size, an unknown key. The message names
/// the file, line or key at fault; place() gives them apart where the reader knew them.
class ConfigError : public Error {
 public:
  using Error::Error;
  ConfigError(const std::string& message, InputPlace place)
      : Error(message), place_(std::make_shared<const InputPlace>(std::move(place))) {}
  /// The file, line and key at fault (all empty when the thrower did not say).
  const InputPlace& place() const noexcept {
    static const InputPlace kNowhere;
    return place_ ? *place_ : kNowhere;
  }

 private:
  std::shared_ptr<const InputPlace> place_;  // shared: copying an exception must not throw
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
