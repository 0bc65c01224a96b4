#pragma once
// Reading the kernel's small text files (/proc, /sys): why a call was refused, what the machine
// has. Start-up only: everything here allocates.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "grip/common/result.hpp"

namespace grip::platform::detail {

// The whole file (at most 64 KiB); an error names the path and the errno.
Result<std::string> read_small_file(const std::string& path);

// The file's content as one integer ("950000\n"); nullopt when absent or not a number.
std::optional<std::int64_t> read_integer_file(const std::string& path);

// The kernel's CPU list format, "0-3,8,10-11\n", as CPU numbers in ascending order.
Result<std::vector<int>> parse_cpu_list(std::string_view text);

// The inverse of parse_cpu_list for sorted input: {0, 1, 2, 5} -> "0-2,5".
std::string format_cpu_list(const std::vector<int>& cpus);

// The value of a "Key:\tvalue" line in a /proc/<pid>/status file, trimmed; nullopt if absent.
std::optional<std::string_view> status_field(std::string_view status, std::string_view key);

}  // namespace grip::platform::detail
