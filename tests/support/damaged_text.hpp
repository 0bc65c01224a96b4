#pragma once
// Damaged copies of a good file for the parsers' fuzz tests: each parser must parse a damaged
// file or refuse it with a message, never crash, hang or read out of bounds (ASan runs them).

#include <cstddef>
#include <string>

#include "grip/common/random.hpp"

namespace grip::testing {

// One to three random edits: flip a byte, delete a span, duplicate a span, or cut the tail.
inline std::string damaged(const std::string& good, Random& rng) {
  std::string s = good;
  const auto pick = [&](std::size_t n) {
    return static_cast<std::size_t>(rng.uniform(0.0, static_cast<double>(n)));
  };
  const int edits = 1 + static_cast<int>(pick(3));
  for (int e = 0; e < edits && !s.empty(); ++e) {
    const std::size_t at = pick(s.size());
    switch (pick(4)) {
      case 0:
        s[at] = static_cast<char>(pick(256));
        break;
      case 1:
        s.erase(at, 1 + pick(8));
        break;
      case 2:
        s.insert(at, s.substr(at, 1 + pick(8)));
        break;
      default:
        s.resize(at);
        break;
    }
  }
  return s;
}

}  // namespace grip::testing
