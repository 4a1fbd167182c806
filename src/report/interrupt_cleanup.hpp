#pragma once
// What an interrupted pcsim removes before it exits. SIGINT, SIGTERM and SIGHUP while pcsim
// writes an output would otherwise leave its temporary file or staging folder behind; the
// handler removes every one registered (pcsim's own files by name: unlink and rmdir, which a
// signal handler may call) and exits with 128 + the signal's number (130, 143, 129).
// Registration is cheap and needs no handler: a program embedding the library registers
// nothing unless it installs the handler (pcsim does, in main).

#include <csignal>
#include <string>

namespace pagecache::report {

/// Installs the handler for SIGINT, SIGTERM and SIGHUP (once; later calls do nothing).
void install_interrupt_cleanup();

/// SIGINT, SIGTERM and SIGHUP held back (in this thread) while it lives, then delivered: for
/// the steps between making a path and registering it, or unregistering it and renaming it,
/// where an interruption would otherwise leave it behind or remove what was put in place.
class SignalsHeld {
 public:
  SignalsHeld();
  ~SignalsHeld();
  SignalsHeld(const SignalsHeld&) = delete;
  SignalsHeld& operator=(const SignalsHeld&) = delete;

 private:
  sigset_t previous_{};
};

/// A path removed if the process is interrupted while this object lives: a temporary file, or
/// a staging folder (its pcsim files, then the folder). At most 64 at once; beyond, the path is
/// not registered (an interruption may then leave it, as before).
class RemovedOnInterrupt {
 public:
  enum class Kind { File, StagingFolder };
  RemovedOnInterrupt(const std::string& path, Kind kind);
  ~RemovedOnInterrupt();
  RemovedOnInterrupt(const RemovedOnInterrupt&) = delete;
  RemovedOnInterrupt& operator=(const RemovedOnInterrupt&) = delete;

 private:
  int slot_ = -1;
};

}  // namespace pagecache::report
