#pragma once
// The 8 m x 8 m room (1 m MovingAI cells) with a pillar and a wall that the exploration
// command tests explore around.

#include <gtest/gtest.h>

#include <fstream>
#include <string>

namespace grip::testing {

// Writes it to the test temp directory under `name`; its path.
inline std::string write_small_room_map(const std::string& name) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream out(path);
  out << "type octile\nheight 10\nwidth 10\nmap\n"
      << "@@@@@@@@@@\n@........@\n@........@\n@...@@...@\n@...@@...@\n"
      << "@........@\n@.@@@@@..@\n@........@\n@........@\n@@@@@@@@@@\n";
  return path;
}

}  // namespace grip::testing
