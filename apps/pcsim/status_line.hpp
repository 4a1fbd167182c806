#pragma once
// StatusLine: one line of stderr rewritten in place, for progress: only on a terminal, and at
// most five times a second (after `quiet_start`, so that short commands print nothing).

#include <fmt/format.h>

#include <chrono>
#include <optional>
#include <string>
#include <unistd.h>

namespace pcsim {

class StatusLine {
 public:
  explicit StatusLine(bool enabled, std::chrono::milliseconds quiet_start = std::chrono::milliseconds(0))
      : enabled_(enabled && ::isatty(STDERR_FILENO) == 1), quiet_start_(quiet_start) {}

  /// The seconds since it was made if a line is due now, else nothing; `force` (a last line)
  /// skips the rate limit.
  std::optional<double> due(bool force = false) {
    if (!enabled_) return std::nullopt;
    const auto now = std::chrono::steady_clock::now();
    if (!force && (now - start_ < quiet_start_ || now - last_ < std::chrono::milliseconds(200))) return std::nullopt;
    last_ = now;
    return std::chrono::duration<double>(now - start_).count();
  }
  void show(const std::string& text) {
    fmt::print(stderr, "\r{}   ", text);
    shown_ = true;
  }
  void clear() {
    if (shown_) fmt::print(stderr, "\r{:60}\r", "");
  }

 private:
  bool enabled_;
  std::chrono::milliseconds quiet_start_;
  bool shown_ = false;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::chrono::steady_clock::time_point last_{};
};

}  // namespace pcsim
