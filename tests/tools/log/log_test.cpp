// The command's log lines: an ISO-8601 UTC timestamp with milliseconds, the level, the source,
// the text; lines below the threshold are dropped; unknown levels are refused.

#include "grip/tools/log.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

namespace {

using grip::tools::format_log_line;
using grip::tools::Logger;
using grip::tools::LogLevel;

constexpr std::int64_t kDecember4th14h = 1'796'392'800'123'456'789;  // 2026-12-04T14:00:00.123Z

TEST(LogLine, StartsWithTheUtcTimeToTheMillisecondThenLevelAndSource) {
  EXPECT_EQ(format_log_line(kDecember4th14h, LogLevel::kWarning, "grip planner", "map gap"),
            "2026-12-04T14:00:00.123Z warning grip planner: map gap\n");
  EXPECT_EQ(format_log_line(0, LogLevel::kError, "grip", "x"),
            "1970-01-01T00:00:00.000Z error grip: x\n");
  EXPECT_EQ(format_log_line(999'999'999, LogLevel::kInfo, "grip", "x"),
            "1970-01-01T00:00:00.999Z info grip: x\n");
}

TEST(LogLevel, NamesParseBackAndAnythingElseIsRefused) {
  for (const LogLevel l : {LogLevel::kError, LogLevel::kWarning, LogLevel::kInfo}) {
    const auto parsed = grip::tools::parse_log_level(grip::tools::log_level_name(l));
    ASSERT_TRUE(parsed.ok());
    EXPECT_EQ(*parsed, l);
  }
  const auto refused = grip::tools::parse_log_level("debug");
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find("debug"), std::string::npos);
}

// What a logger wrote to its stream.
std::string written_at(LogLevel threshold) {
  std::FILE* out = std::tmpfile();
  const Logger log("grip planner", threshold, out);
  log.error("e");
  log.warning("w");
  log.info("i");
  std::rewind(out);
  std::string text;
  for (int c = std::fgetc(out); c != EOF; c = std::fgetc(out)) text += static_cast<char>(c);
  std::fclose(out);
  return text;
}

TEST(Logger, WritesOnlyLinesAtOrAboveItsThreshold) {
  const std::string error_only = written_at(LogLevel::kError);
  EXPECT_NE(error_only.find("Z error grip planner: e\n"), std::string::npos) << error_only;
  EXPECT_EQ(error_only.find("warning"), std::string::npos) << error_only;
  EXPECT_EQ(error_only.find("info"), std::string::npos) << error_only;
  const std::string warnings = written_at(LogLevel::kWarning);
  EXPECT_NE(warnings.find("Z warning grip planner: w\n"), std::string::npos) << warnings;
  EXPECT_EQ(warnings.find("info"), std::string::npos) << warnings;
  const std::string all = written_at(LogLevel::kInfo);
  EXPECT_NE(all.find("Z info grip planner: i\n"), std::string::npos) << all;
}

}  // namespace
