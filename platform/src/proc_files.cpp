#include "grip/platform/proc_files.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <array>
#include <charconv>

#include "grip/platform/os_call.hpp"

namespace grip::platform::detail {

Result<std::string> read_small_file(const std::string& path) {
  const auto opened = os_call("open", [&] { return ::open(path.c_str(), O_RDONLY | O_CLOEXEC); });
  if (!opened.ok()) return Error{ErrorCode::kIo, path + ": " + opened.describe()};
  constexpr std::size_t kMaxBytes = std::size_t{64} * 1024;
  std::string text;
  std::array<char, 4096> chunk{};
  while (text.size() < kMaxBytes) {
    const auto got =
        os_call("read", [&] { return ::read(opened.value, chunk.data(), chunk.size()); });
    if (!got.ok() && got.error == EINTR) continue;
    if (!got.ok()) {
      (void)os_call("close", [&] { return ::close(opened.value); });
      return Error{ErrorCode::kIo, path + ": " + got.describe()};
    }
    if (got.value == 0) break;
    text.append(chunk.data(), static_cast<std::size_t>(got.value));
  }
  (void)os_call("close", [&] { return ::close(opened.value); });
  return text;
}

std::optional<std::int64_t> read_integer_file(const std::string& path) {
  const Result<std::string> text = read_small_file(path);
  if (!text.ok()) return std::nullopt;
  std::int64_t value = 0;
  const char* first = text->data();
  const char* last = first + text->size();
  const auto [end, ec] = std::from_chars(first, last, value);
  if (ec != std::errc{} || end == first) return std::nullopt;
  return value;
}

namespace {
bool parse_int(std::string_view text, int& out) {
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
  return ec == std::errc{} && end == text.data() + text.size() && out >= 0;
}
}  // namespace

Result<std::vector<int>> parse_cpu_list(std::string_view text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.remove_suffix(1);
  std::vector<int> cpus;
  while (!text.empty()) {
    const std::size_t comma = text.find(',');
    const std::string_view range = text.substr(0, comma);
    text = comma == std::string_view::npos ? std::string_view() : text.substr(comma + 1);
    const std::size_t dash = range.find('-');
    int first = 0;
    int last = 0;
    const bool parsed =
        dash == std::string_view::npos
            ? parse_int(range, first) && parse_int(range, last)
            : parse_int(range.substr(0, dash), first) && parse_int(range.substr(dash + 1), last);
    if (!parsed || last < first) {
      return Error{ErrorCode::kParse, "bad CPU list entry '" + std::string(range) + "'"};
    }
    for (int cpu = first; cpu <= last; ++cpu) cpus.push_back(cpu);
  }
  return cpus;
}

std::string format_cpu_list(const std::vector<int>& cpus) {
  std::string text;
  for (std::size_t i = 0; i < cpus.size();) {
    std::size_t j = i;
    while (j + 1 < cpus.size() && cpus[j + 1] == cpus[j] + 1) ++j;
    if (!text.empty()) text += ',';
    text += std::to_string(cpus[i]);
    if (j > i) text += '-' + std::to_string(cpus[j]);
    i = j + 1;
  }
  return text.empty() ? std::string("none") : text;
}

std::optional<std::string_view> status_field(std::string_view status, std::string_view key) {
  std::size_t line_start = 0;
  while (line_start < status.size()) {
    std::size_t line_end = status.find('\n', line_start);
    if (line_end == std::string_view::npos) line_end = status.size();
    const std::string_view line = status.substr(line_start, line_end - line_start);
    if (line.size() > key.size() && line.substr(0, key.size()) == key && line[key.size()] == ':') {
      std::string_view value = line.substr(key.size() + 1);
      while (!value.empty() && (value.front() == ' ' || value.front() == '\t')) {
        value.remove_prefix(1);
      }
      return value;
    }
    line_start = line_end + 1;
  }
  return std::nullopt;
}

}  // namespace grip::platform::detail
