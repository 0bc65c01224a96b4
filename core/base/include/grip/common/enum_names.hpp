#pragma once
// Names of enumerators as the command line and the reports spell them, from one table per
// enum, and the lookup that refuses an unknown name by listing the valid ones.

#include <array>
#include <string>
#include <string_view>

#include "grip/common/result.hpp"

namespace grip {

template <typename E>
struct NamedValue {
  E value;
  std::string_view name;
};

template <typename E, std::size_t N>
constexpr std::string_view name_in(const std::array<NamedValue<E>, N>& table, E value) noexcept {
  for (const auto& entry : table) {
    if (entry.value == value) return entry.name;
  }
  return "unknown";
}

// `what` names the kind of thing in the error: "unknown robot 'tank' (expected one of: ...)".
template <typename E, std::size_t N>
Result<E> value_named(const std::array<NamedValue<E>, N>& table, std::string_view name,
                      std::string_view what) {
  std::string valid;
  for (const auto& entry : table) {
    if (entry.name == name) return entry.value;
    valid += valid.empty() ? "" : ", ";
    valid += entry.name;
  }
  return invalid_argument("unknown " + std::string(what) + " '" + std::string(name) +
                          "' (expected one of: " + valid + ")");
}

}  // namespace grip
