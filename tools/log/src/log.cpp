#include "grip/tools/log.hpp"

#include <chrono>
#include <ctime>

namespace grip::tools {

std::string_view log_level_name(LogLevel level) noexcept {
  switch (level) {
    case LogLevel::kError:
      return "error";
    case LogLevel::kWarning:
      return "warning";
    case LogLevel::kInfo:
      return "info";
  }
  return "info";
}

Result<LogLevel> parse_log_level(std::string_view name) {
  for (const LogLevel level : {LogLevel::kError, LogLevel::kWarning, LogLevel::kInfo}) {
    if (name == log_level_name(level)) return level;
  }
  return invalid_argument("log level must be error, warning or info (got '" + std::string(name) +
                          "')");
}

std::string format_log_line(std::int64_t unix_ns, LogLevel level, std::string_view source,
                            std::string_view text) {
  const std::int64_t ms = unix_ns / 1'000'000;
  const auto seconds = static_cast<std::time_t>(ms / 1000);
  const auto ms_of_second = static_cast<int>(ms % 1000);
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char stamp[40];
  const std::size_t n = std::strftime(stamp, sizeof stamp, "%Y-%m-%dT%H:%M:%S", &utc);
  std::snprintf(stamp + n, sizeof stamp - n, ".%03dZ", ms_of_second);
  std::string line = stamp;
  line += ' ';
  line += log_level_name(level);
  line += ' ';
  line += source;
  line += ": ";
  line += text;
  line += '\n';
  return line;
}

void Logger::log(LogLevel level, std::string_view text) const {
  if (!enabled(level)) return;
  const std::int64_t now = std::chrono::duration_cast<std::chrono::nanoseconds>(
                               std::chrono::system_clock::now().time_since_epoch())
                               .count();
  const std::string line = format_log_line(now, level, source_, text);
  std::fwrite(line.data(), 1, line.size(), out_);
  std::fflush(out_);
}

}  // namespace grip::tools
