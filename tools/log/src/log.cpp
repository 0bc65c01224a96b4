#include "grip/tools/log.hpp"

#include <array>
#include <chrono>
#include <ctime>

#include "grip/common/enum_names.hpp"

namespace grip::tools {

namespace {
constexpr std::array<NamedValue<LogLevel>, 3> kLogLevelNames{{
    {LogLevel::kError, "error"},
    {LogLevel::kWarning, "warning"},
    {LogLevel::kInfo, "info"},
}};
}  // namespace

std::string_view log_level_name(LogLevel level) noexcept { return name_in(kLogLevelNames, level); }

Result<LogLevel> parse_log_level(std::string_view name) {
  return value_named(kLogLevelNames, name, "log level");
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
