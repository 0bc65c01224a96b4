#pragma once
// The `grip` command's log lines, for a terminal and for a service's journal alike: each line
// says when (ISO-8601, UTC, milliseconds), how bad and who, then what:
//
//   2026-12-04T14:00:00.123Z warning grip planner: rejected goal: out of map (x_m)
//
// Never on the planning path: formatting allocates.

#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

#include "grip/common/result.hpp"

namespace grip::tools {

enum class LogLevel { kError, kWarning, kInfo };

// "error", "warning" or "info".
std::string_view log_level_name(LogLevel level) noexcept;
// The inverse of log_level_name; an error naming the accepted levels otherwise.
Result<LogLevel> parse_log_level(std::string_view name);

// "2026-12-04T14:00:00.123Z warning grip planner: text\n"; unix_ns (>= 0) is the time since
// the epoch.
std::string format_log_line(std::int64_t unix_ns, LogLevel level, std::string_view source,
                            std::string_view text);

class Logger {
 public:
  // Lines at `threshold` or more severe go to `out` (not owned).
  Logger(std::string source, LogLevel threshold, std::FILE* out = stderr)
      : source_(std::move(source)), threshold_(threshold), out_(out) {}

  bool enabled(LogLevel level) const noexcept { return level <= threshold_; }
  // Any thread: each line is one write, so lines from different threads do not interleave.
  void log(LogLevel level, std::string_view text) const;
  void error(std::string_view text) const { log(LogLevel::kError, text); }
  void warning(std::string_view text) const { log(LogLevel::kWarning, text); }
  void info(std::string_view text) const { log(LogLevel::kInfo, text); }

 private:
  std::string source_;
  LogLevel threshold_;
  std::FILE* out_;
};

}  // namespace grip::tools
