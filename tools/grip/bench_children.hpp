#pragma once
// What the benchmarks that run `grip` child processes share: the executable to start and the
// folder their reports go to, and reading back a child's JSON report.

#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <system_error>

#include "child.hpp"

namespace grip::tools {

// Finds this executable (into `self`) and creates `out_dir`. 0, or the exit status after
// saying on stderr what failed: 1 without an executable, 2 without the folder.
inline int prepare_bench_children(const char* command, const std::string& out_dir,
                                  std::string& self) {
  auto found = self_executable();
  if (!found) {
    std::cerr << command << ": " << found.error().message << "\n";
    return 1;
  }
  self = *found;
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (ec) {
    std::cerr << command << ": cannot create " << out_dir << ": " << ec.message() << "\n";
    return 2;
  }
  return 0;
}

// A child's JSON report; null when it left none, or not a whole one.
inline nlohmann::json read_child_report(const std::string& path) {
  try {
    std::ifstream in(path);
    if (in) return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception&) {
  }
  return nullptr;
}

}  // namespace grip::tools
