#pragma once
// The output of `grip echo`: one JSON document per line.

#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace grip::testing {

inline std::vector<nlohmann::json> json_lines(const std::string& text) {
  std::vector<nlohmann::json> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(nlohmann::json::parse(line));
  return lines;
}

}  // namespace grip::testing
