#pragma once
// What the planner's sampled controls do: edges of hold_s from each start state, driven with
// the vehicle's sample_control(q, hold_s, rng) at the planner's integration step, and the
// share of their end states that each predicate holds for. Every control and every end state
// must be within the model's limits.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <initializer_list>

#include "grip/common/random.hpp"

namespace grip::testing {

template <typename V, typename... Predicates>
std::array<double, sizeof...(Predicates)> share_of_edge_ends(
    const V& vehicle, std::initializer_list<typename V::State> starts, double hold_s,
    Predicates... holds) {
  constexpr double kDt = 0.05;
  constexpr int kEdgesPerStart = 2'000;
  const auto steps = static_cast<int>(std::lround(hold_s / kDt));
  const double weight = 1.0 / (static_cast<double>(starts.size()) * kEdgesPerStart);
  std::array<double, sizeof...(Predicates)> shares{};
  Random rng(5);
  for (const auto& from : starts) {
    for (int i = 0; i < kEdgesPerStart; ++i) {
      const auto u = vehicle.sample_control(from, hold_s, rng);
      EXPECT_TRUE(vehicle.validate_control(u));
      auto q = from;
      for (int k = 0; k < steps; ++k) q = vehicle.step(q, u, kDt);
      EXPECT_TRUE(vehicle.validate_state(q));
      std::size_t p = 0;
      ((shares[p++] += holds(q) ? weight : 0.0), ...);
    }
  }
  return shares;
}

}  // namespace grip::testing
