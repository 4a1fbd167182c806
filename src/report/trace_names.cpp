// The names of a trace's phase kinds and flush causes, as the outputs write them.

#include <pagecache/trace.hpp>

namespace pagecache {

std::string_view to_string(PhaseKind kind) noexcept {
  switch (kind) {
    case PhaseKind::Read: return "read";
    case PhaseKind::Compute: return "compute";
    case PhaseKind::Write: return "write";
  }
  return "?";
}

std::string_view to_string(FlushCause cause) noexcept {
  switch (cause) {
    case FlushCause::DirtyLimit: return "dirty_limit";
    case FlushCause::Reclaim: return "reclaim";
    case FlushCause::Background: return "background";
    case FlushCause::Expiry: return "expiry";
    case FlushCause::Fsync: return "fsync";
  }
  return "?";
}

}  // namespace pagecache
